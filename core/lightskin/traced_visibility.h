// LightSkin's occlusion reference (issue "LightSkin's indirect shadows"): the fraction of a light
// cache's one-bounce light that reaches it unblocked, traced with Embree. Not real-time and not in
// the paper: `lightskin.tracedOcclusion` puts it where the double projection's estimate goes, so
// that the image's error splits into what the caches and their interpolation cost (traced) and what
// the double projection adds (docs/lightskin.md, "Occlusion").
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/lightskin/light_caches.h"
#include "core/trace/ray_scene.h"

namespace vplgi {

// A virtual area light as the proxy pass sees it (glsl/passes/lightskin_proxy.comp): position,
// geometric normal, eq. (1)'s area and the luminance of its reflected flux (after the shading-normal
// correction).
struct TracedVAL {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};
    float area = 0.0f;  // [m^2]
    float power = 0.0f; // luminance of the flux [W]
};

// Per cache: sum_l c_l V(c, l) / sum_l c_l with c_l the VAL's eq. (3) term at the cache (flux times
// glsl/shared/lightskin.h valGeometryTerm) and V the visibility of the segment between them (both
// ends lifted off their surfaces by 1e-4 of the scene's diagonal), estimated from `samples` VALs
// drawn in proportion to c_l (a Monte Carlo standard error of at most 0.5/sqrt(samples)). 1 for a
// cache no VAL lights. Deterministic: the draws are keyed by (seed, cache), not by threads. With
// `wanted` (one flag per cache; empty: every cache), a cache flagged 0 is not traced and gets 1.
std::vector<float> traceCacheVisibility(const RayScene& rays, const std::vector<LightCache>& caches,
                                        const std::vector<TracedVAL>& vals, int samples, std::uint32_t seed,
                                        const std::vector<std::uint8_t>& wanted = {});

// Each cache's reach record (glsl/shared/light_cache_lookup.h, lightCacheReaches) for the search
// radius `radius`: 16 rays per cache from kLightCacheReachLift radius above it, along
// lightCacheReachDirection, each hit's distance (in the tangent plane for the azimuths) floored to
// 1/255 of the radius. Any surface stops a ray, from either side. Deterministic; not in the paper.
std::vector<glm::uvec4> traceLightCacheReach(const RayScene& rays, const std::vector<LightCache>& caches, float radius);

// LightSkin's visibility maps (glsl/shared/lightskin_visibility.h; not in the paper): for each cache,
// size x size texels over its hemisphere, cache after cache, row after row; texel (x, y) is
// uvec2(bits of the distance t, packSnorm2x16 of the octEncode'd hit normal turned towards the
// cache), t = kVisibilityMapMiss for a miss. The rays start lightCacheVisibilityLift(rays) above the
// cache and stop at any surface from either side (Looker::None, as the path tracer's rays), except
// within 4 lifts of their start (a surface that close counts as the cache's own). Deterministic.
std::vector<glm::uvec2> traceLightCacheVisibilityMaps(const RayScene& rays, const std::vector<LightCache>& caches,
                                                      int size);
// How far the maps' rays start above the cache (and the margin of their verdicts): 1e-4 of the
// scene's diagonal, the lift of traceCacheVisibility.
float lightCacheVisibilityLift(const RayScene& rays);
// The maps' visibility (0-1) of a VAL at `val` (unit geometric normal valNormal) from cache `index`,
// as glsl/passes/lightskin_proxy.comp takes it. A VAL below the lifted cache's tangent plane takes
// the map's rim.
float lightCacheVisibilityMapVisibility(const std::vector<glm::uvec2>& maps, int size, const LightCache& cache,
                                        std::size_t index, glm::vec3 val, glm::vec3 valNormal, float lift);

} // namespace vplgi
