// What a CPU half of a technique (a VPL sampler on a worker thread) may know about a frame: a copy,
// taken on the render thread, of everything it reads that the render thread writes (the camera and
// the lights, which animations move). A worker reads only its snapshot and the scene's static parts
// (geometry, materials, textures: never changed while a technique lives), so the render thread may
// animate the scene while the worker runs.
#pragma once

#include <cstdint>
#include <vector>

#include "core/scene/scene.h"

namespace vplgi {

struct FrameSnapshot {
    Camera camera;
    float aspect = 16.0f / 9.0f;   // the view's width / height
    std::vector<Light> lights;     // the scene's lights at this frame, by value
    double time = 0.0;             // animation time [s]

    // A snapshot of `scene`'s lights with `camera` (call it on the thread that owns the scene).
    static FrameSnapshot of(const Scene& scene, const Camera& camera, float aspect, double time = 0.0)
    {
        return FrameSnapshot{camera, aspect, scene.lights, time};
    }
};

} // namespace vplgi
