// Techniques `lightskin` and `lightskin-full` (gl/techniques/lightskin_technique.h): the selected VALs
// converge to all VALs as N grows (eq. 14 is unbiased), all VALs agree with the one-bounce path
// tracer on an unoccluded corner within LightSkin's own approximation, the double projection
// removes the light a wall blocks and keeps the light nothing blocks, determinism. The maths of
// each equation is tested on its own in tests/cpu/test_lightskin_math.cpp and the cache
// distribution in tests/cpu/test_light_caches.cpp; the selection's frequencies (SAT + binary
// search, chi-square against the CPU twin) in tests/gl/test_importance_sampler.cpp.
#include <catch2/catch.hpp>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "core/scene/builtin_scenes.h"
#include "core/trace/path_tracer.h"
#include "core/trace/ray_scene.h"
#include "glsl/shared/lightskin_gpu.h"
#include "glsl/shared/tonemap.h"
#include "gl/techniques/lightskin_technique.h"
#include "gl_test_context.h"
#include "measured.h"
#include "technique_determinism.h"
#include "test_scenes.h"

using namespace vplgi;

namespace {

using test::meanLuminance;

// A spot light on a floor patch (x < 0.9), a wall at x = 3 facing it that the spot does not reach,
// and, with `blocker`, a 2.5 m wall at x = 1.5 between them that takes every one-bounce path from
// the lit patch to the wall. The camera stands between blocker and wall and sees only the wall.
Scene blockedWallScene(bool blocker)
{
    Scene scene;
    scene.name = blocker ? "blocked wall" : "open wall";
    const int grey = test::addTestMaterial(scene, "grey", glm::vec3(0.7f));
    test::addTestQuad(scene, grey, {-2.0f, 0.0f, 2.0f}, {5.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -4.0f}); // floor, +y
    test::addTestQuad(scene, grey, {3.0f, 0.0f, -2.0f}, {0.0f, 0.0f, 4.0f}, {0.0f, 3.0f, 0.0f});  // wall, -x
    if (blocker) {
        test::addTestQuad(scene, grey, {1.5f, 0.0f, -3.0f}, {0.0f, 2.5f, 0.0f}, {0.0f, 0.0f, 6.0f}); // -x face
        test::addTestQuad(scene, grey, {1.5f, 0.0f, -3.0f}, {0.0f, 0.0f, 6.0f}, {0.0f, 2.5f, 0.0f}); // +x face
    }
    scene.lights.push_back(test::makeTestSpot("spot", {-0.6f, 2.5f, 0.0f}, {0.0f, -1.0f, 0.0f}, 20.0f, 0.4f, 0.5f));
    Camera camera;
    camera.name = "wall";
    camera.position = {2.0f, 1.5f, 0.0f};
    camera.target = {3.0f, 1.5f, 0.0f};
    scene.cameras.push_back(camera);
    scene.validate();
    return scene;
}

} // namespace

TEST_CASE("lightskin: the selected VALs converge to all VALs as N grows, all VALs near the one-bounce path tracer",
          "[lightskin][image][numbers]")
{
    test::ensureGLContext();
    const Scene scene = test::cornerScene(0.0f, 1.0f);
    const Camera& camera = scene.cameras[0];
    const int width = 48, height = 36;
    const Settings common = {{"rsm.size", "32"}, {"lightskin.cacheDistance", "0.25"}};
    auto render = [&](const std::string& technique, const Settings& extra) {
        Settings settings = common;
        settings.insert(settings.end(), extra.begin(), extra.end());
        std::unique_ptr<Renderer> renderer = test::makeTechniqueRenderer(scene, technique, settings);
        return test::renderIndirect(*renderer, camera, width, height);
    };
    const ImageRGBA32F full = render("lightskin-full", {});
    const int counts[] = {64, 1024, 16384};
    double toFull[3];
    for (int i = 0; i < 3; ++i)
        toFull[i] = test::relativeL1(render("lightskin", {{"lightskin.valCount", std::to_string(counts[i])}}), full);

    const ImageRGBA32F reference = test::oneBounceReference(scene, camera, width, height, 4096);
    const double fullError = test::relativeL1(full, reference);
    const double fullBias = meanLuminance(full) / meanLuminance(reference) - 1.0;
    test::saveTestImage("lightskin_full_corner", full);
    MEASURED("unoccluded corner (48x36, RSM 32^2, d_eps 0.25 m): relative L1 of lightskin against lightskin-full at "
             "N = 64/1024/16384: "
             << toFull[0] << " " << toFull[1] << " " << toFull[2]
             << "; lightskin-full against the one-bounce path tracer " << fullError << " (mean " << 100.0 * fullBias
             << "%)");
    // Eq. (14) is unbiased: more draws, closer to all VALs (a Monte Carlo error falls as 1/sqrt(N)).
    CHECK(toFull[1] < toFull[0]);
    CHECK(toFull[2] < toFull[1]);
    CHECK(toFull[2] < 0.25 * toFull[0]);
    // LightSkin itself approximates (a point proxy per cache, interpolation): measured relative L1
    // 0.076 and mean +4.2% against the path tracer (its own noise at 4096 spp is far below); the
    // bounds are 2.5-3x those.
    CHECK(fullError < 0.2);
    CHECK(std::abs(fullBias) < 0.12);
}

TEST_CASE("lightskin: the double projection removes the light a wall blocks and keeps the light nothing blocks",
          "[lightskin][image][numbers]")
{
    test::ensureGLContext();
    auto mean = [&](bool blocker, bool occlusion, bool maps = false) {
        const Scene scene = blockedWallScene(blocker);
        std::unique_ptr<Renderer> renderer =
            test::makeTechniqueRenderer(scene, "lightskin-full",
                                        {{"rsm.size", "32"},
                                         {"lightskin.cacheDistance", "0.4"},
                                         {"lightskin.occlusion", occlusion ? "true" : "false"},
                                         {"lightskin.visibilityMaps", maps ? "true" : "false"}});
        return meanLuminance(test::renderIndirect(*renderer, scene.cameras[0], 32, 24));
    };
    const double blockedOn = mean(true, true), blockedOff = mean(true, false);
    const double openOn = mean(false, true), openOff = mean(false, false);
    const double blockedMaps = mean(true, true, true), openMaps = mean(false, true, true);
    MEASURED("wall seen past a blocker: indirect with occlusion / without "
             << blockedOn / blockedOff << "; without the blocker: " << openOn / openOff << " (means " << blockedOn
             << " " << blockedOff << " " << openOn << " " << openOff << "); with visibility maps instead "
             << blockedMaps / blockedOff << " and " << openMaps / openOff);
    REQUIRE(openOff > 0.0);
    REQUIRE(blockedOff > 0.0); // without occlusion the caches see the lit floor through the blocker
    // Measured exactly 0 with the blocker and 1.000 without it (0.978, 2.2% falsely occluded, before
    // the caches' reach and lightskin.occluderLight). With the blocker, 1e-3 of the unblocked
    // light is far above float noise and far below any real leak (the old bound, 10%, let one
    // through); without it the bound allows about 3x the false occlusion.
    CHECK(blockedOn < 1e-3 * blockedOff);
    CHECK(openOn > 0.94 * openOff);
    // The visibility maps (lightskin.visibilityMaps, not in the paper): the same bounds.
    CHECK(blockedMaps < 1e-3 * blockedOff);
    CHECK(openMaps > 0.94 * openOff);
}

TEST_CASE("lightskin: occlusion acts on a wall that a board shades from a broad lit floor (the board scene)",
          "[lightskin][image][numbers]")
{
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("board");
    const Camera& camera = scene.cameras[0]; // every pixel on the wall behind the board
    const int width = 32, height = 18;
    auto mean = [&](const Settings& extra) {
        // The double projection's variants with the visibility maps off (they are the default).
        Settings settings = {{"rsm.size", "128"}, {"lightskin.visibilityMaps", "false"}};
        settings.insert(settings.end(), extra.begin(), extra.end());
        std::unique_ptr<Renderer> renderer = test::makeTechniqueRenderer(scene, "lightskin-full", settings);
        return meanLuminance(test::renderIndirect(*renderer, camera, width, height));
    };
    const double cells = mean({});
    const double traced = mean({{"lightskin.tracedOcclusion", "true"}});
    const double paper = mean({{"lightskin.occlusionCells", "false"}});
    const double maps = mean({{"lightskin.visibilityMaps", "true"}});
    const double off = mean({{"lightskin.occlusion", "false"}});
    const double reference = meanLuminance(test::oneBounceReference(scene, camera, width, height, 1024));
    MEASURED("board scene, the wall behind the board (32x18, RSM 128^2, automatic d_eps): lightskin-full against the "
             "one-bounce path tracer with occlusion cells "
             << 100.0 * (cells / reference - 1.0) << "%, with traced visibility " << 100.0 * (traced / reference - 1.0)
             << "%, with visibility maps " << 100.0 * (maps / reference - 1.0) << "%, the paper's sphere per proxy "
             << 100.0 * (paper / reference - 1.0) << "%, without occlusion "
             << 100.0 * (off / reference - 1.0) << "%; cells / traced " << cells / traced);
    REQUIRE(reference > 0.0);
    // The paper's sphere contains the cache (its VALs span the floor): no occluder counts, so it
    // is the unoccluded light, about twice the path tracer's (measured +98%).
    CHECK(paper == Approx(off).epsilon(1e-3));
    CHECK(paper > 1.6 * reference);
    // With each cache's visibility traced, the caches and their interpolation are close to the path
    // tracer (measured -4.0%; bound about 2.5x).
    CHECK(std::abs(traced / reference - 1.0) < 0.1);
    // The cells' double projection against the traced visibility: measured 0.842 (it blocks a
    // little too much); the bound is about 2x that error. The last check is the acceptance
    // line (within 20% of the path tracer; measured -19.2%), not a tolerance: the path tracer's
    // noise at 1024 spp moves the mean by well under 1%, the rest is deterministic.
    CHECK(std::abs(cells / traced - 1.0) < 0.3);
    CHECK(std::abs(cells / reference - 1.0) < 0.2);
    // The visibility maps (not in the paper): measured +6.8% (1.11x the traced visibility; the maps
    // err towards light within a texel of the board's edge); the same acceptance line.
    CHECK(std::abs(maps / traced - 1.0) < 0.3);
    CHECK(std::abs(maps / reference - 1.0) < 0.2);
}

TEST_CASE("lightskin: visibility maps keep the sealed rooms' closed room dark", "[lightskin][image][numbers]")
{
    // The sealed rooms (core/scene/builtin_scenes.cpp makeSealed): the path tracer gives exactly 0
    // in the closed room. The closed room's brightest indirect pixel over the lit room's mean, as
    // conform measures it, for lightskin-full (deterministic) with the double projection and with
    // the visibility maps (lightskin.visibilityMaps, not in the paper).
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("sealed");
    const Camera* lit = &scene.cameras[0];
    const Camera* closed = nullptr;
    for (const Camera& camera : scene.cameras)
        if (camera.name == "closed") closed = &camera;
    REQUIRE(closed != nullptr);
    auto leak = [&](const Settings& extra) {
        Settings settings = {{"rsm.size", "128"}};
        settings.insert(settings.end(), extra.begin(), extra.end());
        std::unique_ptr<Renderer> renderer = test::makeTechniqueRenderer(scene, "lightskin-full", settings);
        const double litMean = meanLuminance(test::renderIndirect(*renderer, *lit, 32, 18));
        const ImageRGBA32F image = test::renderIndirect(*renderer, *closed, 32, 18);
        double brightest = 0.0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                const float* p = image.at(x, y);
                brightest = std::max(brightest, double(shared::luminanceRec709(glm::vec3(p[0], p[1], p[2]))));
            }
        REQUIRE(litMean > 0.0);
        return brightest / litMean;
    };
    const double projection = leak({{"lightskin.visibilityMaps", "false"}});
    const double maps = leak({});
    const double none = leak({{"lightskin.occlusion", "false"}});
    MEASURED("sealed rooms, lightskin-full (32x18, RSM 128^2): the closed room's brightest indirect pixel over the lit "
             "room's mean: double projection " << projection << ", visibility maps " << maps << ", no occlusion " << none);
    // Measured: double projection 0.31, maps exactly 0, no occlusion 2.24. The bound on the maps is
    // the target (below 1e-4 of the lit room's mean), not a tolerance; the double projection
    // is far from it (docs/lightskin.md, "Occlusion").
    CHECK(none > 0.1); // the check can fail: without occlusion the closed room is lit
    CHECK(maps < 1e-4);
}

TEST_CASE("lightskin and lightskin-full images are bit-identical over runs", "[lightskin][lightskin-determinism]")
{
    test::ensureGLContext();
    const Scene scene = test::cornerScene(1.0f, 0.3f); // glossy: the glossy proxies too
    for (const std::string technique : {"lightskin", "lightskin-full"})
        test::checkTechniqueBitIdentical(scene, technique, {{"rsm.size", "32"}, {"lightskin.cacheDistance", "0.3"}}, 32,
                                         24);
}

TEST_CASE("lightskin: view culling makes proxies only for caches in view and changes no bit", "[lightskin][image]")
{
    // A narrow camera on the corner's joint: most caches lie outside its frustum (by more than d_eps).
    // Culled caches' proxies are never interpolated (lightskin.h, lightCacheInView), so the image is
    // the same bits with and without culling; the stats count what the passes kept.
    test::ensureGLContext();
    const Scene scene = test::cornerScene(1.0f, 0.3f);
    Camera camera = scene.cameras[0];
    camera.target = glm::vec3(-1.0f, 0.3f, 0.2f);
    camera.fovY = 0.2f;
    // lightskin with the traced occlusion too: it traces only the caches in view.
    for (const auto& [technique, traced] : {std::pair<std::string, const char*>{"lightskin", "false"},
                                            {"lightskin-full", "false"},
                                            {"lightskin", "true"}}) {
        INFO(technique << ", traced occlusion " << traced);
        std::vector<ImageRGBA32F> images;
        std::vector<double> inView, caches;
        for (const char* culling : {"true", "false"}) {
            std::unique_ptr<Renderer> renderer = test::makeTechniqueRenderer(
                scene, technique,
                {{"rsm.size", "32"},
                 {"lightskin.cacheDistance", "0.3"},
                 {"lightskin.viewCulling", culling},
                 {"lightskin.tracedOcclusion", traced}});
            images.push_back(test::renderIndirect(*renderer, camera, 32, 24));
            for (const auto& [key, value] : renderer->technique().frameStats()) {
                if (key == "caches in view") inView.push_back(value);
                if (key == "caches") caches.push_back(value);
            }
        }
        REQUIRE(inView.size() == 2u);
        REQUIRE(caches.size() == 2u);
        INFO("caches " << caches[0] << ", in view " << inView[0]);
        CHECK(inView[0] > 0.0);
        CHECK(inView[0] < 0.5 * caches[0]); // the culling acts
        CHECK(inView[1] == caches[1]);      // without it, every cache
        CHECK(meanLuminance(images[0]) > 0.0);
        CHECK(test::firstBitDifference(images[0].pixels, images[1].pixels) == -1);
    }
}

namespace {

// The canyon's bias split (issue "LightSkin's indirect shadows", acceptance): lightskin-full with
// traced visibility, against the path tracer's one-bounce irradiance E (luminance, at white
// Lambertian points: pi (L_2 - L_1), L_b the reflected radiance with at most b reflections, the same
// seed so the direct part cancels sample by sample), at each pixel's surface point x (camera rays,
// Embree) and at the caches eq. (8) weighs there (the C++ twin of the lookup, with the reach):
//   truth       E(x)
//   A           sum_c w_c E(c) / sum_c w_c          caches as the truth has them, interpolated
//   B           sum_c w_c E_ls(c) / sum_c w_c        caches as lightskin-full gives them (its diffuse
//                                                    proxy reproduces eq. (14)'s sum at the cache, eq. (7),
//                                                    times the traced visibility: sum_l E_l V_l)
//   C           eq. (9): the interpolated diffuse proxy as a point light at x, Phi cos / (4 pi d^2)
// Over the pixels: cache points sum B / sum A - 1 (the RSM's texels as light), interpolation sum A /
// sum truth - 1 (caches for points), eq. (9) sum C / sum B - 1 (moving one proxy instead of
// averaging irradiance); their product is lightskin-full's bias with traced visibility, and the
// double projection's share is the default's image against that (docs/lightskin.md, "Occlusion").
constexpr double kPi = 3.14159265358979323846;

struct BiasSplit {
    int caches = 0;    // caches some pixel interpolates
    int pixels = 0;    // pixels with a cache and a surface
    double cachePoints = 0.0, interpolation = 0.0, proxyMove = 0.0, total = 0.0;
};

BiasSplit canyonBiasSplit(const Scene& scene, float cacheDistance, int rsmSize, int samples)
{
    const int width = 64, height = 36;
    std::unique_ptr<Renderer> renderer = test::makeTechniqueRenderer(
        scene, "lightskin-full",
        {{"rsm.size", std::to_string(rsmSize)},
         {"lightskin.cacheDistance", std::to_string(cacheDistance)},
         {"lightskin.tracedOcclusion", "true"}});
    const Camera& camera = scene.cameras[0];
    test::renderIndirect(*renderer, camera, width, height);
    const auto& technique = dynamic_cast<const LightSkinTechnique&>(renderer->technique());
    const LightCacheSet& set = technique.caches();
    const std::vector<shared::ProxyLight> proxies =
        test::readBuffer<shared::ProxyLight>(technique.proxies(), set.caches.size());
    const RayScene rays(scene);
    const ReflectedRadianceEstimator one(scene, rays, 1), two(scene, rays, 2);
    auto pathIrradiance = [&](const glm::vec3& position, const glm::vec3& normal, std::uint32_t seed) {
        SurfacePoint y;
        y.position = position;
        y.normal = y.geometricNormal = normal;
        y.material.baseColor = glm::vec3(1.0f); // white and Lambertian: L = E / pi
        y.material.metallic = 0.0f;
        y.material.roughness = 1.0f;
        y.material.specular = 1.0f;
        return kPi * (double(shared::luminanceRec709(two.estimate(y, samples, seed))) -
                      double(shared::luminanceRec709(one.estimate(y, samples, seed))));
    };
    // The pixels' surface points and their caches (eq. 8 as lightskin_shading.frag: fixed d_max = d_eps,
    // p = 1).
    struct Pixel {
        glm::vec3 x{0.0f}, n{0.0f};
        shared::LightCacheNeighbours near{};
        bool valid = false;
    };
    std::vector<Pixel> pixels(static_cast<std::size_t>(width * height));
    const CameraRays cameraRays(camera, width, height);
    std::vector<std::uint8_t> used(set.caches.size(), 0);
    for (int py = 0; py < height; ++py)
        for (int px = 0; px < width; ++px) {
            Pixel& p = pixels[static_cast<std::size_t>(py * width + px)];
            const Ray ray = cameraRays.at(px + 0.5, py + 0.5);
            const Hit hit = rays.intersect(ray, Looker::Origin);
            if (!hit.valid()) continue;
            const SurfacePoint s = surfaceAt(scene, hit, -ray.direction);
            p.x = s.position;
            p.n = s.normal;
            p.valid = nearestLightCaches(set, p.x, p.n, p.near) > 0;
            for (int i = 0; p.valid && i < p.near.count; ++i) used[static_cast<std::size_t>(p.near.index[i])] = 1;
        }
    std::vector<double> truthCache(set.caches.size(), 0.0), lightskinCache(set.caches.size(), 0.0), truthPixel(pixels.size(), 0.0);
    tbb::parallel_for(std::size_t(0), set.caches.size(), [&](std::size_t i) {
        if (used[i] == 0) return;
        const LightCache& c = set.caches[i];
        const shared::ProxyLight& p = proxies[i];
        const glm::vec3 toProxy = glm::vec3(p.diffusePositionRadius) - c.position;
        const float distance2 = glm::dot(toProxy, toProxy);
        const float cosine = distance2 > 0.0f ? glm::dot(c.normal, toProxy) / std::sqrt(distance2) : 0.0f;
        lightskinCache[i] = distance2 > 0.0f ? double(shared::luminanceRec709(glm::vec3(p.diffuseFlux))) *
                                                   p.diffuseFlux.w * std::max(cosine, 0.0f) / (4.0 * kPi * distance2)
                                             : 0.0;
        truthCache[i] = pathIrradiance(c.position, c.normal, static_cast<std::uint32_t>(i));
    });
    tbb::parallel_for(std::size_t(0), pixels.size(), [&](std::size_t i) {
        if (pixels[i].valid) truthPixel[i] = pathIrradiance(pixels[i].x, pixels[i].n, static_cast<std::uint32_t>(1u << 24u) + i);
    });
    BiasSplit split;
    for (std::uint8_t u : used) split.caches += u;
    double truth = 0.0, a = 0.0, b = 0.0, c = 0.0;
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        const Pixel& p = pixels[i];
        if (!p.valid) continue;
        double sumW = 0.0, sumA = 0.0, sumB = 0.0;
        glm::dvec3 position(0.0), flux(0.0);
        for (int k = 0; k < p.near.count; ++k) {
            const auto index = static_cast<std::size_t>(p.near.index[k]);
            const LightCache& cache = set.caches[index];
            const double w = shared::interpolationWeight(std::sqrt(p.near.distance2[k]), set.grid.cellSize,
                                                         shared::kInterpolationExponent, glm::dot(p.n, cache.normal));
            sumW += w;
            sumA += w * truthCache[index];
            sumB += w * lightskinCache[index];
            position += w * glm::dvec3(proxies[index].diffusePositionRadius);
            flux += w * glm::dvec3(proxies[index].diffuseFlux) * double(proxies[index].diffuseFlux.w);
        }
        if (!(sumW > 0.0)) continue;
        ++split.pixels;
        const glm::dvec3 toProxy = position / sumW - glm::dvec3(p.x);
        const double distance2 = glm::dot(toProxy, toProxy);
        const double cosine = distance2 > 0.0 ? glm::dot(glm::dvec3(p.n), toProxy) / std::sqrt(distance2) : 0.0;
        const glm::vec3 meanFlux(flux / sumW);
        truth += truthPixel[i];
        a += sumA / sumW;
        b += sumB / sumW;
        c += distance2 > 0.0 ? double(shared::luminanceRec709(meanFlux)) * std::max(cosine, 0.0) / (4.0 * kPi * distance2)
                             : 0.0;
    }
    split.cachePoints = b / a - 1.0;
    split.interpolation = a / truth - 1.0;
    split.proxyMove = c / b - 1.0;
    split.total = c / truth - 1.0;
    return split;
}

void printSplit(float distance, const BiasSplit& s)
{
    std::printf("| %.0f m | %d | %d | %+.1f%% | %+.1f%% | %+.1f%% | %+.1f%% |\n", static_cast<double>(distance), s.caches,
                s.pixels, 100.0 * s.cachePoints, 100.0 * s.interpolation, 100.0 * s.proxyMove, 100.0 * s.total);
}

} // namespace

TEST_CASE("lightskin: the canyon's bias split into cache points, interpolation and eq. (9)", "[lightskin][numbers]")
{
    // d_eps = 8 m, a 128^2 RSM, 64 paths per estimate (the hidden case below makes docs/lightskin.md's
    // table at 8, 4 and 2 m, 256^2, 256 paths). The three parts multiply to the whole (plumbing);
    // what can fail: lightskin-full with traced visibility stays within 15% of the path tracer here
    // (the image comparison's -9.2% at 8 m, docs/lightskin.md).
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("canyon");
    const BiasSplit split = canyonBiasSplit(scene, 8.0f, 128, 64);
    printSplit(8.0f, split);
    INFO("cache points " << split.cachePoints << ", interpolation " << split.interpolation << ", eq. (9) "
                         << split.proxyMove << ", total " << split.total);
    CHECK(split.pixels > 1000);
    CHECK(split.caches > 50);
    CHECK((1.0 + split.cachePoints) * (1.0 + split.interpolation) * (1.0 + split.proxyMove) ==
          Approx(1.0 + split.total).epsilon(1e-9));
    CHECK(std::abs(split.total) < 0.15);
}

TEST_CASE("lightskin: the canyon's bias split at 8, 4 and 2 m", "[.lightskin-bias-split]")
{
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("canyon");
    std::printf("| d_eps | caches used | pixels | cache points | interpolation | eq. (9) | lightskin-full, traced |\n"
                "|---|---|---|---|---|---|---|\n");
    for (float distance : {8.0f, 4.0f, 2.0f}) {
        const BiasSplit split = canyonBiasSplit(scene, distance, 256, 256);
        printSplit(distance, split);
        CHECK(split.pixels > 0);
    }
}

TEST_CASE("lightskin: a scene without an RSM light renders no indirect light", "[lightskin][image]")
{
    test::ensureGLContext();
    Scene scene = test::cornerScene(0.0f, 1.0f);
    scene.lights.clear();
    for (const std::string technique : {"lightskin", "lightskin-full"}) {
        std::unique_ptr<Renderer> renderer =
            test::makeTechniqueRenderer(scene, technique, {{"rsm.size", "32"}, {"lightskin.cacheDistance", "0.5"}});
        const ImageRGBA32F image = test::renderIndirect(*renderer, scene.cameras[0], 16, 12);
        CHECK(meanLuminance(image) == 0.0);
    }
}
