// libFuzzer harness: scene-file text (JSON, see README "Scene format") through
// vplgi::loadSceneFileFromText, as if the file lay in the sandbox folder (fuzz_sandbox.h).
// A "gltf:" source loads a glTF file; scene files may name any path (../shared/scenes/...), so the
// harness, not the reader, skips inputs whose source resolves outside the sandbox: the sandbox holds
// the glTF files the seeds use. Contract and findings as in fuzz_gltf.cpp.
// Sources are loaded once and then copied (a cache around vplgi::loadSceneSource): generating a
// built-in scene under ASan takes 10 ms to 1 s, reading the scene file around it well under 1 ms, and
// the reader, not the generators, is what this harness is for.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "core/scene/scene_loader.h"
#include "core/util/error.h"
#include "fuzz_sandbox.h"

namespace {

namespace fs = std::filesystem;

// False when the text's "source" names a glTF file outside the sandbox. Parsed as the reader parses
// it (ordered_json: the last of duplicate keys wins in both), so the two always agree on the source.
bool staysInSandbox(const std::string& text)
{
    const auto doc = nlohmann::ordered_json::parse(text, nullptr, false);
    if (!doc.is_object()) return true; // the reader refuses it before loading anything
    const auto source = doc.find("source");
    if (source == doc.end() || !source->is_string()) return true;
    const std::string value = source->get<std::string>();
    if (value.rfind("gltf:", 0) != 0) return true;
    std::error_code ec;
    const fs::path sandbox = vplgi::fuzz::sandboxDir();
    const fs::path file = fs::weakly_canonical(sandbox / value.substr(5), ec); // absolute paths replace sandbox
    if (ec) return false;
    const fs::path relative = file.lexically_relative(sandbox);
    return !relative.empty() && *relative.begin() != ".." && *relative.begin() != ".";
}

// Deterministic (the sandbox never changes), so a cached copy is what loading again would give.
// Only scenes that loaded are kept: a few built-in names and the sandbox's glTF files.
vplgi::Scene loadSourceOnce(const std::string& source, const std::string& sceneFilePath)
{
    static std::map<std::string, vplgi::Scene> cache;
    auto it = cache.find(source);
    if (it == cache.end()) it = cache.emplace(source, vplgi::loadSceneSource(source, sceneFilePath)).first;
    return it->second;
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
    vplgi::fuzz::sandboxDir();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const std::string text(reinterpret_cast<const char*>(data), size);
    if (!staysInSandbox(text)) return -1; // -1: libFuzzer keeps the input out of the corpus
    try {
        vplgi::SceneDescription description =
            vplgi::loadSceneFileFromText(text, vplgi::fuzz::sandboxDir() + "/input.json", loadSourceOnce);
        (void)description;
    } catch (const vplgi::Error&) {
        // Refused with a message: the expected outcome for most inputs.
    }
    return 0;
}
