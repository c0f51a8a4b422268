// Technique `smcir` (gl/techniques/vpl_technique.h): the GPU half of SMCIR against the CPU gather
// of the same VPL set (core/vpl/vpl_gather.h: Embree visibility), against the furnace's closed form,
// and the lazy shadow-map update against a full rebuild.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>

#include "core/scene/builtin_scenes.h"
#include "core/scene/scene_loader.h"
#include "core/trace/path_tracer.h"
#include "core/trace/ray_scene.h"
#include "core/util/params.h"
#include "core/vpl/vpl_gather.h"
#include "gl/renderer.h"
#include "gl/techniques/vpl_technique.h"
#include "glsl/shared/shadow_atlas.h"
#include "determinism.h"
#include "gl_test_context.h"
#include "measured.h"
#include "shared_assets.h"
#include "test_scenes.h"

using namespace vplgi;

namespace {

struct Rendered {
    ImageRGBA32F indirect; // radiance - direct, rows top to bottom
    VPLSet set;            // the set the last frame rendered
};

std::unique_ptr<Renderer> makeRenderer(const Scene& scene, const std::string& name, const Settings& settings)
{
    return test::makeTechniqueRenderer(scene, name, settings);
}

Rendered renderIndirect(Renderer& renderer, const Camera& camera, int width, int height)
{
    Rendered out;
    out.indirect = test::renderIndirect(renderer, camera, width, height);
    out.set = *dynamic_cast<VPLTechnique&>(renderer.technique()).renderedSet();
    return out;
}

using test::meanLuminance;

// The clamped path-traced reference the renderer's technique asks for (Technique::configureReference:
// SMCIR's and IR's clamp, untextured bounces and bounce cap), at pixel centres as the rasteriser samples.
ImageRGBA32F clampedReference(const Scene& scene, Renderer& renderer, const Camera& camera, int width, int height,
                              int spp)
{
    RayScene rays(scene);
    PathTracerParams reference;
    reference.mode = PathTracerParams::Mode::Clamped;
    reference.spp = spp;
    reference.jitterPixels = false;
    renderer.technique().configureReference(reference, {});
    return renderReference(scene, rays, camera, width, height, reference).image;
}

// Texels of valid slots' paraboloid maps that differ from a full rebuild of the rendered set.
std::size_t differingMapTexels(Renderer& renderer)
{
    const VPLTechnique& technique = dynamic_cast<VPLTechnique&>(renderer.technique());
    const VPLShadowMaps& lazy = *technique.shadowMaps();
    VPLShadowMaps full(test::shaders(), lazy.params());
    const VPLSet& set = *technique.renderedSet();
    std::vector<std::uint32_t> all(set.slots.size());
    for (std::uint32_t i = 0; i < all.size(); ++i)
        all[i] = i;
    full.update(renderer.gpuScene(), set, all);
    const ShadowAtlasLayout& layout = lazy.layout();
    const std::size_t texels = static_cast<std::size_t>(layout.layerSize) * layout.layerSize * layout.layers;
    std::vector<float> a(texels), b(texels);
    glGetTextureImage(lazy.maps().id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(a.size() * sizeof(float)), a.data());
    glGetTextureImage(full.maps().id(), 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(b.size() * sizeof(float)), b.data());
    // Invalid slots keep whatever they last held (the shading skips them): compare the valid ones.
    std::size_t differing = 0;
    const int size = lazy.params().mapSize;
    for (std::uint32_t slot = 0; slot < set.slots.size(); ++slot) {
        if (!set.slots[slot].valid) continue;
        const glm::ivec3 tile = shared::shadowAtlasTileFromIndex(static_cast<int>(slot), layout.tilesPerRow);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const std::size_t i = (static_cast<std::size_t>(tile.z) * layout.layerSize +
                                       static_cast<std::size_t>(tile.y * size + y)) * layout.layerSize +
                                      static_cast<std::size_t>(tile.x * size + x);
                differing += std::memcmp(&a[i], &b[i], sizeof(float)) != 0;
            }
    }
    return differing;
}

} // namespace

TEST_CASE("smcir: exhaustive shadow-map shading against the ray-traced gather of the same VPLs on cornell",
          "[image][smcir][numbers]")
{
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("cornell");
    const Camera& camera = scene.cameras[0];
    const int width = 64, height = 64;
    const Settings settings = {{"smcir.vplCount", "256"},        {"smcir.warmupIterations", "3"},
                               {"smcir.shading", "exhaustive"},  {"smcir.filter.enabled", "false"},
                               {"smcir.synchronous", "true"}};
    std::unique_ptr<Renderer> renderer = makeRenderer(scene, "smcir", settings);
    const Rendered gpu = renderIndirect(*renderer, camera, width, height);

    RayScene rays(scene);
    VPLGatherParams gather;
    gather.clampGeometry = test::vplClampGeometry(rays, 256);
    const ImageRGBA32F cpu = renderVPLGather(scene, rays, camera, width, height, gpu.set, gather);
    const double meanError = meanLuminance(gpu.indirect) / meanLuminance(cpu) - 1.0;
    const double pixelError = test::relativeL1(gpu.indirect, cpu);
    MEASURED("smcir cornell, 128^2 paraboloid maps vs ray-traced visibility (same 256 VPLs): mean "
             << meanError << ", mean |pixel difference| / mean " << pixelError);
    CHECK(meanLuminance(cpu) > 0.0);
    // Measured -0.45% and 0.78% (64 x 64, I = 256; -0.28% and 0.66% with the former depth bias of 2%
    // of the distance, which also let light through thin walls): limits 2.2x and 2.6x.
    CHECK(std::abs(meanError) < 0.01);
    CHECK(pixelError < 0.02);
}

namespace {

// A 2 cm slab, 40 cm high, standing on a floor, and a wall 1.5 m in front of it lit by a spot that
// lights nothing behind the slab: the VPLs on the wall (the only ones that reach behind the slab,
// over its top) leave the floor within 30 cm behind the slab in the slab's shadow (the shadow of
// the top edge from the wall's highest point falls 40 cm behind). `camera` looks at that floor.
Scene slabScene()
{
    Scene scene;
    scene.name = "slab";
    const int grey = test::addTestMaterial(scene, "grey", glm::vec3(0.7f));
    test::addTestQuad(scene, grey, {-2.0f, 0.0f, 2.0f}, {4.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -4.0f}); // floor, up
    test::addTestQuad(scene, grey, {-1.5f, 0.0f, 0.01f}, {3.0f, 0.0f, 0.0f}, {0.0f, 0.4f, 0.0f}); // slab front, +z
    test::addTestQuad(scene, grey, {1.5f, 0.0f, -0.01f}, {-3.0f, 0.0f, 0.0f}, {0.0f, 0.4f, 0.0f}); // slab back, -z
    test::addTestQuad(scene, grey, {-1.5f, 0.4f, 0.01f}, {3.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -0.02f}); // slab top
    test::addTestQuad(scene, grey, {2.0f, 0.0f, 1.5f}, {-4.0f, 0.0f, 0.0f}, {0.0f, 1.5f, 0.0f});   // wall, -z
    scene.lights.push_back(test::makeTestSpot("spot", {0.0f, 1.2f, 0.5f}, {0.0f, -0.4f, 1.0f}, 20.0f, 0.4f, 0.5f));
    test::addTestCamera(scene, "behind", {0.0f, 1.2f, -1.6f}, {0.0f, 0.0f, -0.2f});
    scene.validate();
    return scene;
}

} // namespace

TEST_CASE("ir: a slab standing on a floor keeps the floor behind it dark with shadow maps", "[image][ir][numbers]")
{
    // #23 part 4: a depth bias must not let light through a thin object where it touches the
    // floor. Exhaustive shading with the paraboloid maps against the CPU gather of the same VPLs
    // (Embree), on the floor within 30 cm behind the slab (the gather: exactly 0 there).
    test::ensureGLContext();
    const Scene scene = slabScene();
    const Camera& camera = scene.cameras[0];
    const int width = 96, height = 64;
    RayScene rays(scene);
    CameraRays cameraRays(camera, width, height);
    std::vector<int> region(static_cast<std::size_t>(width * height), 0); // 1 band, 2 floor beyond 70 cm
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Ray ray = cameraRays.at(x + 0.5, y + 0.5);
            const Hit hit = rays.intersect(ray);
            if (!hit.valid() || hit.instance != 0) continue; // the floor
            const glm::vec3 p = ray.origin + hit.t * ray.direction;
            region[static_cast<std::size_t>(y * width + x)] = (p.z > -0.3f && p.z < -0.01f) ? 1 : (p.z < -0.7f ? 2 : 0);
        }
    for (const char* bias : {"0.16", "0.64"}) { // the default, and the former 2% of the distance at 128^2
        std::unique_ptr<Renderer> renderer = makeRenderer(
            scene, "ir",
            {{"ir.vplCount", "1024"}, {"ir.bounces", "1"}, {"ir.shading", "exhaustive"}, {"ir.filter.enabled", "false"},
             {"ir.synchronous", "true"}, {"ir.depthBias", bias}});
        const Rendered gpu = renderIndirect(*renderer, camera, width, height);
        VPLGatherParams gather;
        gather.clampGeometry = test::vplClampGeometry(rays, 1024);
        const ImageRGBA32F cpu = renderVPLGather(scene, rays, camera, width, height, gpu.set, gather);
        double band[2] = {}, beyond[2] = {}, bandMax = 0.0;
        int bandCount = 0, beyondCount = 0;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const int r = region[static_cast<std::size_t>(y * width + x)];
                if (r == 0) continue;
                const double g = test::pixelLuminance(gpu.indirect.at(x, y)), c = test::pixelLuminance(cpu.at(x, y));
                if (r == 1) {
                    band[0] += g;
                    band[1] += c;
                    bandMax = std::max(bandMax, g);
                    ++bandCount;
                } else {
                    beyond[0] += g;
                    beyond[1] += c;
                    ++beyondCount;
                }
            }
        REQUIRE(bandCount > 100);
        REQUIRE(beyondCount > 100);
        REQUIRE(beyond[1] > 0.0);
        const double lit = beyond[1] / beyondCount;
        MEASURED("ir slab, depthBias " << bias << " texels: floor within 30 cm behind the slab (" << bandCount
                                       << " pixels), mean / the lit floor's mean: shadow maps " << band[0] / bandCount / lit
                                       << " (max " << bandMax / lit << "), Embree " << band[1] / bandCount / lit
                                       << "; lit floor, shadow maps / Embree - 1: " << beyond[0] / beyond[1] - 1.0);
        CHECK(band[1] == 0.0); // the geometry does what the test needs
        // Measured (128^2 maps): the default 0.08 of the lit floor's mean (max 1.0), the former bias
        // 1.03 (max 10.8): it lit the whole band. What the default leaves comes from the normal
        // offset (1 texel, 6 cm here, lifts the receiver towards the slab's top edge); with 512^2 maps
        // the band is exactly 0 with either bias. The lit floor beyond 70 cm is in the long, grazing
        // shadows of the VPLs low on the wall, where the same offset moves the shadow's edge:
        // +141% against Embree at 128^2, +31% at 512^2 (docs/smcir.md).
        if (std::string(bias) == "0.16") CHECK(band[0] / bandCount < 0.25 * lit);
        else CHECK(band[0] / bandCount > 0.5 * lit); // the test can tell the former bias
    }
}

TEST_CASE("smcir on cornell: the filter leaves no more of the 4x4 pattern on the grazing side walls than on the back wall",
          "[image][smcir][numbers]")
{
    // #23 part 3: relative L1 per wall of the interleaved, filtered image against exhaustive shading of
    // the same VPLs; the side walls are seen at |n.v| 0.1-0.35. Against the unfiltered exhaustive image
    // (the measure) the error is the 4x4 pattern the filter left plus the blur of the true
    // light; against the exhaustive image through the same filter it is the pattern alone.
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("cornell");
    const Camera& camera = scene.cameras[0];
    const int width = 128, height = 128;
    auto render = [&](Settings settings) {
        settings.insert(settings.begin(), {{"smcir.vplCount", "256"}, {"smcir.warmupIterations", "3"},
                                           {"smcir.synchronous", "true"}});
        std::unique_ptr<Renderer> renderer = makeRenderer(scene, "smcir", settings);
        return renderIndirect(*renderer, camera, width, height);
    };
    const Settings paperFilter = {{"smcir.filter.sigmaPlane", "3"}, {"smcir.filter.cosFloor", "1"},
                                  {"smcir.filter.normals", "shading"}};
    Settings exhaustive = {{"smcir.shading", "exhaustive"}};
    const Rendered exact = render({{"smcir.shading", "exhaustive"}, {"smcir.filter.enabled", "false"}});
    const Rendered exactOurs = render(exhaustive);
    exhaustive.insert(exhaustive.end(), paperFilter.begin(), paperFilter.end());
    const Rendered exactPaper = render(exhaustive);
    const Rendered ours = render({});
    const Rendered paper = render(paperFilter);
    // The same VPLs in all (the sampler does not depend on how the GPU shades).
    for (const Rendered* other : {&exactOurs, &exactPaper, &ours, &paper}) {
        REQUIRE(exact.set.slots.size() == other->set.slots.size());
        for (std::size_t i = 0; i < exact.set.slots.size(); ++i) {
            REQUIRE(exact.set.slots[i].valid == other->set.slots[i].valid);
            REQUIRE(exact.set.slots[i].position == other->set.slots[i].position);
        }
    }

    // Which wall each pixel sees (primary rays through pixel centres); only pixels whose 9 x 9
    // neighbourhood (the 8 x 8 window's reach) sees the same wall count, so edges do not dominate.
    RayScene rays(scene);
    CameraRays cameraRays(camera, width, height);
    std::vector<std::string> wall(static_cast<std::size_t>(width * height));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Hit hit = rays.intersect(cameraRays.at(x + 0.5, y + 0.5));
            if (!hit.valid()) continue;
            const Instance& instance = scene.instances[static_cast<std::size_t>(hit.instance)];
            wall[static_cast<std::size_t>(y * width + x)] = scene.meshes[static_cast<std::size_t>(instance.mesh)].name;
        }
    auto relativeL1 = [&](const ImageRGBA32F& image, const ImageRGBA32F& truth, const std::vector<std::string>& names) {
        double difference = 0.0, reference = 0.0;
        int count = 0;
        for (int y = 4; y < height - 4; ++y)
            for (int x = 4; x < width - 4; ++x) {
                const std::string& name = wall[static_cast<std::size_t>(y * width + x)];
                if (std::find(names.begin(), names.end(), name) == names.end()) continue;
                bool inside = true;
                for (int dy = -4; dy <= 4 && inside; ++dy)
                    for (int dx = -4; dx <= 4 && inside; ++dx)
                        inside = wall[static_cast<std::size_t>((y + dy) * width + x + dx)] == name;
                if (!inside) continue;
                difference += std::abs(test::pixelLuminance(image.at(x, y)) - test::pixelLuminance(truth.at(x, y)));
                reference += test::pixelLuminance(truth.at(x, y));
                ++count;
            }
        REQUIRE(count > 100);
        return difference / reference;
    };
    const std::vector<std::string> sides = {"red_wall", "green_wall"}, back = {"back_wall"};
    auto ratio = [&](const char* label, const ImageRGBA32F& image, const ImageRGBA32F& truth) {
        const double side = relativeL1(image, truth, sides), end = relativeL1(image, truth, back);
        MEASURED("smcir cornell 128^2, I = 256, " << label << ": relative L1 side walls " << side << ", back wall "
                                                  << end << ", ratio " << side / end);
        return side / end;
    };
    ratio("paper's filter vs exhaustive unfiltered", paper.indirect, exact.indirect);
    ratio("default filter vs exhaustive unfiltered", ours.indirect, exact.indirect);
    const double paperPattern = ratio("paper's filter vs exhaustive through it (pattern)", paper.indirect,
                                      exactPaper.indirect);
    const double oursPattern = ratio("default filter vs exhaustive through it (pattern)", ours.indirect,
                                     exactOurs.indirect);
    CHECK(paperPattern > 2.0); // the case the test is about exists
    CHECK(oursPattern < 1.5);  // #23 part 3's goal, on the pattern
}

TEST_CASE("smcir: after 30 moving-light frames the lazily updated maps equal a full rebuild", "[image][smcir]")
{
    test::ensureGLContext();
    Scene scene = makeBuiltinScene("cornell");
    const Camera& camera = scene.cameras[0];
    const Settings settings = {{"smcir.vplCount", "128"},  {"smcir.warmupIterations", "2"},
                               {"smcir.shadowMapSize", "32"}, {"smcir.synchronous", "true"},
                               {"smcir.shadowBatch", "48"}};
    // A point light inside the box that walks sideways (the box's own light is emissive geometry).
    Light lamp;
    lamp.name = "lamp";
    lamp.intensity = 0.5f;
    lamp.position = scene.worldBounds().center() + glm::vec3(0.0f, 0.25f, 0.0f) * scene.worldBounds().extent();
    scene.lights.push_back(lamp);
    std::unique_ptr<Renderer> renderer = makeRenderer(scene, "smcir", settings);
    const glm::vec3 start = scene.lights.back().position;
    const float step = 0.01f * scene.worldBounds().extent().x;
    std::size_t moved = 0;
    for (int frame = 0; frame < 30; ++frame) {
        scene.lights.back().position = start + glm::vec3(step * frame, 0.0f, 0.0f);
        renderer->markLightsChanged();
        renderer->renderFrame(camera, 16, 16);
        if (frame > 0) moved += dynamic_cast<VPLTechnique&>(renderer->technique()).renderedSet()->changed.size();
    }
    INFO("slots changed over 29 frames: " << moved);
    CHECK(moved > 0); // the lazy path was exercised
    CHECK(differingMapTexels(*renderer) == 0);
}

TEST_CASE("smcir: maps spread over frames (mapsPerFrame) complete to a full rebuild", "[image][smcir]")
{
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("cornell");
    const Settings settings = {{"smcir.vplCount", "128"},      {"smcir.warmupIterations", "2"},
                               {"smcir.shadowMapSize", "16"},  {"smcir.synchronous", "true"},
                               {"smcir.mapsPerFrame", "40"}, {"smcir.maxMoves", "0"}}; // a set that stays
    std::unique_ptr<Renderer> renderer = makeRenderer(scene, "smcir", settings);
    for (int frame = 0; frame < 3; ++frame)
        renderer->renderFrame(scene.cameras[0], 16, 16);
    CHECK(differingMapTexels(*renderer) > 0); // 120 of 128 maps made
    renderer->renderFrame(scene.cameras[0], 16, 16);
    CHECK(differingMapTexels(*renderer) == 0);
}

TEST_CASE("smcir on the furnace: interleaved shading averages to the CPU gather and to rho L_all",
          "[image][smcir][furnace][numbers]")
{
    // Inside a sphere G = 1/(4 R^2) between any two points and nothing is occluded, so every pixel
    // of an interleaving class sees the same value and an aligned image's mean is the full
    // estimator exactly (glsl/shared/vpl.h); clamping (G_max far above 1/(4R^2)) does not act.
    test::ensureGLContext();
    FurnaceParams furnace;
    furnace.rings = 48; // a quarter of the default triangles: the test's cost is the sampler and the maps
    furnace.segments = 96;
    const Scene scene = makeFurnace(furnace);
    const Camera& camera = scene.cameras[0];
    const int width = 32, height = 16; // multiples of the 4 x 4 tiles
    const Settings settings = {{"smcir.vplCount", "4096"},       {"smcir.warmupIterations", "10"},
                               {"smcir.radiosityBounces", "40"}, // 0.5^40: truncation far below 1%
                               {"smcir.radiositySamples", "64"}, {"smcir.shadowMapSize", "16"},
                               {"smcir.filter.enabled", "false"},        {"smcir.synchronous", "true"},
                               // After 10 frames the set is mostly fresh, where smcir.knnCountsSelf
                               // (the default) is -1/k by construction: eq. (7) self excluded here, as in
                               // the smcir-rt furnace test (tests/cpu/test_smcir_rt.cpp).
                               {"smcir.knnCountsSelf", "false"}};
    std::unique_ptr<Renderer> renderer = makeRenderer(scene, "smcir", settings);
    const Rendered gpu = renderIndirect(*renderer, camera, width, height);

    RayScene rays(scene);
    const ImageRGBA32F cpu = renderVPLGather(scene, rays, camera, width, height, gpu.set, VPLGatherParams{});
    const double expected = furnace.albedo * furnaceRadianceAll(furnace); // indirect = rho * L_all
    const double againstGather = meanLuminance(gpu.indirect) / meanLuminance(cpu) - 1.0;
    const double againstClosedForm = meanLuminance(gpu.indirect) / expected - 1.0;
    MEASURED("smcir furnace, I = 4096, interleaved: mean vs the CPU gather of the same VPLs " << againstGather
             << ", vs rho L_all " << againstClosedForm);
    // Measured 7.3e-5 (1.1e-5 before the geometric-normal test): float summation order, and VPLs
    // within ~1e-3 rad of a pixel's triangle plane, which the GPU's geometric normal (screen-space
    // derivatives, octahedral float16) and Embree's exact one put on different sides; 2.5x.
    CHECK(std::abs(againstGather) < 1.8e-4);
    // The sampler's own bias at I = 4096 (measured +3.3%; smcir-rt furnace test: +3.5%); 8% as there.
    CHECK(std::abs(againstClosedForm) < 0.08);
}

TEST_CASE("ir on the furnace (GPU): interleaved shading averages to the CPU gather and to the one-bounce closed form",
          "[image][ir][furnace][numbers]")
{
    // IR's GPU half on the furnace, as the smcir test above: with one bounce every path deposits
    // one VPL of flux Phi / I, so the estimate is L_2 = rho^2 I0 / (pi R^2) (MATH.md 3; the CPU
    // test "ir furnace: ..." checks the sampler alone) up to the tessellation and the GPU's floats.
    test::ensureGLContext();
    FurnaceParams furnace;
    furnace.rings = 48; // as the smcir test: the test's cost is the shadow maps
    furnace.segments = 96;
    const Scene scene = makeFurnace(furnace);
    const Camera& camera = scene.cameras[0];
    const int width = 32, height = 16; // multiples of the 4 x 4 tiles
    const Settings settings = {{"ir.vplCount", "4096"},   {"ir.bounces", "1"},          {"ir.clampScale", "0"},
                               {"ir.shadowMapSize", "16"}, {"ir.filter.enabled", "false"}, {"ir.synchronous", "true"}};
    std::unique_ptr<Renderer> renderer = makeRenderer(scene, "ir", settings);
    const Rendered gpu = renderIndirect(*renderer, camera, width, height);

    RayScene rays(scene);
    const ImageRGBA32F cpu = renderVPLGather(scene, rays, camera, width, height, gpu.set, VPLGatherParams{});
    const double expected = furnaceRadianceBounce(furnace, 2);
    const double againstGather = meanLuminance(gpu.indirect) / meanLuminance(cpu) - 1.0;
    const double againstClosedForm = meanLuminance(gpu.indirect) / expected - 1.0;
    MEASURED("ir furnace (GPU), I = 4096, one bounce, interleaved: mean vs the CPU gather of the same VPLs "
             << againstGather << ", vs rho^2 I0 / (pi R^2) " << againstClosedForm);
    // Measured 2.3e-5 against the gather (float summation order, GPU vs CPU) and +1.2e-3 against
    // the closed form (the 48-ring tessellation: G is 1/(4R^2) only on the true sphere; with one
    // bounce nothing random is left but the VPL positions). Bounds about 2.6x.
    CHECK(std::abs(againstGather) < 6e-5);
    CHECK(std::abs(againstClosedForm) < 3e-3);
}

TEST_CASE("ir: glossy indirect light on a metal floor like the matched path tracer", "[image][ir][numbers]")
{
    // The glossy receiver's BRDF on the GPU (GGX at every VPL) against the clamped one-bounce path
    // tracer that ir asks for (Technique::configureReference): only the wall sends light, and it is
    // Lambertian, so the VPLs' diffuse emission is exact (tests/common/test_scenes.h).
    test::ensureGLContext();
    const Scene scene = test::glossyFloorScene();
    const Camera& camera = scene.cameras[0];
    const int width = 48, height = 32;
    std::unique_ptr<Renderer> renderer =
        makeRenderer(scene, "ir", {{"ir.vplCount", "4096"}, {"ir.bounces", "1"}, {"ir.synchronous", "true"}});
    const Rendered gpu = renderIndirect(*renderer, camera, width, height);
    const ImageRGBA32F truth = clampedReference(scene, *renderer, camera, width, height, 2048);
    const double bias = meanLuminance(gpu.indirect) / meanLuminance(truth) - 1.0;
    const double error = test::relativeL1(gpu.indirect, truth);
    MEASURED("ir on the glossy metal floor (48x32, I = 4096, one bounce) vs the clamped path tracer (2048 spp): "
             "mean bias " << bias << ", relative L1 " << error);
    // Measured mean bias -0.1% and relative L1 0.142 (4096 VPLs on a GGX lobe of roughness 0.3:
    // per-pixel noise; the reference's own is far below; unfiltered -1.2% and 0.109, the paper's
    // isotropic filter +1.2% and 0.146, ours without its glossy exception +2.9% and 0.21:
    // gl/passes/bilateral_filter.h). Bounds: a lost or doubled glossy lobe (the floor has no other)
    // moves the mean by far more.
    CHECK(std::abs(bias) < 0.04);
    CHECK(error < 0.35);
}

TEST_CASE("the default scene (scenes/cornell.json, smcir) lights the ceiling with bounced light like the path tracer",
          "[image][smcir][numbers]")
{
    // ./scripts/run renders scenes/cornell.json: its technique and settings, paper defaults
    // (I = 2048, 100 warm-up frames). The ceiling sees no light but bounced light.
    test::ensureGLContext();
    const SceneDescription description = loadSceneFile(std::string(VPLGI_SOURCE_DIR) + "/scenes/cornell.json");
    REQUIRE(description.technique == "smcir");
    const Scene& scene = description.scene;
    const Camera& camera = scene.cameras[0];
    const int width = 48, height = 48;
    std::unique_ptr<Renderer> renderer = makeRenderer(scene, description.technique, description.settings);
    const Rendered gpu = renderIndirect(*renderer, camera, width, height);

    // The same part of the light transport from the path tracer: light reflected 1 to 3 times
    // before the primary hit (the sampler's 3 radiosity bounces), clamped and untextured as the
    // technique asks (Technique::configureReference).
    const ImageRGBA32F truth = clampedReference(scene, *renderer, camera, width, height, 1024);

    double smcir = 0.0, path = 0.0;
    const std::vector<glm::ivec2> ceiling = test::ceilingPixels(scene, camera, width, height);
    const int count = static_cast<int>(ceiling.size());
    for (const glm::ivec2& p : ceiling) {
        smcir += test::pixelLuminance(gpu.indirect.at(p.x, p.y));
        path += test::pixelLuminance(truth.at(p.x, p.y));
    }
    REQUIRE(count > 20);
    const double relative = smcir / path - 1.0;
    MEASURED("default scene: ceiling (" << count << " px) mean indirect radiance, smcir " << smcir / count
             << " vs path tracer " << path / count << ": " << relative);
    CHECK(smcir > 0.0);
    // Measured +11.4% with the default selection (smcir.rankRadiance = candidate, knnCountsSelf; +23%
    // with the paper's ranking by the rendered radiance and eq. (7) self excluded): SMCIR's own bias at
    // I = 2048 after 100 warm-up frames (docs/smcir.md, "Selection bias"), not the GPU half (same
    // VPLs: -0.3%, first test). It was +6.0% when the selection landed (9294568); which later commit
    // moved it is not bisected yet (issue 23). The run is deterministic, so the band only has to hold
    // code changes that keep the light transport: a lost tenth of the light (+0.3%) or a tenth more
    // (+22.5%) leaves it.
    CHECK(relative > 0.04);
    CHECK(relative < 0.19);
}

namespace {

struct FramesResult {
    std::vector<float> image; // the last frame's radiance
    VPLSet set;               // the set it rendered
};

// `frames` frames with a camera that moves, so that the sampler's steps do work.
FramesResult renderFrames(const std::string& technique, const Settings& settings, int frames)
{
    Scene scene = makeBuiltinScene("cornell");
    std::unique_ptr<Renderer> renderer = makeRenderer(scene, technique, settings);
    Camera camera = scene.cameras[0];
    for (int frame = 0; frame < frames; ++frame) {
        renderer->renderFrame(camera, 24, 24);
        camera.position.x += 0.01f;
        camera.target.x += 0.01f;
    }
    return {renderer->readRadiance().pixels, *dynamic_cast<VPLTechnique&>(renderer->technique()).renderedSet()};
}

bool sameSlots(const VPLSet& a, const VPLSet& b)
{
    if (a.slots.size() != b.slots.size()) return false;
    for (std::size_t i = 0; i < a.slots.size(); ++i) {
        const VPL& p = a.slots[i];
        const VPL& q = b.slots[i];
        if (p.valid != q.valid || p.position != q.position || p.normal != q.normal || p.radiance != q.radiance ||
            p.density != q.density)
            return false;
    }
    return true;
}

std::uint64_t hashOf(const std::vector<float>& values)
{
    return test::hashBytes(values.data(), values.size() * sizeof(float));
}

} // namespace

TEST_CASE("smcir and ir: the same seed gives the same image, with or without the worker thread", "[image][smcir][vpl-determinism]")
{
    test::ensureGLContext();
    for (const std::string technique : {"smcir", "ir"}) {
        const std::string p = technique + ".";
        Settings base = {{p + "vplCount", "64"}, {p + "shadowMapSize", "16"}};
        if (technique == "smcir") base.emplace_back("smcir.warmupIterations", "2");
        Settings sync = base;
        sync.emplace_back(p + "synchronous", "true");
        const FramesResult withWorker = renderFrames(technique, base, 4);
        CHECK(renderFrames(technique, base, 4).image == withWorker.image);
        CHECK(renderFrames(technique, sync, 4).image == renderFrames(technique, sync, 4).image);
        // The worker's frame n renders the set of the synchronous frame n - 1 (core/vpl/vpl_pipeline.h;
        // the images differ by the camera of the frame).
        CHECK(sameSlots(renderFrames(technique, sync, 3).set, withWorker.set));
        CHECK(test::recordHash(technique, hashOf(withWorker.image)));
    }
}

TEST_CASE("smcir on the shared CornellBox.glb (millimetres): shadow maps agree with rays, indirect with the path tracer",
          "[image][smcir][shared][numbers]")
{
    // A scene made elsewhere, in millimetres, lit by an emissive quad: the shadow maps' near/far
    // planes, the clamp and the biases all scale with the scene; a leak through the box's walls or a
    // self-shadowing bias would show against Embree's visibility of the same VPLs.
    const std::optional<std::filesystem::path> file = test::findSharedAsset("scenes/cornell-box/CornellBox.glb");
    if (!file) return;
    test::ensureGLContext();
    const Scene scene = loadGltf(file->string());
    const Camera& camera = scene.cameras[0];
    const int width = 48, height = 48;
    const Settings settings = {{"smcir.vplCount", "512"}, {"smcir.warmupIterations", "10"},
                               {"smcir.shading", "exhaustive"}, {"smcir.filter.enabled", "false"},
                               {"smcir.synchronous", "true"},
                               // 10 frames: a mostly fresh set, where the default smcir.knnCountsSelf
                               // is -1/k (-25% at I = 512) by construction; self excluded, as measured.
                               {"smcir.knnCountsSelf", "false"}};
    std::unique_ptr<Renderer> renderer = makeRenderer(scene, "smcir", settings);
    const Rendered gpu = renderIndirect(*renderer, camera, width, height);

    RayScene rays(scene);
    VPLGatherParams gather;
    gather.clampGeometry = clampGeometryFor(2.0f, 512, rays.sceneScale());
    const ImageRGBA32F cpu = renderVPLGather(scene, rays, camera, width, height, gpu.set, gather);
    PathTracerParams reference;
    reference.mode = PathTracerParams::Mode::Clamped;
    reference.spp = 512;
    reference.jitterPixels = false;
    renderer->technique().configureReference(reference, {});
    const ImageRGBA32F truth = renderReference(scene, rays, camera, width, height, reference).image;

    const double againstRays = meanLuminance(gpu.indirect) / meanLuminance(cpu) - 1.0;
    const double pixelsAgainstRays = test::relativeL1(gpu.indirect, cpu);
    const double againstPath = meanLuminance(gpu.indirect) / meanLuminance(truth) - 1.0;
    MEASURED("smcir on CornellBox.glb (I = 512): mean vs the same VPLs ray-traced " << againstRays
             << " (mean |pixel difference| / mean " << pixelsAgainstRays << "), mean vs the path tracer "
             << againstPath);
    CHECK(meanLuminance(truth) > 0.0);
    // Measured -0.38% and 1.04% (-0.31% and 0.97% with the former depth bias): limits about 2.6x and 3x.
    CHECK(std::abs(againstRays) < 0.01);
    CHECK(pixelsAgainstRays < 0.03);
    // Measured +18.2% (+20.0% with the paper's ranking by the rendered radiance): SMCIR's own bias at
    // I = 512 after 10 frames, which moves with the sampler ("SMCIR without drift"), against the
    // matched reference, whose VPL vertex reflects the diffuse lobe only as the
    // VPLs do (reference.diffuseVertices = 1). This box's dielectrics (roughness 0.5, F0 0.04) also
    // reflect specularly there: the old reference kept that, 13% more light, which hid most of the
    // bias (+3.9%; +23% before new VPLs got radiance estimates independent of their selection). The
    // band is one-sided around the measured bias; a wrong unit or a missing bounce (40-50% of this
    // light) leaves it.
    CHECK(againstPath > 0.05);
    CHECK(againstPath < 0.35);
}
