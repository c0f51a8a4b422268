// Renders of the `direct` technique against closed forms and CPU evaluations:
//  - furnace: direct radiance inside the sphere is rho I0 / (pi R^2) everywhere (MATH.md section 3);
//  - cornell: pixels match the CPU evaluation of the same emitters with the same BRDF and Embree
//    visibility (core/scene/surface.cpp);
//  - the shared glTF scenes load and render (tests/common/shared_assets.h: skipped when ../shared is
//    absent, failed when CI=true).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/scene/builtin_scenes.h"
#include "core/trace/ray_scene.h"
#include "core/scene/scene_loader.h"
#include "core/scene/surface.h"
#include "glsl/shared/normals.h"
#include "core/util/params.h"
#include "gl/renderer.h"
#include "gl_test_context.h"
#include "measured.h"
#include "shared_assets.h"
#include "test_scenes.h"

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

// The CPU evaluation of the renderer's direct light (same emitters, BRDF, Embree visibility).
ImageRGBA32F cpuDirectImage(const Scene& scene, const DirectLightSet& lights, const Camera& camera, int width, int height)
{
    RayScene rays(scene);
    ImageRGBA32F image;
    image.width = width;
    image.height = height;
    image.pixels.assign(static_cast<std::size_t>(width) * height * 4, 1.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            Ray ray = pixelRay(camera, width, height, x, y);
            Hit hit = rays.intersect(ray);
            glm::vec3 value(0.0f);
            if (hit.valid()) {
                SurfacePoint s = surfaceAt(scene, hit, -ray.direction);
                value = s.emission + evaluateDirectLight(rays, lights, s, -ray.direction);
            }
            float* c = image.at(x, y);
            c[0] = value.r, c[1] = value.g, c[2] = value.b;
        }
    return image;
}

double luminance(const float* c)
{
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

// Fraction of pixels lit on the CPU whose luminance agrees within `tolerance` (relative).
double agreement(const ImageRGBA32F& gpu, const ImageRGBA32F& cpu, double tolerance, int* litCount = nullptr)
{
    int agreeing = 0, lit = 0;
    for (int y = 0; y < gpu.height; ++y)
        for (int x = 0; x < gpu.width; ++x) {
            double g = luminance(gpu.at(x, y)), c = luminance(cpu.at(x, y));
            if (c <= 1e-4) continue;
            ++lit;
            if (std::abs(g / c - 1.0) <= tolerance) ++agreeing;
        }
    if (litCount) *litCount = lit;
    return lit > 0 ? static_cast<double>(agreeing) / lit : 0.0;
}

// An axis-aligned box with outward faces (flat normals, counter-clockwise seen from outside).
Mesh boxMesh(glm::vec3 lower, glm::vec3 upper, int material)
{
    Mesh mesh;
    mesh.material = material;
    const glm::vec3 c[8] = {{lower.x, lower.y, lower.z}, {upper.x, lower.y, lower.z}, {upper.x, upper.y, lower.z},
                            {lower.x, upper.y, lower.z}, {lower.x, lower.y, upper.z}, {upper.x, lower.y, upper.z},
                            {upper.x, upper.y, upper.z}, {lower.x, upper.y, upper.z}};
    const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}};
    for (const auto& f : faces) {
        const std::uint32_t base = static_cast<std::uint32_t>(mesh.vertices.size());
        const glm::vec3 n = glm::normalize(glm::cross(c[f[1]] - c[f[0]], c[f[2]] - c[f[0]]));
        for (int k = 0; k < 4; ++k) {
            Vertex v;
            v.position = c[f[k]];
            v.normal = n;
            mesh.vertices.push_back(v);
        }
        for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) mesh.indices.push_back(base + i);
    }
    return mesh;
}

} // namespace

TEST_CASE("furnace: direct radiance equals rho I0 / (pi R^2)", "[image][furnace][numbers]")
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
    MEASURED("furnace direct (GPU): mean relative deviation " << mean / expected - 1.0 << ", worst pixel "
                                                              << maxDeviation);
    // Tolerances 2-3x the measured: mean -3.0e-4, worst pixel 6.3e-4 (the facets of the 96 x 192
    // sphere and float shading; llvmpipe).
    if (std::abs(mean / expected - 1.0) > 7.5e-4 || maxDeviation > 1.5e-3)
        test::saveTestImage("furnace-direct-actual", image);
    CHECK(mean == Approx(expected).epsilon(7.5e-4));
    CHECK(maxDeviation < 1.5e-3); // every pixel, not just the mean
}

TEST_CASE("cornell: direct light matches the CPU evaluation at floor and wall pixels", "[image][cornell][numbers]")
{
    Scene scene = makeBuiltinScene("cornell");
    RendererParams params;
    params.shadow.cubeSize = 256;
    auto renderer = makeRenderer(scene, params);
    const int width = 128, height = 128;
    const Camera& camera = scene.cameras[0];
    renderer->renderFrame(camera, width, height);
    ImageRGBA32F gpu = renderer->readDirect();
    const ImageRGBA32F cpu = cpuDirectImage(scene, renderer->lights(), camera, width, height);
    int compared = 0, within = 0;
    double worst = 0.0;
    // Chosen pixels, lit and away from shadow edges: floor, back wall (centre, upper corners, right of
    // the tall block), green and red walls, the tall block's front face.
    const std::vector<glm::ivec2> chosen = {{30, 115}, {64, 40}, {85, 60},  {30, 30}, {100, 30},
                                            {120, 64}, {110, 95}, {8, 64}, {45, 80}, {40, 110}};
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
        // Measured: worst 4.3e-4 over the ten pixels (same emitters and BRDF, float shading, and a
        // shadow-map lookup that agrees with the ray away from edges); 2.3x that.
        if (error <= 1e-3) ++within;
        CHECK(error <= 1e-3);
    }
    // Over the whole image most pixels agree as well. What disagrees is on shadow edges (a 256^2
    // cube map against exact ray visibility) and at sub-pixel geometry: measured 91.3% of lit
    // pixels within 1% (93.8% within 5%). Required: 85% within 1%, i.e. at most 1.7x the measured
    // share of disagreeing pixels (a few more edge pixels on another rasterizer are not a bug).
    int lit = 0;
    const double agreeing = agreement(gpu, cpu, 0.01, &lit);
    MEASURED("cornell direct GPU vs CPU: worst relative difference at the chosen pixels " << worst << "; "
             << agreeing * 100.0 << "% of " << lit << " lit pixels within 1%, " << agreement(gpu, cpu, 0.05) * 100.0
             << "% within 5%");
    if (within != compared || agreeing < 0.85) {
        test::saveTestImage("cornell-direct-gpu", gpu);
        test::saveTestImage("cornell-direct-cpu", cpu);
    }
    CHECK(agreeing >= 0.85);
}

TEST_CASE("spot and directional lights and glossy surfaces match the CPU evaluation", "[image][lights][numbers]")
{
    // A floor, two boxes (one glossy metal, one glossy dielectric), a spot light and a sun.
    Scene scene;
    scene.name = "spot-and-sun";
    auto material = [&](glm::vec3 color, float metallic, float roughness, float specular) {
        Material m;
        m.baseColor = glm::vec4(color, 1.0f);
        m.metallic = metallic;
        m.roughness = roughness;
        m.specular = specular;
        scene.materials.push_back(m);
        return static_cast<int>(scene.materials.size()) - 1;
    };
    auto addBox = [&](glm::vec3 lower, glm::vec3 upper, int mat) {
        scene.meshes.push_back(boxMesh(lower, upper, mat));
        scene.instances.push_back(Instance{static_cast<int>(scene.meshes.size()) - 1, glm::mat4(1.0f)});
    };
    addBox({-5, -0.1f, -5}, {5, 0, 5}, material({0.6f, 0.6f, 0.6f}, 0.0f, 1.0f, 0.0f));
    addBox({-1.5f, 0, -1}, {-0.5f, 1.2f, 0}, material({0.9f, 0.6f, 0.3f}, 1.0f, 0.35f, 1.0f));
    addBox({0.5f, 0, -0.5f}, {1.3f, 0.6f, 0.3f}, material({0.2f, 0.4f, 0.8f}, 0.0f, 0.3f, 1.0f));
    scene.lights.push_back(test::makeTestSpot("spot", {0.5f, 3.0f, 1.0f}, {-0.2f, -1.0f, -0.4f}, 6.0f, 0.35f, 0.6f));
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.5f, -1.0f, -0.3f));
    sun.color = {1.0f, 0.9f, 0.8f};
    sun.intensity = 1.5f;
    scene.lights.push_back(sun);
    Camera camera;
    camera.name = "default";
    camera.position = {0.5f, 2.5f, 4.5f};
    camera.target = {0.0f, 0.3f, -0.3f};
    camera.fovY = 0.9f;
    scene.cameras.push_back(camera);
    scene.validate();

    RendererParams params;
    params.shadow.mapSize = 4096;
    auto renderer = makeRenderer(scene, params);
    const int width = 128, height = 96;
    renderer->renderFrame(camera, width, height);
    const ImageRGBA32F gpu = renderer->readDirect();
    const ImageRGBA32F cpu = cpuDirectImage(scene, renderer->lights(), camera, width, height);
    int lit = 0;
    // Measured: 98.7% of lit pixels within 1% (the rest on shadow edges: a 4096^2 map against
    // rays); required 97%, at most 2.3x the measured share of disagreeing pixels.
    const double agreeing = agreement(gpu, cpu, 0.01, &lit);
    MEASURED("spot and sun GPU vs CPU: " << agreeing * 100.0 << "% of " << lit << " lit pixels within 1%, "
                                         << agreement(gpu, cpu, 0.05) * 100.0 << "% within 5%");
    if (agreeing < 0.97) {
        test::saveTestImage("spot-sun-gpu", gpu);
        test::saveTestImage("spot-sun-cpu", cpu);
    }
    CHECK(lit > width * height / 2);
    CHECK(agreeing >= 0.97);
}

TEST_CASE("moving one light re-renders only its shadow cube, with the same image as a fresh render",
          "[image][shadows]")
{
    FurnaceParams params;
    params.rings = 24;
    params.segments = 48;
    Scene scene = makeFurnace(params);
    // An occluder inside the sphere so that shadows matter, and two more point lights.
    const Mesh box = boxMesh({-0.2f, -0.2f, -0.6f}, {0.2f, 0.2f, -0.4f}, scene.meshes[0].material);
    scene.meshes.push_back(box);
    scene.instances.push_back(Instance{1, glm::mat4(1.0f)});
    for (glm::vec3 p : {glm::vec3(0.3f, 0.2f, 0.0f), glm::vec3(-0.3f, -0.1f, 0.2f)}) {
        Light l = scene.lights[0];
        l.name = "extra" + std::to_string(scene.lights.size());
        l.position = p;
        scene.lights.push_back(l);
    }
    auto renderer = makeRenderer(scene);
    const Camera camera = scene.cameras[0];
    renderer->renderFrame(camera, 64, 48);
    CHECK(renderer->lastRenderedShadowCubes() == 3);
    scene.lights[1].position = glm::vec3(0.1f, 0.3f, -0.1f);
    renderer->markLightsChanged();
    renderer->renderFrame(camera, 64, 48);
    CHECK(renderer->lastRenderedShadowCubes() == 1);
    const ImageRGBA32F updated = renderer->readDirect();

    auto fresh = makeRenderer(scene);
    fresh->renderFrame(camera, 64, 48);
    const ImageRGBA32F expected = fresh->readDirect();
    CHECK(updated.pixels == expected.pixels);
}

TEST_CASE("G-buffer normals: the geometric one is Embree's triangle, the interpolated one the vertex "
          "normals without the normal map", "[image][gbuffer][numbers]")
{
    // The glossy room: a normal-mapped floor and block (shading != interpolated normal) and a brass
    // sphere of 24 x 48 quads (interpolated != geometric normal). Per pixel, the G-buffer's
    // octahedral normals against the CPU at the Embree hit through the pixel centre: surfaceAt's
    // geometric normal (on the shading normal's side) and, with the untextured table (no normal
    // map), its vertex-interpolated normal.
    Scene scene = makeBuiltinScene("glossy");
    auto renderer = makeRenderer(scene);
    const int width = 96, height = 54;
    const Camera& camera = scene.cameras[0];
    renderer->renderFrame(camera, width, height);
    const gl::Texture& normals = renderer->gbuffer().surfaceNormals();
    std::vector<glm::vec4> texels(static_cast<std::size_t>(width) * height);
    glGetTextureImage(normals.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)),
                      texels.data());
    RayScene rays(scene);
    const UntexturedMaterials untextured = computeUntexturedMaterials(scene);
    int compared = 0, geometricWithin = 0, interpolatedWithin = 0, curved = 0, bumped = 0;
    int curvedWithin = 0, bumpedWithin = 0; // the pixels where a swapped normal would show
    std::vector<double> geometricErrors, interpolatedErrors;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Ray ray = pixelRay(camera, width, height, x, y);
            const Hit hit = rays.intersect(ray);
            if (!hit.valid()) continue;
            const SurfacePoint textured = surfaceAt(scene, hit, -ray.direction);
            const SurfacePoint plain = surfaceAt(scene, hit, -ray.direction, &untextured);
            const glm::vec4 t = texels[static_cast<std::size_t>((height - 1 - y) * width + x)];
            const glm::vec3 geometric = shared::octDecode(glm::vec2(t.x, t.y));
            const glm::vec3 interpolated = shared::octDecode(glm::vec2(t.z, t.w));
            const double eg = std::acos(std::clamp(double(glm::dot(geometric, textured.geometricNormal)), -1.0, 1.0));
            const double ei = std::acos(std::clamp(double(glm::dot(interpolated, plain.normal)), -1.0, 1.0));
            ++compared;
            // Measured (below): the few pixels whose centre lies on another triangle for the
            // rasterizer than for Embree disagree by a triangle's turn; 5e-3 rad is ~3x the
            // octahedral float16 round trip.
            if (eg <= 5e-3) ++geometricWithin;
            if (ei <= 5e-3) ++interpolatedWithin;
            geometricErrors.push_back(eg);
            interpolatedErrors.push_back(ei);
            if (glm::dot(plain.normal, textured.geometricNormal) < 0.9999f) {
                ++curved;
                if (eg <= 5e-3 && ei <= 5e-3) ++curvedWithin;
            }
            if (glm::dot(plain.normal, textured.normal) < 0.9999f) {
                ++bumped;
                if (eg <= 5e-3 && ei <= 5e-3) ++bumpedWithin;
            }
        }
    std::sort(geometricErrors.begin(), geometricErrors.end());
    std::sort(interpolatedErrors.begin(), interpolatedErrors.end());
    const auto median = [](const std::vector<double>& v) { return v[v.size() / 2]; };
    MEASURED("G-buffer normals on the glossy room, " << compared << " pixels (" << curved << " where the "
             << "interpolated normal leaves the triangle's plane, " << bumped << " where the normal map tilts it): "
             << "geometric within 5e-3 rad " << 100.0 * geometricWithin / compared << "% (median "
             << median(geometricErrors) << " rad), interpolated " << 100.0 * interpolatedWithin / compared
             << "% (median " << median(interpolatedErrors) << " rad); both within on " << curvedWithin
             << " of the curved and " << bumpedWithin << " of the bumped pixels");
    REQUIRE(compared > width * height / 2);
    // The scene exercises both differences (else the test could not tell the normals apart):
    // measured 51 and 1161 pixels, required half of that.
    CHECK(curved > 25);
    CHECK(bumped > 580);
    // Measured: all but 2 pixels (triangle edges) within; required 97% overall, and 90% on the
    // curved and bumped pixels alone, where a normal written in the other's place would fail.
    CHECK(geometricWithin >= 0.97 * compared);
    CHECK(interpolatedWithin >= 0.97 * compared);
    CHECK(curvedWithin >= 0.9 * curved);
    CHECK(bumpedWithin >= 0.9 * bumped);
}

TEST_CASE("shared glTF scenes load and render: geometry in view, textures drawn, lit where they have light",
          "[image][shared][numbers]")
{
    const std::optional<std::filesystem::path> dir = test::findSharedAsset("scenes");
    if (!dir) return;
    test::ensureGLContext();
    int rendered = 0;
    for (const auto& folder : std::filesystem::directory_iterator(*dir)) {
        if (!folder.is_directory()) continue;
        for (const auto& file : std::filesystem::directory_iterator(folder.path())) {
            if (file.path().extension() != ".glb") continue;
            INFO(file.path().string());
            const Scene scene = loadGltf(file.path().string());
            // The G-buffer's albedo view: non-black wherever a surface was drawn, whatever the light
            // (most of these glTFs have none of their own), so a lost mesh, a wrong transform or an
            // unreadable texture shows as missing coverage.
            RendererParams params;
            ParamSetter setter(Settings{{"renderer.display", "albedo"}});
            params.visitParams(setter);
            setter.finish();
            Renderer renderer(test::shaders(), scene, params, createTechnique("direct"));
            renderer.renderFrame(scene.cameras[0], 64, 48);
            const ImageRGBA8 albedo = renderer.readDisplay();
            const ImageRGBA32F radiance = renderer.readRadiance();
            bool finite = true;
            int covered = 0, lit = 0;
            for (std::size_t i = 0; i < radiance.pixels.size(); i += 4) {
                for (int c = 0; c < 3; ++c) finite = finite && std::isfinite(radiance.pixels[i + c]);
                lit += radiance.pixels[i] + radiance.pixels[i + 1] + radiance.pixels[i + 2] > 0.0f ? 1 : 0;
                covered += albedo.pixels[i] + albedo.pixels[i + 1] + albedo.pixels[i + 2] > 0 ? 1 : 0;
            }
            const double pixels = static_cast<double>(radiance.width) * radiance.height;
            bool hasLight = !scene.lights.empty();
            for (const Material& m : scene.materials) hasLight = hasLight || m.isEmissive();
            MEASURED(file.path().filename().string() << ": surfaces drawn in " << covered / pixels
                     << " of the pixels, lit " << lit / pixels << (hasLight ? "" : " (no light of its own)"));
            CHECK(finite);
            // The default camera frames the scene's bounds from outside (single-sided walls facing in
            // are culled): measured coverage 0.094-0.34 (docs/testing.md), 4% is below all of them
            // at 2.4x the smallest and far above a black image; CornellBox.glb (its emissive quad)
            // is lit in 0.25 of the pixels, the bound 2.5x below.
            CHECK(covered > 0.04 * pixels);
            if (hasLight) CHECK(lit > 0.1 * pixels);
            ++rendered;
        }
    }
    CHECK(rendered >= 6);
}
