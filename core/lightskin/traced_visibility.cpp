#include "core/lightskin/traced_visibility.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include <glm/gtc/packing.hpp>

#include "core/util/random.h"
#include "glsl/shared/lightskin.h"
#include "glsl/shared/lightskin_visibility.h"
#include "glsl/shared/normals.h"

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

float lightCacheVisibilityLift(const RayScene& rays)
{
    return 1e-4f * rays.sceneScale();
}

namespace {
constexpr float kVisibilityMapOwnSurface = 4.0f; // lifts
} // namespace

std::vector<glm::uvec2> traceLightCacheVisibilityMaps(const RayScene& rays, const std::vector<LightCache>& caches,
                                                      int size)
{
    const auto texels = static_cast<std::size_t>(size) * static_cast<std::size_t>(size);
    std::vector<glm::uvec2> maps(caches.size() * texels);
    const float lift = lightCacheVisibilityLift(rays);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, caches.size(), 16), [&](const auto& range) {
        for (std::size_t c = range.begin(); c != range.end(); ++c) {
            const LightCache& cache = caches[c];
            const glm::mat3 frame = shared::occlusionFrame(cache.normal);
            for (int y = 0; y < size; ++y)
                for (int x = 0; x < size; ++x) {
                    Ray ray;
                    ray.origin = cache.position + lift * cache.normal;
                    ray.direction = frame * shared::visibilityMapTexelDirection(x, y, size);
                    // A surface within a few lifts of the cache counts as its own (a lamp quad 0.1 mm
                    // under the Cornell box's ceiling hid the whole room from the ceiling's caches
                    // above it, and the interpolation carried their darkness to the ceiling around).
                    ray.tMin = kVisibilityMapOwnSurface * lift;
                    const Hit hit = rays.intersect(ray, Looker::None);
                    glm::vec3 normal = cache.normal;
                    float t = shared::kVisibilityMapMiss;
                    if (hit.valid() && glm::dot(hit.geometricNormal, hit.geometricNormal) > 0.0f) {
                        t = hit.t;
                        normal = glm::normalize(hit.geometricNormal);
                        if (glm::dot(normal, ray.direction) > 0.0f) normal = -normal; // towards the cache
                    }
                    maps[c * texels + static_cast<std::size_t>(y * size + x)] =
                        glm::uvec2(glm::floatBitsToUint(t), glm::packSnorm2x16(shared::octEncode(normal)));
                }
        }
    });
    return maps;
}

float lightCacheVisibilityMapVisibility(const std::vector<glm::uvec2>& maps, int size, const LightCache& cache,
                                        std::size_t index, glm::vec3 val, glm::vec3 valNormal, float lift)
{
    const glm::mat3 frame = shared::occlusionFrame(cache.normal);
    const glm::vec3 origin = cache.position + lift * cache.normal;
    // A VAL within the lift of the cache's plane takes the map's rim (visibilityMapFromLocal clamps z).
    const glm::vec3 local = glm::transpose(frame) * (val - origin);
    if (!(glm::dot(local, local) > 0.0f)) return 1.0f;
    const glm::vec2 uv = shared::visibilityMapFromLocal(local);
    const glm::ivec2 first = shared::visibilityMapFirstNeighbour(uv, size);
    glm::vec3 d[4], n[4];
    float t[4];
    for (int k = 0; k < 4; ++k) {
        const int x = std::min(first.x + (k & 1), size - 1), y = std::min(first.y + (k >> 1), size - 1);
        const glm::uvec2 record = maps[index * static_cast<std::size_t>(size) * static_cast<std::size_t>(size) +
                                       static_cast<std::size_t>(y * size + x)];
        d[k] = frame * shared::visibilityMapTexelDirection(x, y, size);
        t[k] = glm::uintBitsToFloat(record.x);
        n[k] = shared::octDecode(glm::unpackSnorm2x16(record.y));
    }
    return shared::visibilityMapVisibility(origin, val, valNormal, lift, size,
                                           shared::visibilityMapBilinear(uv, first, size), d[0], t[0], n[0], d[1], t[1],
                                           n[1], d[2], t[2], n[2], d[3], t[3], n[3]);
}

} // namespace vplgi
