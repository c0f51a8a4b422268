// Renders of the `direct` technique against closed forms and CPU evaluations:
//  - furnace: direct radiance inside the sphere is rho I0 / (pi R^2) everywhere (MATH.md section 3);
//  - cornell: pixels match the CPU evaluation of the same emitters with the same BRDF and Embree
//    visibility (core/surface.cpp);
//  - the shared glTF scenes load and render (skipped when ../shared is absent).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include "core/builtin_scenes.h"
#include "core/ray_scene.h"
#include "core/scene_loader.h"
#include "core/surface.h"
#include "gl/renderer.h"
#include "gl_test_context.h"

using namespace vplgi;

namespace {

std::unique_ptr<Renderer> makeRenderer(const Scene& scene, const RendererParams& params = {})
{
    test::ensureGLContext();
    return std::make_unique<Renderer>(test::shaders(), scene, params, createTechnique("direct"));
}

// The primary ray through the centre of pixel (x, y) (y down), as the rasterizer samples it.
Ray pixelRay(const Camera& camera, int width, int height, int x, int y)
{
    glm::mat4 worldFromClip = glm::inverse(camera.clipFromView(float(width) / float(height)) * camera.viewFromWorld());
    glm::vec2 ndc((x + 0.5f) / width * 2.0f - 1.0f, 1.0f - (y + 0.5f) / height * 2.0f);
    glm::vec4 nearPoint = worldFromClip * glm::vec4(ndc, -1.0f, 1.0f);
    glm::vec4 farPoint = worldFromClip * glm::vec4(ndc, 1.0f, 1.0f);
    Ray ray;
    ray.origin = camera.position;
    ray.direction = glm::normalize(glm::vec3(farPoint) / farPoint.w - glm::vec3(nearPoint) / nearPoint.w);
    return ray;
}

} // namespace

TEST_CASE("furnace: direct radiance equals rho I0 / (pi R^2)", "[image][furnace]")
{
    FurnaceParams params;
    params.radius = 1.5f;
    params.albedo = 0.6f;
    params.intensity = 2.0f;
    Scene scene = makeFurnace(params);
    auto renderer = makeRenderer(scene);
    renderer->renderFrame(scene.cameras[0], 96, 64);
    ImageRGBA32F image = renderer->readRadiance();
    const double expected = furnaceRadianceBounce(params, 1);
    REQUIRE(expected == Approx(0.6 * 2.0 / (3.14159265358979 * 1.5 * 1.5)));
    double sum = 0.0, maxDeviation = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            sum += image.at(x, y)[1];
            maxDeviation = std::max(maxDeviation, std::abs(image.at(x, y)[1] / expected - 1.0));
        }
    const double mean = sum / (image.width * image.height);
    INFO("mean " << mean << " expected " << expected << " max pixel deviation " << maxDeviation);
    if (std::abs(mean / expected - 1.0) > 0.02) test::saveTestImage("furnace-direct-actual", image);
    CHECK(mean == Approx(expected).epsilon(0.02));
    CHECK(maxDeviation < 0.05); // every pixel, not just the mean
}

TEST_CASE("cornell: direct light matches the CPU evaluation at floor and wall pixels", "[image][cornell]")
{
    Scene scene = makeBuiltinScene("cornell");
    RendererParams params;
    params.shadow.cubeSize = 256;
    auto renderer = makeRenderer(scene, params);
    const int width = 128, height = 128;
    const Camera& camera = scene.cameras[0];
    renderer->renderFrame(camera, width, height);
    ImageRGBA32F gpu = renderer->readDirect();
    RayScene rays(scene);
    const DirectLightSet& lights = renderer->lights();

    ImageRGBA32F cpu = gpu;
    int compared = 0, within = 0;
    double worst = 0.0;
    // Chosen pixels, lit and away from shadow edges: floor, back wall (centre, upper corners, right of
    // the tall block), green and red walls, the tall block's front face.
    const std::vector<glm::ivec2> chosen = {{30, 115}, {64, 40}, {85, 60},  {30, 30}, {100, 30},
                                            {120, 64}, {110, 95}, {8, 64}, {45, 80}, {40, 110}};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            Ray ray = pixelRay(camera, width, height, x, y);
            Hit hit = rays.intersect(ray);
            glm::vec3 value(0.0f);
            if (hit.valid()) {
                SurfacePoint s = surfaceAt(scene, hit, -ray.direction);
                value = s.emission + evaluateDirectLight(rays, lights, s, -ray.direction);
            }
            float* c = cpu.at(x, y);
            c[0] = value.r, c[1] = value.g, c[2] = value.b;
        }
    for (glm::ivec2 p : chosen) {
        const float* g = gpu.at(p.x, p.y);
        const float* c = cpu.at(p.x, p.y);
        double lumG = 0.2126 * g[0] + 0.7152 * g[1] + 0.0722 * g[2];
        double lumC = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        INFO("pixel " << p.x << "," << p.y << " gpu " << lumG << " cpu " << lumC);
        REQUIRE(lumC > 0.0);
        double error = std::abs(lumG / lumC - 1.0);
        worst = std::max(worst, error);
        ++compared;
        if (error <= 0.05) ++within;
        CHECK(error <= 0.05);
    }
    // Over the whole image (shadow edges included) most pixels must agree as well.
    int agreeing = 0, lit = 0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            double lumG = gpu.at(x, y)[1], lumC = cpu.at(x, y)[1];
            if (lumC <= 1e-4) continue;
            ++lit;
            if (std::abs(lumG / lumC - 1.0) <= 0.05) ++agreeing;
        }
    INFO("whole image: " << agreeing << " of " << lit << " lit pixels within 5%");
    if (within != compared || agreeing < 0.9 * lit) {
        test::saveTestImage("cornell-direct-gpu", gpu);
        test::saveTestImage("cornell-direct-cpu", cpu);
    }
    CHECK(agreeing >= 0.9 * lit);
}

TEST_CASE("shared glTF scenes load and render", "[image][shared]")
{
    const std::filesystem::path dir = std::filesystem::path(VPLGI_SHARED_DIR) / "scenes";
    if (!std::filesystem::is_directory(dir)) {
        WARN("skipped: " << dir.string() << " is absent");
        return;
    }
    int rendered = 0;
    for (const auto& folder : std::filesystem::directory_iterator(dir)) {
        if (!folder.is_directory()) continue;
        for (const auto& file : std::filesystem::directory_iterator(folder.path())) {
            if (file.path().extension() != ".glb") continue;
            INFO(file.path().string());
            Scene scene = loadGltf(file.path().string());
            auto renderer = makeRenderer(scene);
            renderer->renderFrame(scene.cameras[0], 64, 48);
            ImageRGBA32F image = renderer->readRadiance();
            bool finite = true;
            for (float v : image.pixels) finite = finite && std::isfinite(v);
            CHECK(finite);
            ++rendered;
        }
    }
    CHECK(rendered >= 6);
}
