// LightSkin's occlusion reference (core/lightskin/traced_visibility.h) against closed forms: a cache
// under a plane of VALs sees all of them, none through a blocker that covers the plane, and half of
// their light when the blocker covers the half x < 0 (the weights are symmetric in x).
#include <catch2/catch.hpp>

#include <cmath>

#include "core/lightskin/traced_visibility.h"
#include "measured.h"
#include "test_scenes.h"

using namespace vplgi;

namespace {

// VALs on a 4 x 4 m grid at y = 2 facing down, 0.01 m^2 each, equal power.
std::vector<TracedVAL> ceilingVALs()
{
    std::vector<TracedVAL> vals;
    for (int i = 0; i < 40; ++i)
        for (int k = 0; k < 40; ++k) {
            TracedVAL val;
            val.position = glm::vec3(-1.95f + 0.1f * static_cast<float>(i), 2.0f, -1.95f + 0.1f * static_cast<float>(k));
            val.normal = glm::vec3(0.0f, -1.0f, 0.0f);
            val.area = 0.01f;
            val.power = 1.0f;
            vals.push_back(val);
        }
    return vals;
}

// A blocker quad at y = 1 over x in [x0, x1] (z in [-10, 10]), and a floor far below that keeps the
// scene's bounds (and so the ray offsets) the same with and without it.
Scene blockerScene(float x0, float x1)
{
    Scene scene;
    scene.name = "blocker";
    const int grey = test::addTestMaterial(scene, "grey", glm::vec3(0.5f));
    test::addTestQuad(scene, grey, {-10.0f, -5.0f, 10.0f}, {20.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -20.0f});
    if (x1 > x0) test::addTestQuad(scene, grey, {x0, 1.0f, 10.0f}, {x1 - x0, 0.0f, 0.0f}, {0.0f, 0.0f, -20.0f});
    scene.validate();
    return scene;
}

} // namespace

TEST_CASE("lightskin traced visibility: all, none and half of a ceiling of VALs", "[lightskin]")
{
    LightCache cache;
    cache.position = glm::vec3(0.0f);
    cache.normal = glm::vec3(0.0f, 1.0f, 0.0f);
    LightCache sideways = cache; // faces +x: only the VALs at x > 0 light it
    sideways.normal = glm::vec3(1.0f, 0.0f, 0.0f);
    const std::vector<LightCache> caches{cache, sideways};
    const std::vector<TracedVAL> vals = ceilingVALs();
    const int samples = 4096;

    const Scene open = blockerScene(0.0f, 0.0f), covered = blockerScene(-10.0f, 10.0f), half = blockerScene(-10.0f, 0.0f);
    const RayScene openRays(open), coveredRays(covered), halfRays(half);
    const std::vector<float> all = traceCacheVisibility(openRays, caches, vals, samples, 1);
    const std::vector<float> none = traceCacheVisibility(coveredRays, caches, vals, samples, 1);
    const std::vector<float> halves = traceCacheVisibility(halfRays, caches, vals, samples, 1);
    MEASURED("traced visibility of a ceiling of VALs: open " << all[0] << ", covered " << none[0] << ", half covered "
             << halves[0] << " (0.5 expected), the cache facing +x behind the half blocker " << halves[1]
             << " (1 expected)");
    CHECK(all[0] == 1.0f);
    CHECK(none[0] == 0.0f);
    // 4096 draws: the standard error of a fraction 0.5 is 0.0078; the bound is 3 of them.
    CHECK(std::abs(halves[0] - 0.5f) < 0.025f);
    // The cache facing +x draws only VALs at x > 0 (its cosine is 0 for the rest): none blocked.
    CHECK(halves[1] == 1.0f);
    // Deterministic: the same seed, the same estimate.
    CHECK(traceCacheVisibility(halfRays, caches, vals, samples, 1) == halves);
}
