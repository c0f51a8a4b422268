// The C interface between core/util/image_io.cpp and the OpenImageIO codec module
// (core/util/image_codec_oiio.cpp, built as libvplgi_image_oiio.so).
//
// Why a module: OpenImageIO pulls in about 260 shared libraries (its format plug-ins: OpenCV, GDAL,
// DCMTK, FFmpeg, ...), and the dynamic loader's relocations for them took 0.4 s at every start of
// vplgi and of the test binaries (0.8 s under ASan), before main(): more than a small render itself.
// image_io.cpp opens the module with dlopen on the first image it reads or writes, so a command that
// fails on its arguments, lists parameters or renders only statistics never pays for it. The
// sanitizer builds link it in instead (core/CMakeLists.txt says why).
//
// Plain C types only, so nothing C++ (exceptions, allocators, std::string) crosses the boundary: the
// module catches everything and reports one line of text.
#pragma once

#include <stddef.h>

extern "C" {

// Receives encoded bytes (encode may call it several times, in order).
typedef void (*VplgiImageSink)(void* context, const void* bytes, size_t size);
// Returns the buffer decode fills: width * height * 4 values of the requested type, or null to fail.
typedef void* (*VplgiImageAllocate)(void* context, int width, int height);

struct VplgiImageCodec {
    int version; // kVplgiImageCodecVersion of the module's build
    // Encodes width x height RGBA pixels (rows top to bottom; float32 linear when floatPixels, else
    // uint8) in the format that `fileName`'s extension names (zip-compressed EXR for floats), into
    // `sink`. Returns 1, or 0 with a message in error[errorSize].
    int (*encode)(const char* fileName, int width, int height, int floatPixels, const void* pixels, VplgiImageSink sink,
                  void* sinkContext, char* error, int errorSize);
    // Decodes the image file `path` to RGBA of the requested type (missing channels: grey from the
    // first, opaque alpha). Returns 1, or 0 with a message in error[errorSize].
    int (*decode)(const char* path, int floatPixels, VplgiImageAllocate allocate, void* allocateContext, char* error,
                  int errorSize);
};

// The module's one exported symbol.
const VplgiImageCodec* vplgi_image_codec(void);
typedef const VplgiImageCodec* (*VplgiImageCodecEntry)(void);

} // extern "C"

// Bumped when the struct above changes: a stale module next to a new binary is refused by name.
constexpr int kVplgiImageCodecVersion = 1;
