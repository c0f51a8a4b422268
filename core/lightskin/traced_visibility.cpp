#include "core/lightskin/traced_visibility.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/util/random.h"
#include "glsl/shared/lightskin.h"

namespace vplgi {

std::vector<float> traceCacheVisibility(const RayScene& rays, const std::vector<LightCache>& caches,
                                        const std::vector<TracedVAL>& vals, int samples, std::uint32_t seed,
                                        const std::vector<std::uint8_t>& wanted)
{
    std::vector<float> visibility(caches.size(), 1.0f);
    const float lift = 1e-4f * rays.sceneScale();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, caches.size(), 16), [&](const auto& range) {
        std::vector<double> cumulative(vals.size());
        for (std::size_t c = range.begin(); c != range.end(); ++c) {
            if (!wanted.empty() && wanted[c] == 0) continue;
            const LightCache& cache = caches[c];
            double total = 0.0;
            for (std::size_t l = 0; l < vals.size(); ++l) {
                const TracedVAL& val = vals[l];
                const glm::vec3 toVal = val.position - cache.position;
                const float distance2 = glm::dot(toVal, toVal);
                if (distance2 > 0.0f) {
                    const glm::vec3 w = toVal / std::sqrt(distance2);
                    total += double(val.power) * shared::valGeometryTerm(val.area, -glm::dot(val.normal, w),
                                                                         glm::dot(cache.normal, w), distance2);
                }
                cumulative[l] = total;
            }
            if (!(total > 0.0)) continue;
            Pcg32 random(mix64((std::uint64_t(seed) << 32u) ^ c), 0x6c736b76u); // "lskv"
            int visible = 0;
            for (int s = 0; s < samples; ++s) {
                const double u = double(random.uniform()) * total;
                const auto l = static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), u) -
                                                        cumulative.begin());
                const TracedVAL& val = vals[std::min(l, vals.size() - 1)];
                if (rays.visible(cache.position + lift * cache.normal, val.position + lift * val.normal, Looker::End))
                    ++visible; // the VAL looks
            }
            visibility[c] = static_cast<float>(visible) / static_cast<float>(samples);
        }
    });
    return visibility;
}

std::vector<glm::uvec4> traceLightCacheReach(const RayScene& rays, const std::vector<LightCache>& caches, float radius)
{
    std::vector<glm::uvec4> reach(caches.size(), glm::uvec4(0u));
    const float lift = shared::kLightCacheReachLift * radius;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, caches.size(), 64), [&](const auto& range) {
        for (std::size_t c = range.begin(); c != range.end(); ++c) {
            const LightCache& cache = caches[c];
            for (int i = 0; i <= shared::kLightCacheReachAzimuths; ++i) {
                const glm::vec3 direction = shared::lightCacheReachDirection(cache.normal, i);
                // The tangent-plane distance of a hit at t along a rising ray is t cos(rise).
                const float planar =
                    i < shared::kLightCacheReachAzimuths
                        ? std::sqrt(1.0f - glm::dot(direction, cache.normal) * glm::dot(direction, cache.normal))
                        : 1.0f;
                Ray ray;
                ray.origin = cache.position + lift * cache.normal;
                ray.direction = direction;
                ray.tMax = radius / planar;
                const Hit hit = rays.intersect(ray);
                const float fraction = hit.valid() ? std::min(hit.t * planar / radius, 1.0f) : 1.0f;
                const auto byte = static_cast<std::uint32_t>(std::floor(fraction * 255.0f));
                reach[c][i / 4] |= byte << (8 * (i % 4));
            }
        }
    });
    return reach;
}

} // namespace vplgi
