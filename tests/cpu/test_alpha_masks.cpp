// Alpha masks on the CPU side (glsl/shared/alpha_mask.h): Embree's filter lets rays through what a
// mask cuts and stops them on what it keeps, surface samples land only on kept surface, the
// untextured material tables average only kept texels. On the built-in cutout scene (a leaf cut out
// of a 2 m x 1.8 m panel at z = 0, 31% of its texels kept); the rasterizer's side is in
// tests/image/test_alpha_masks.cpp.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/scene/builtin_scenes.h"
#include "core/scene/surface.h"
#include "core/scene/surface_points.h"
#include "core/trace/ray_scene.h"
#include "measured.h"

using namespace vplgi;

namespace {

constexpr int kLeafMaterial = 1;

// The panel's texture coordinate at world (x, y) on z = 0 (addRect: u along +x, v along +y).
glm::vec2 panelUV(float x, float y)
{
    return {(x + 1.0f) / 2.0f, (y - 0.1f) / 1.8f};
}

} // namespace

TEST_CASE("alpha masks: rays pass where the mask cuts and stop where it keeps, for both ray kinds", "[alpha][numbers]")
{
    const Scene scene = makeBuiltinScene("cutout");
    const Material& leaf = scene.materials[kLeafMaterial];
    REQUIRE(leaf.isMasked());
    const RayScene rays(scene);
    const Image& image = scene.images[static_cast<std::size_t>(leaf.baseColorTexture.image)];
    // A 200 x 180 grid of rays along -z through the panel, from both sides (it is double-sided: the
    // mask must act on either). Rays within 1e-3 of the cutoff are left out: there Embree's
    // barycentrics and panelUV round differently (2 of 36000 rays did).
    int kept = 0, total = 0, wrongHit = 0, wrongOcclusion = 0;
    for (int j = 0; j < 180; ++j)
        for (int i = 0; i < 200; ++i) {
            const float x = -1.0f + (i + 0.5f) * 0.01f, y = 0.1f + (j + 0.5f) * 0.01f;
            const bool keeps = alphaMaskKeeps(scene, leaf, panelUV(x, y));
            if (std::abs(sampleImage(image, panelUV(x, y), false).a - leaf.alphaCutoff) < 1e-3f) continue;
            kept += keeps ? 1 : 0;
            ++total;
            for (float side : {1.0f, -1.0f}) {
                Ray ray;
                ray.origin = glm::vec3(x, y, side);
                ray.direction = glm::vec3(0.0f, 0.0f, -side);
                ray.tMax = 1.5f; // reaches the panel, not the floor
                const Hit hit = rays.intersect(ray);
                wrongHit += (hit.valid() != keeps) ? 1 : 0;
                if (hit.valid()) wrongHit += std::abs(hit.t - 1.0f) > 1e-4f ? 1 : 0;
                wrongOcclusion += (rays.occluded(ray) != keeps) ? 1 : 0;
            }
        }
    const double fraction = static_cast<double>(kept) / total;
    MEASURED("cutout leaf: " << kept << " of " << total << " rays hit (" << fraction << "); texel coverage "
                             << alphaCoverage(scene, leaf));
    CHECK(wrongHit == 0);
    CHECK(wrongOcclusion == 0);
    // The ray grid and the texel count measure the same area: 0.3091 and 0.3098 (the grid samples
    // the bilinear outline); 0.01 is 14x that difference and far below the 0.69 more that an
    // unmasked panel would give.
    CHECK(std::abs(fraction - alphaCoverage(scene, leaf)) < 0.01);
    CHECK(fraction > 0.25);
    CHECK(fraction < 0.4);

    // A closest-hit ray through a cut-out part of the panel goes on to the floor behind it.
    float x = 0.0f, y = 1.0f; // the leaf's centre: kept
    for (int i = 1; i < 2000 && alphaMaskKeeps(scene, leaf, panelUV(x, y)); ++i) {
        x = -0.95f + 0.0009f * i;
        y = 0.15f + 1.7f * std::fmod(0.618f * i, 1.0f);
    }
    REQUIRE_FALSE(alphaMaskKeeps(scene, leaf, panelUV(x, y)));
    Ray through;
    through.origin = glm::vec3(x, 2.0f * y, 1.0f);
    through.direction = glm::vec3(0.0f, -y, -1.0f); // through (x, y, 0) at t = 1, the floor at z = -1 at t = 2
    const Hit floor = rays.intersect(through);
    REQUIRE(floor.valid());
    CHECK(floor.t == Approx(2.0f));
    CHECK(scene.meshes[scene.instances[floor.instance].mesh].material == 0);
}

TEST_CASE("alpha masks: surface points only on kept surface, and the kept area", "[alpha][numbers]")
{
    const Scene scene = makeBuiltinScene("cutout");
    const Material& leaf = scene.materials[kLeafMaterial];
    const double coverage = alphaCoverage(scene, leaf);
    const double keptArea = 36.0 + 2.0 * 1.8 * coverage; // floor 6 x 6 m, the panel's kept part
    for (int blockSize : {0, 512}) {
        const SurfacePoints points = sampleSurfacePoints(scene, 200000, 7, blockSize);
        int onPanel = 0, onCut = 0;
        for (const glm::vec3& p : points.positions) {
            if (std::abs(p.z) > 1e-5f || p.y < 0.05f) continue; // the floor
            ++onPanel;
            onCut += alphaMaskKeeps(scene, leaf, panelUV(p.x, p.y)) ? 0 : 1;
        }
        const double panelShare = static_cast<double>(onPanel) / 200000.0;
        MEASURED("cutout surface points (block " << blockSize << "): area " << points.totalArea << " m^2 (kept "
                                                 << keptArea << "), panel share " << panelShare << " (expected "
                                                 << 3.6 * coverage / keptArea << "), " << onCut << " on cut texels");
        CHECK(onCut == 0);
        // Binomial: the share 0.0295 has sd sqrt(p (1-p) / n) = 3.8e-4 over 200000 points, 1.3% of
        // it; the area estimate's is the same. 5% is about 4 sd.
        CHECK(panelShare == Approx(3.6 * coverage / keptArea).epsilon(0.05));
        CHECK(points.totalArea == Approx(keptArea).epsilon(0.002)); // the panel is 1% of the area
    }
}

TEST_CASE("alpha masks: the untextured tables average only the texels a mask keeps", "[alpha]")
{
    Scene scene = makeBuiltinScene("cutout");
    Material& leaf = scene.materials[kLeafMaterial];
    Image& image = scene.images[static_cast<std::size_t>(leaf.baseColorTexture.image)];
    // Paint every cut texel black: the rays never see them, so the mean must not either.
    for (std::size_t i = 0; i < image.rgba.size(); i += 4)
        if (image.rgba[i + 3] == 0) image.rgba[i] = image.rgba[i + 1] = image.rgba[i + 2] = 0;
    const glm::vec3 kept = glm::vec3(sampleImage(image, panelUV(0.0f, 1.0f), true)); // the leaf's centre
    const UntexturedMaterials masked = computeUntexturedMaterials(scene);
    CHECK(glm::length(masked.baseColor[kLeafMaterial] - kept) < 1e-4f);
    const float coverage = alphaCoverage(scene, leaf);
    leaf.alphaMode = Material::AlphaMode::Opaque; // the same texture, opaque: the black part counts
    CHECK(alphaCoverage(scene, leaf) == 1.0f);
    const UntexturedMaterials opaque = computeUntexturedMaterials(scene);
    CHECK(glm::length(opaque.baseColor[kLeafMaterial] - coverage * kept) < 1e-4f);
}
