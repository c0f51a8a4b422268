// Camera paths recorded in the viewer, saved as a scene file whose animation replays them: the same
// "animations" format scenes/*.json use (scenes/maze-walk.json), so a recorded path plays in the
// viewer (P), in `vplgi render --frames N --out 'frames/%04d.png'` and in `vplgi compare`.
#pragma once

#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace vplgi {

class CameraPathRecorder {
public:
    void start();
    void stop() { mRecording = false; }
    bool recording() const { return mRecording; }
    std::size_t keyCount() const { return mKeys.size(); }
    // A key at `time` [s] on the recorder's clock (the first key's time becomes 0). Keys closer than
    // `minStep` [s] to the previous one are dropped (a wall-clock recording at 60 fps would write a
    // key per frame), and so are times that do not increase (scene files require increasing "t").
    void add(float time, const Camera& camera, float minStep);

    // The scene file: for a built-in or glTF `sceneSpec` one that sources it, for a scene file a
    // copy of it (relative glTF sources made absolute, the camera's other animations dropped); either
    // way with the animation "recorded" of camera `cameraName` holding the keys. Throws Error when there are fewer than
    // two keys or the file cannot be written.
    std::string sceneFileText(const std::string& sceneSpec, const std::string& cameraName) const;
    void write(const std::string& path, const std::string& sceneSpec, const std::string& cameraName) const;

private:
    bool mRecording = false;
    float mStartTime = 0.0f;
    std::vector<Keyframe> mKeys;
};

} // namespace vplgi
