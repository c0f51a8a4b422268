// Turning a `--scene` argument into a core::Scene: a built-in generator name, a scene file
// (scenes/<name>.json, see README "Scene format"), or a .gltf/.glb path.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/scene/scene.h"

namespace vplgi {

// What a scene file adds beyond geometry: parameter overrides ("smcir.vplCount" -> "4096") and the
// technique it selects by default. Parameters set on the command line win over these.
struct SceneDescription {
    Scene scene;
    std::vector<std::pair<std::string, std::string>> settings;
    std::string technique; // empty = the CLI default
};

// spec: a built-in name ("cornell"), a .json scene file, or a .gltf/.glb file. Throws Error.
SceneDescription loadSceneSpec(const std::string& spec);

// glTF 2.0 (tinygltf): nodes, meshes, materials + textures, KHR_lights_punctual,
// KHR_materials_emissive_strength, KHR_materials_specular, cameras. Throws Error naming the file.
// External buffers and images are read only from the file's folder (or below it).
Scene loadGltf(const std::string& path);

// The same from bytes already in memory (the fuzz harness, tests/fuzz): `path` names the file in
// messages, its extension (.gltf or .glb) says which form the bytes are in, and its folder is the
// only place external buffers and images are read from.
Scene loadGltfFromMemory(const std::string& bytes, const std::string& path);

// A scene file (JSON). Relative paths inside it are relative to the file.
SceneDescription loadSceneFile(const std::string& path);

// A scene file's "source" ("builtin:<name>" or "gltf:<path>", relative to the scene file at
// sceneFilePath) as a Scene. Throws Error naming the scene file.
Scene loadSceneSource(const std::string& source, const std::string& sceneFilePath);

// What turns a "source" into a Scene: loadSceneSource unless given (the fuzz harness caches it, since
// generating a built-in scene costs more than reading the scene file around it).
using SceneSourceLoader = std::function<Scene(const std::string& source, const std::string& sceneFilePath)>;

// The same from text already in memory: `path` names the file in messages and its folder is where
// relative paths inside it start.
SceneDescription loadSceneFileFromText(const std::string& text, const std::string& path,
                                       const SceneSourceLoader& sourceLoader = nullptr);

} // namespace vplgi
