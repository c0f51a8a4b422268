#include "camera_path.h"

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/scene/builtin_scenes.h"
#include "core/util/error.h"

namespace vplgi {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

void CameraPathRecorder::start()
{
    mRecording = true;
    mKeys.clear();
}

void CameraPathRecorder::add(float time, const Camera& camera)
{
    if (!mRecording) return;
    if (mKeys.empty()) mStartTime = time;
    const float t = time - mStartTime;
    if (!mKeys.empty() && !(t > mKeys.back().time)) return;
    Keyframe key;
    key.time = t;
    key.position = camera.position;
    key.target = camera.target;
    mKeys.push_back(key);
}

std::string CameraPathRecorder::sceneFileText(const std::string& sceneSpec, const std::string& cameraName) const
{
    require(mKeys.size() >= 2, "camera path: recorded " + std::to_string(mKeys.size()) +
                                   " key(s), a path needs at least two (record while the frames advance)");
    Json doc;
    const std::string ext = fs::path(sceneSpec).extension().string();
    if (isBuiltinScene(sceneSpec)) {
        doc["source"] = "builtin:" + sceneSpec;
    } else if (ext == ".json") {
        std::ifstream in(sceneSpec);
        require(in.good(), sceneSpec + ": cannot read");
        doc = Json::parse(in, nullptr, false);
        require(doc.is_object() && doc.contains("source") && doc["source"].is_string(), sceneSpec + ": not a scene file");
        // The copy lives elsewhere: a relative glTF source is made absolute (relative to the original).
        const std::string source = doc["source"].get<std::string>();
        if (source.rfind("gltf:", 0) == 0 && fs::path(source.substr(5)).is_relative())
            doc["source"] = "gltf:" + fs::absolute(fs::path(sceneSpec).parent_path() / source.substr(5)).string();
    } else {
        doc["source"] = "gltf:" + fs::absolute(sceneSpec).string();
    }
    Json keys = Json::array();
    for (const Keyframe& k : mKeys)
        keys.push_back({{"t", k.time},
                        {"position", {k.position.x, k.position.y, k.position.z}},
                        {"target", {k.target.x, k.target.y, k.target.z}}});
    Json animation = {{"name", "recorded"}, {"camera", cameraName}, {"keys", keys}};
    Json animations = Json::array();
    if (doc.contains("animations") && doc["animations"].is_array())
        for (const Json& a : doc["animations"])
            if (!(a.contains("name") && a["name"] == "recorded")) animations.push_back(a);
    animations.push_back(animation);
    doc["animations"] = animations;
    return doc.dump(2) + "\n";
}

void CameraPathRecorder::write(const std::string& path, const std::string& sceneSpec,
                               const std::string& cameraName) const
{
    const std::string text = sceneFileText(sceneSpec, cameraName); // before touching the file
    const std::string temporary = path + ".tmp";
    {
        std::ofstream out(temporary, std::ios::binary);
        require(out.good(), path + ": cannot write");
        out << text;
        out.close();
        require(out.good(), path + ": cannot write");
    }
    fs::rename(temporary, path);
}

} // namespace vplgi
