// The direct-light emitter list shared by the GPU direct pass and the CPU evaluations: scene lights
// become PointEmitters / DirectionalEmitters (glsl/shared/lights.h); emissive triangles are
// represented by `emitterSamples` cosine-emitting point samples, stratified by power.
#pragma once

#include <cstdint>
#include <vector>

#include "glsl/shared/lights.h"
#include "core/scene/scene.h"

namespace vplgi {

struct DirectLightParams {
    int emitterSamples = 64;   // point samples representing all emissive triangles together
    std::uint32_t seed = 1;    // sample placement seed
};

struct DirectLightSet {
    std::vector<shared::PointEmitter> points;
    std::vector<shared::DirectionalEmitter> directionals;
};

DirectLightSet buildDirectLights(const Scene& scene, const DirectLightParams& params);
// The same with `lights` in place of scene.lights (a snapshot taken by another thread: the scene's
// geometry and materials are read, its light list is not).
DirectLightSet buildDirectLights(const Scene& scene, const std::vector<Light>& lights, const DirectLightParams& params);

} // namespace vplgi
