// tinygltf's implementation compiled from Debian's header, with fuzzer coverage and sanitizers
// (the fuzz build only; everything else links Debian's libtinygltf). Debian builds its library with
// the header's defaults: system nlohmann/json and stb_image / stb_image_write from libstb, so the
// same defaults here give the same parser; stb's implementations are compiled here too, so the image
// decoders are instrumented as well.
#define TINYGLTF_IMPLEMENTATION
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <tiny_gltf.h>
