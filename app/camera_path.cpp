#include "camera_path.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/scene/builtin_scenes.h"
#include "core/util/error.h"
#include "report.h"

namespace vplgi {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

// Millimetre-ish precision is plenty for a camera path and keeps the file readable ("0.278", not
// "0.27799999713897705").
double rounded(float v)
{
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", static_cast<double>(v));
    return std::strtod(text, nullptr);
}

// dump(2) puts every array element on its own line; arrays of numbers go on one line, like the
// hand-written scene files.
std::string collapseNumberArrays(const std::string& text)
{
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] == '[') {
            const std::size_t close = text.find(']', i);
            const std::string inner = close == std::string::npos ? "" : text.substr(i + 1, close - i - 1);
            if (!inner.empty() && inner.find_first_not_of("0123456789.eE+-, \n") == std::string::npos) {
                std::string compact = "[";
                bool space = false;
                for (char c : inner) {
                    if (c == ' ' || c == '\n') {
                        space = true;
                        continue;
                    }
                    if (space && compact.size() > 1 && compact.back() == ',') compact += ' ';
                    space = false;
                    compact += c;
                }
                out += compact + "]";
                i = close;
                continue;
            }
        }
        out += text[i];
    }
    return out;
}

} // namespace

void CameraPathRecorder::start()
{
    mRecording = true;
    mKeys.clear();
}

void CameraPathRecorder::add(float time, const Camera& camera, float minStep)
{
    if (!mRecording) return;
    if (mKeys.empty()) mStartTime = time;
    const float t = time - mStartTime;
    if (!mKeys.empty() && !(t > mKeys.back().time && t - mKeys.back().time >= 0.999f * minStep)) return;
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
        require(doc.is_object() && doc.contains("source") && doc["source"].is_string(),
                sceneSpec + ": not a scene file");
        // The copy lives elsewhere: a relative glTF source is made absolute (relative to the original).
        const std::string source = doc["source"].get<std::string>();
        if (source.rfind("gltf:", 0) == 0 && fs::path(source.substr(5)).is_relative())
            doc["source"] = "gltf:" + fs::absolute(fs::path(sceneSpec).parent_path() / source.substr(5)).string();
    } else {
        doc["source"] = "gltf:" + fs::absolute(sceneSpec).string();
    }
    Json keys = Json::array();
    for (const Keyframe& k : mKeys)
        keys.push_back({{"t", rounded(k.time)},
                        {"position", {rounded(k.position.x), rounded(k.position.y), rounded(k.position.z)}},
                        {"target", {rounded(k.target.x), rounded(k.target.y), rounded(k.target.z)}}});
    Json animation = {{"name", "recorded"}, {"camera", cameraName}, {"keys", keys}};
    Json animations = Json::array();
    if (doc.contains("animations") && doc["animations"].is_array())
        for (const Json& a : doc["animations"])
            // The recorded path replaces any other animation of the same camera (and an older recording).
            if (!(a.contains("name") && a["name"] == "recorded") &&
                !(a.contains("camera") && a["camera"] == cameraName))
                animations.push_back(a);
    animations.push_back(animation);
    doc["animations"] = animations;
    return collapseNumberArrays(doc.dump(2)) + "\n";
}

void CameraPathRecorder::write(const std::string& path, const std::string& sceneSpec,
                               const std::string& cameraName) const
{
    writeTextFile(path, sceneFileText(sceneSpec, cameraName)); // a temporary renamed into place
}

} // namespace vplgi
