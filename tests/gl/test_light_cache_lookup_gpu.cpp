// glsl/shared/light_cache_lookup.h in GLSL (tests/gl/glsl/light_cache_lookup_probe.comp) against its
// C++ build (nearestLightCaches) on the cornell scene's light caches, with and without their reach.
// That the C++ build is the k-nearest search within reach is tests/cpu/test_light_caches.cpp's job
// (against brute force); this proves the two builds agree.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "core/lightskin/light_caches.h"
#include "core/lightskin/traced_visibility.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene/surface_points.h"
#include "gl_test_context.h"

using namespace vplgi;

namespace {

constexpr int kResultsPerCase = 9; // as in light_cache_lookup_probe.comp

std::uint32_t bitsOf(float f)
{
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

void pushVec3(std::vector<std::uint32_t>& words, const glm::vec3& v)
{
    for (int i = 0; i < 3; ++i)
        words.push_back(bitsOf(v[i]));
    words.push_back(0);
}

} // namespace

TEST_CASE("the light cache lookup gives the same caches in GLSL and C++", "[gl][lightskin]")
{
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("cornell");
    LightCacheSet set = distributeLightCaches(scene, LightCacheParams{}, ProgressSink{}, "");
    const bool reach = GENERATE(false, true);
    if (reach) set.reach = traceLightCacheReach(RayScene(scene), set.caches, set.grid.cellSize);
    const SurfacePoints points = sampleSurfacePoints(scene, 2048, 3);
    const int k = shared::kMaxLightCacheNeighbours;

    std::vector<std::uint32_t> words(13, 0);
    for (int i = 0; i < 3; ++i)
        words[static_cast<std::size_t>(i)] = bitsOf(set.grid.origin[i]);
    words[3] = bitsOf(set.grid.cellSize);
    words[4] = set.grid.slotMask;
    words[5] = static_cast<std::uint32_t>(set.grid.maxProbe);
    words[7] = static_cast<std::uint32_t>(k);
    words[8] = static_cast<std::uint32_t>(words.size());
    for (const LightCache& c : set.caches) {
        pushVec3(words, c.position);
        pushVec3(words, c.normal);
    }
    words[9] = static_cast<std::uint32_t>(words.size());
    for (const glm::uvec4& s : set.grid.slots)
        words.insert(words.end(), {s.x, s.y, s.z, s.w});
    words[10] = static_cast<std::uint32_t>(words.size());
    words.insert(words.end(), set.grid.cacheIndices.begin(), set.grid.cacheIndices.end());
    words[11] = static_cast<std::uint32_t>(words.size());
    for (std::size_t i = 0; i < points.positions.size(); ++i) {
        pushVec3(words, points.positions[i]);
        pushVec3(words, points.normals[i]);
    }
    if (reach) {
        words[12] = static_cast<std::uint32_t>(words.size());
        for (const glm::uvec4& r : set.reach)
            words.insert(words.end(), {r.x, r.y, r.z, r.w});
    }
    const int count = static_cast<int>(points.positions.size());
    const std::vector<glm::vec4> results =
        test::runComputeProbe("light cache lookup probe", "light_cache_lookup_probe.comp", words.data(),
                              words.size() * sizeof(std::uint32_t), count, kResultsPerCase);

    int setMismatches = 0, found = 0;
    double worstDistance = 0.0;
    shared::LightCacheNeighbours expected;
    for (int q = 0; q < count; ++q) {
        nearestLightCaches(set, points.positions[static_cast<std::size_t>(q)],
                           points.normals[static_cast<std::size_t>(q)], expected, k);
        const glm::vec4* got = &results[static_cast<std::size_t>(q) * kResultsPerCase];
        bool same = static_cast<int>(got[0].x) == expected.count;
        for (int s = 0; same && s < expected.count; ++s) {
            same = static_cast<int>(got[1 + s / 4][s % 4]) == expected.index[s];
            worstDistance = std::max(worstDistance, std::abs(static_cast<double>(got[5 + s / 4][s % 4]) -
                                                             static_cast<double>(expected.distance2[s])));
        }
        setMismatches += same ? 0 : 1;
        found += expected.count;
    }
    INFO("reach " << reach << ", mean caches per point " << static_cast<double>(found) / count
                  << ", worst |d^2 GPU - CPU| " << worstDistance << " m^2, d_eps " << set.distance << " m");
    CHECK(found > 8 * count); // the lookups found caches (about 12.6 per point within d_eps)
    // The same float operations in the same order, except that llvmpipe fuses the dot product's
    // multiply-adds: measured worst 2.3e-10 m^2, one ulp of a d^2 near d_eps^2 = 3.7e-3 m^2 (ulp 2^-32);
    // the bound is three such ulps. Sets: 0 mismatches measured; an ulp can only reorder a near-tie
    // or move a cache across the radius, which none of these points hit.
    CHECK(setMismatches == 0);
    CHECK(worstDistance <= 7e-10);
}
