// libFuzzer harness: glTF bytes (a .glb when they start with the GLB magic "glTF", a .gltf otherwise)
// through vplgi::loadGltfFromMemory, as if the file lay in the sandbox folder (fuzz_sandbox.h).
// The loader's contract: it returns a valid Scene or throws vplgi::Error. Anything else (another
// exception, a crash, a sanitizer report, a leak, a hang, a huge allocation) is a finding.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "core/scene/scene_loader.h"
#include "core/util/error.h"
#include "fuzz_sandbox.h"

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    vplgi::fuzz::sandboxDir();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::string path = vplgi::fuzz::sandboxDir() + (binary ? "/input.glb" : "/input.gltf");
    try {
        vplgi::Scene scene = vplgi::loadGltfFromMemory(std::string(reinterpret_cast<const char*>(data), size), path);
        (void)scene;
    } catch (const vplgi::Error&) {
        // Refused with a message: the expected outcome for most inputs.
    }
    return 0;
}
