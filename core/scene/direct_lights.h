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

// The emissive samples of `lights` (kProfileCosine) merged into at most `maxGroups` cosine emitters,
// the RSM techniques' sources for emissive triangles (gl/passes/rsm_pass.h; not in any paper).
// Samples are clustered by position and normal (power-weighted farthest-point seeds, then a few
// Lloyd steps; deterministic). A group sits at its samples' power-weighted centroid, emits around
// their power-weighted mean normal with a cosine profile, and its peak intensity is the sum of
// theirs, so its power pi * I is theirs exactly; its emission is exact for samples of one flat
// emitter seen from afar and approximate where a group's normals differ (curved lamps). Empty when
// there is no emissive sample or maxGroups is 0.
std::vector<shared::PointEmitter> groupCosineEmitters(const DirectLightSet& lights, int maxGroups);

} // namespace vplgi
