// RSMPass (gl/passes/rsm_pass.h) against a CPU rasterisation of a plane (texel centres through the
// inverse view-projection), closed forms for the flux a spot cone and a directional light put on
// the plane, a CPU twin of the mip reduction, a half-empty RSM whose mips must stay on the surface,
// and the determinism of the mips (bit-identical over runs; tests/gl/rsm_threads.sh compares
// LP_NUM_THREADS=1 and 2).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "core/util/error.h"
#include "core/util/params.h"
#include "gl/gpu_scene.h"
#include "gl/passes/rsm_pass.h"
#include "determinism.h"
#include "gl_test_context.h"
#include "glsl/shared/light_view.h"
#include "glsl/shared/lights.h"
#include "glsl/shared/normals.h"
#include "glsl/shared/rsm.h"
#include "measured.h"

using namespace vplgi;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Level `level`, layer `layer` of an RSM attachment, RGBA rows bottom to top.
std::vector<glm::vec4> readLevel(const gl::Texture& texture, int level, int layer, int size)
{
    std::vector<glm::vec4> texels(static_cast<std::size_t>(size * size));
    glGetTextureSubImage(texture.id(), level, 0, 0, layer, size, size, 1, GL_RGBA, GL_FLOAT,
                         static_cast<GLsizei>(texels.size() * sizeof(glm::vec4)), texels.data());
    return texels;
}

using Level = std::vector<std::vector<glm::vec4>>; // [attachment][texel]

Level readAll(const RSMPass& pass, int level, int layer)
{
    const int size = pass.target().width() >> level;
    Level out;
    for (int a = 0; a < shared::kRSMAttachmentCount; ++a)
        out.push_back(readLevel(pass.target().color(a), level, layer, size));
    return out;
}

// CPU twin of glsl/passes/rsm_downsample.comp: the same weights and summation order.
Level downsampleOnCPU(const Level& source, int sourceSize)
{
    const int size = sourceSize / 2;
    Level out(shared::kRSMAttachmentCount, std::vector<glm::vec4>(static_cast<std::size_t>(size * size)));
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const std::size_t child[4] = {static_cast<std::size_t>(2 * y * sourceSize + 2 * x),
                                          static_cast<std::size_t>(2 * y * sourceSize + 2 * x + 1),
                                          static_cast<std::size_t>((2 * y + 1) * sourceSize + 2 * x),
                                          static_cast<std::size_t>((2 * y + 1) * sourceSize + 2 * x + 1)};
            float weight[4];
            float total = 0.0f;
            for (int i = 0; i < 4; ++i) {
                const glm::vec4 f = source[shared::kRSMFlux][child[i]];
                weight[i] = f.r + f.g + f.b;
                total += weight[i];
            }
            if (!(total > 0.0f)) {
                total = 0.0f;
                for (int i = 0; i < 4; ++i) {
                    weight[i] = source[shared::kRSMNormal][child[i]].w;
                    total += weight[i];
                }
            }
            const float scale = total > 0.0f ? 1.0f / total : 0.0f;
            const std::size_t t = static_cast<std::size_t>(y * size + x);
            for (int a = 0; a < shared::kRSMAttachmentCount; ++a) {
                const auto& s = source[a];
                if (a == shared::kRSMFlux) {
                    out[a][t] = 0.25f * (((s[child[0]] + s[child[1]]) + s[child[2]]) + s[child[3]]);
                    continue;
                }
                glm::vec4 sum(0.0f);
                for (int i = 0; i < 4; ++i)
                    sum += weight[i] * s[child[i]];
                out[a][t] = sum * scale;
                if (a == shared::kRSMNormal)
                    out[a][t].w = 0.25f * (((s[child[0]].w + s[child[1]].w) + s[child[2]].w) + s[child[3]].w);
            }
        }
    return out;
}

// A one-sided rectangle at height y facing +y, x in [x0, x1], z in [z0, z1], diffuse albedo rho.
Scene planeScene(float x0, float x1, float z0, float z1, float y, float rho)
{
    Scene scene;
    scene.name = "rsm plane";
    Material material;
    material.baseColor = glm::vec4(rho, rho, rho, 1.0f);
    material.specular = 0.0f;
    scene.materials.push_back(material);
    Mesh mesh;
    const glm::vec3 corners[4] = {{x0, y, z0}, {x0, y, z1}, {x1, y, z1}, {x1, y, z0}};
    for (const glm::vec3& c : corners) {
        Vertex v;
        v.position = c;
        v.normal = {0.0f, 1.0f, 0.0f};
        mesh.vertices.push_back(v);
    }
    mesh.indices = {0, 1, 2, 0, 2, 3};
    scene.meshes.push_back(mesh);
    scene.instances.push_back(Instance{0, glm::mat4(1.0f)});
    return scene;
}

// planeScene with a point light of `intensity` at height h above the origin.
Scene pointLitPlane(float x0, float x1, float z0, float z1, float rho, float h, float intensity)
{
    Scene scene = planeScene(x0, x1, z0, z1, 0.0f, rho);
    Light point;
    point.name = "point";
    point.type = LightType::Point;
    point.position = {0.0f, h, 0.0f};
    point.intensity = intensity;
    scene.lights.push_back(point);
    return scene;
}

// A small emissive quad (half side `side`, radiance 50) at height h facing down: material 1, mesh
// and instance appended to planeScene's.
void addEmissiveQuadDown(Scene& scene, float h, float side)
{
    Material lamp;
    lamp.baseColor = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    lamp.emission = glm::vec3(50.0f);
    scene.materials.push_back(lamp);
    Mesh quad;
    quad.material = 1;
    const glm::vec3 corners[4] = {{-side, h, -side}, {-side, h, side}, {side, h, side}, {side, h, -side}};
    for (const glm::vec3& c : corners) {
        Vertex v;
        v.position = c;
        v.normal = {0.0f, -1.0f, 0.0f};
        quad.vertices.push_back(v);
    }
    quad.indices = {0, 2, 1, 0, 3, 2}; // facing down
    scene.meshes.push_back(quad);
    scene.instances.push_back(Instance{1, glm::mat4(1.0f)});
}

Light spotDown(glm::vec3 position, float intensity, float inner, float outer)
{
    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.position = position;
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.intensity = intensity;
    spot.innerConeAngle = inner;
    spot.outerConeAngle = outer;
    return spot;
}

struct CPUTexel {
    bool covered = false;
    glm::vec3 position{0.0f};
    float flux = 0.0f; // one channel (grey lights and surfaces)
};

// CPU rasterisation of planeScene's rectangle into `view`: each texel centre's ray through the
// inverse view-projection, intersected with the plane; flux by MATH.md 1.5.
std::vector<CPUTexel> rasterisePlane(const RSMView& view, const DirectLightSet& lights, int size, float x0, float x1,
                                     float z0, float z1, float y)
{
    const glm::dmat4 worldFromClip = glm::inverse(glm::dmat4(view.clipFromWorld));
    std::vector<CPUTexel> texels(static_cast<std::size_t>(size * size));
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            const glm::dvec2 ndc((i + 0.5) / size * 2.0 - 1.0, (j + 0.5) / size * 2.0 - 1.0);
            const glm::dvec4 nearH = worldFromClip * glm::dvec4(ndc, -1.0, 1.0);
            const glm::dvec4 farH = worldFromClip * glm::dvec4(ndc, 1.0, 1.0);
            const glm::dvec3 a = glm::dvec3(nearH) / nearH.w;
            const glm::dvec3 b = glm::dvec3(farH) / farH.w;
            const double t = (y - a.y) / (b.y - a.y);
            const glm::dvec3 p = a + t * (b - a);
            CPUTexel& texel = texels[static_cast<std::size_t>(j * size + i)];
            if (!(t >= 0.0 && t <= 1.0 && p.x >= x0 && p.x <= x1 && p.z >= z0 && p.z <= z1)) continue;
            texel.covered = true;
            texel.position = glm::vec3(p);
            if (view.kind != shared::kRSMLightDirectional) {
                const shared::PointEmitter& e = view.source;
                const glm::vec3 dir = glm::normalize(glm::vec3(p - glm::dvec3(glm::vec3(e.positionProfile))));
                // The angle to the view axis: the spot's axis or the cube face's.
                const glm::vec3 axis = view.kind == shared::kRSMLightSpot ? glm::vec3(e.axisCosOuter)
                                                                          : shared::lightViewCubeFaceDirection(view.face);
                const float cosAlpha = glm::dot(axis, dir);
                texel.flux = e.intensity.x * shared::emitterProfile(e, dir) * view.texelFactor * cosAlpha *
                             cosAlpha * cosAlpha;
            } else {
                texel.flux =
                    lights.directionals[static_cast<std::size_t>(view.emitter)].irradiance.x * view.texelFactor;
            }
        }
    return texels;
}

struct Rendered {
    std::unique_ptr<GpuScene> gpuScene;
    DirectLightSet lights;
    std::unique_ptr<RSMPass> pass;
};

Rendered renderRSM(const Scene& scene, int size, RSMMips mips = RSMMips::All,
                   RSMCubeFaces faces = RSMCubeFaces::FaceEach)
{
    test::ensureGLContext();
    Rendered r;
    r.gpuScene = std::make_unique<GpuScene>(scene);
    r.lights = buildDirectLights(scene, DirectLightParams{});
    r.pass = std::make_unique<RSMPass>(test::shaders(), mips);
    RSMParams params;
    params.size = size;
    r.pass->render(*r.gpuScene, r.lights, params, nullptr, faces);
    glFinish();
    return r;
}

// Compares the GPU RSM layer with the CPU rasterisation; returns the GPU flux sum. GPU texels above
// `skipAboveY` (another surface of the scene: the emissive quad) are left out.
double compareWithCPU(const Rendered& r, int layer, int size, float x0, float x1, float z0, float z1, float y,
                      float rho, const std::string& what, int minCovered = -1, float skipAboveY = 1e30f)
{
    if (minCovered < 0) minCovered = size * size / 8 + 1;
    const RSMView& view = r.pass->views()[static_cast<std::size_t>(layer)];
    const std::vector<CPUTexel> cpu = rasterisePlane(view, r.lights, size, x0, x1, z0, z1, y);
    const Level gpu = readAll(*r.pass, 0, layer);
    int coverageMismatches = 0;
    int covered = 0;
    double worstPosition = 0.0;
    double worstPositionPerTexel = 0.0; // the error over the texel's world footprint (next texel's distance)
    double worstFlux = 0.0;
    double worstGeometric = 0.0; // |n_g - (0, 1, 0)|: the triangle's normal in flux.w, diffuse.w (rsm.h)
    double gpuSum = 0.0;
    double cpuSum = 0.0;
    double fluxScale = 0.0;
    double mismatchedFlux = 0.0; // of texels on the rectangle's edge that only one side covers
    for (const CPUTexel& t : cpu)
        fluxScale = std::max(fluxScale, static_cast<double>(t.flux));
    for (std::size_t k = 0; k < cpu.size(); ++k) {
        if (gpu[shared::kRSMNormal][k].w > 0.5f && gpu[shared::kRSMPosition][k].y > skipAboveY) {
            CHECK(gpu[shared::kRSMFlux][k].r == 0.0f); // behind the emitter: no flux
            continue;
        }
        const bool gpuCovered = gpu[shared::kRSMNormal][k].w > 0.5f;
        gpuSum += gpu[shared::kRSMFlux][k].r;
        cpuSum += cpu[k].flux;
        if (gpuCovered != cpu[k].covered) {
            ++coverageMismatches;
            mismatchedFlux +=
                std::max(static_cast<double>(gpu[shared::kRSMFlux][k].r), static_cast<double>(cpu[k].flux));
            continue;
        }
        if (!gpuCovered) continue;
        ++covered;
        const double error = glm::length(glm::vec3(gpu[shared::kRSMPosition][k]) - cpu[k].position);
        worstPosition = std::max(worstPosition, error);
        double footprint = 0.0;
        const std::size_t right = k % static_cast<std::size_t>(size) + 1 < static_cast<std::size_t>(size) ? k + 1 : k - 1;
        const std::size_t down = k + static_cast<std::size_t>(size) < cpu.size() ? k + size : k - size;
        for (std::size_t n : {right, down})
            if (cpu[n].covered) footprint = std::max(footprint, static_cast<double>(glm::length(cpu[n].position - cpu[k].position)));
        if (footprint > 0.0) worstPositionPerTexel = std::max(worstPositionPerTexel, error / footprint);
        worstFlux = std::max(worstFlux, std::abs(gpu[shared::kRSMFlux][k].r - cpu[k].flux) / fluxScale);
        const glm::vec3 geometric =
            shared::octDecode(glm::vec2(gpu[shared::kRSMFlux][k].w, gpu[shared::kRSMDiffuse][k].w));
        worstGeometric = std::max(worstGeometric, static_cast<double>(glm::length(geometric - glm::vec3(0.0f, 1.0f, 0.0f))));
        // The flux is incident (before reflection); the albedo is in the diffuse attachment.
        CHECK(gpu[shared::kRSMDiffuse][k].r == Approx(rho).epsilon(1e-6));
    }
    MEASURED(what << ": " << covered << " covered texels, " << coverageMismatches
                  << " coverage mismatches, worst position error " << worstPosition << " m ("
                  << worstPositionPerTexel << " of a texel's footprint), worst flux error "
                  << worstFlux << " of the largest texel flux, geometric normal off by " << worstGeometric
                  << ", flux sum GPU " << gpuSum << " CPU " << cpuSum);
    // Measured 0 (spot: the plane fills the view; directional: no centre on an edge). Only texel
    // centres on the rectangle's edge may rasterise differently; allow two.
    CHECK(coverageMismatches <= 2);
    CHECK(covered >= minCovered);
    // Measured 3.8e-7 (spot), 3.6e-7 m (directional) and 1.2e-6 m (the emissive quad's sources, on
    // the face that reaches 4 m): float interpolation of world positions vs double rays; 3e-6 m is
    // 2.5x the largest. A hardware GPU interpolates at vertices snapped to its sub-pixel grid, an
    // error that scales with the texel's footprint (up to 9.4e-4 m on the emissive quad's grazing
    // face on an H200): there the bound is on the error over the footprint, measured at most 2.1e-3
    // of it on an H200 (the same face; test::twinTolerance).
    if (test::onHardwareGPU())
        CHECK(worstPositionPerTexel < 6e-3);
    else
        CHECK(worstPosition < 3e-6);
    // Measured 3.6e-6 (spot: the direction from the interpolated position through the steep cone
    // falloff) and 0 (directional: constant) of the largest texel flux; 1e-5 is 2.8x. On an H200 the
    // positions' error carries into it: up to 1.2e-4 (the grazing face).
    CHECK(worstFlux < test::twinTolerance(1e-5, 3e-4));
    // The triangle's normal, from the position's screen-space derivatives: measured 0 on these
    // axis-aligned planes (the cross product of axis-aligned derivatives is exact); a channel left 0
    // decodes to (0, 0, 1), sqrt(2) off. Not yet measured on a hardware GPU (its derivatives come
    // from interpolated positions): there the bound is the G-buffer's normals test's 5e-3.
    CHECK(worstGeometric < test::twinTolerance(1e-5, 5e-3));
    // Measured below 1e-6 relative (float sums of 16k terms); 1e-5 leaves room for the order (H200:
    // 1.4e-5). An edge texel covered on one side only moves the sums apart by its flux.
    CHECK(std::abs(gpuSum - cpuSum) <= test::twinTolerance(1e-5, 4e-5) * cpuSum + mismatchedFlux);
    return gpuSum;
}

} // namespace

TEST_CASE("RSM of a plane under a spot light: positions and flux against a CPU rasterisation", "[rsm][numbers]")
{
    const float rho = 0.5f, intensity = 5.0f, inner = 0.35f, outer = 0.5f;
    Scene scene = planeScene(-4.0f, 4.0f, -4.0f, 4.0f, 0.0f, rho);
    scene.lights.push_back(spotDown({0.0f, 2.0f, 0.0f}, intensity, inner, outer));
    scene.validate();
    const int size = 128;
    Rendered r = renderRSM(scene, size);
    REQUIRE(r.pass->layerCount() == 1);
    REQUIRE(r.pass->views()[0].kind == shared::kRSMLightSpot);
    const double gpuSum = compareWithCPU(r, 0, size, -4.0f, 4.0f, -4.0f, 4.0f, 0.0f, rho, "spot RSM vs CPU");
    // The whole cone lands on the plane: incident flux = 2 pi I int t(c)^2 dc over [cos outer, 1],
    // t = (c - cosOuter)/(cosInner - cosOuter) clamped: 2 pi I ((1 - ci) + (ci - co)/3).
    const double ci = std::cos(static_cast<double>(inner)), co = std::cos(static_cast<double>(outer));
    const double closedForm = 2.0 * kPi * intensity * ((1.0 - ci) + (ci - co) / 3.0);
    const double relative = std::abs(gpuSum - closedForm) / closedForm;
    MEASURED("spot RSM flux sum " << gpuSum << " W vs closed form " << closedForm << " W: relative error " << relative);
    // Measured 6.7e-6 at 128^2 (midpoint rule over the texels' solid angles, float sums); 2e-5 is 3x.
    CHECK(relative < 2e-5);
}

TEST_CASE("RSM of a plane under a directional light: positions and flux against a CPU rasterisation", "[rsm][numbers]")
{
    const float rho = 0.7f, irradiance = 2.0f;
    Scene scene = planeScene(-1.0f, 1.0f, -1.5f, 1.5f, 0.0f, rho);
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    sun.intensity = irradiance;
    scene.lights.push_back(sun);
    scene.validate();
    const int size = 128;
    Rendered r = renderRSM(scene, size);
    REQUIRE(r.pass->layerCount() == 1);
    REQUIRE(r.pass->views()[0].kind == shared::kRSMLightDirectional);
    // The RSM's view is the directional shadow map's.
    const AABB bounds = scene.worldBounds();
    const glm::mat4 fit = shared::lightViewDirectionalFit(sun.direction, bounds.lower, bounds.upper);
    for (int c = 0; c < 4; ++c)
        for (int k = 0; k < 4; ++k)
            CHECK(r.pass->views()[0].clipFromWorld[c][k] == Approx(fit[c][k]).margin(1e-6));
    const double gpuSum = compareWithCPU(r, 0, size, -1.0f, 1.0f, -1.5f, 1.5f, 0.0f, rho, "directional RSM vs CPU");
    // Incident flux onto the plane: E A cos(theta).
    const double closedForm = irradiance * 2.0 * 3.0 * std::abs(static_cast<double>(sun.direction.y));
    const double relative = std::abs(gpuSum - closedForm) / closedForm;
    MEASURED("directional RSM flux sum " << gpuSum << " W vs closed form " << closedForm << " W: relative error "
                                         << relative);
    // Measured 2.0e-4 at 128^2: the edge texels (a texel centre inside or not); 6e-4 is 3x.
    CHECK(relative < 6e-4);
}

TEST_CASE("RSM of a plane under a point light: six cube faces, positions and flux against a CPU rasterisation",
          "[rsm][numbers]")
{
    // The light 1 m above a 4 m x 6 m plane, off its centre: the plane is seen through the -Y
    // face and the lower parts of the four side faces, so the sum crosses every seam below the
    // light. Each edge lies in one side face and projects onto a texel-row boundary there (edge
    // at distance d: the row at y/d = -1/d, -1/2 and -1/4 on a grid of 2/64), so no texel is cut
    // by an edge and the sum is a midpoint rule over whole texels, as in the spot test.
    const float rho = 0.6f, intensity = 4.0f, h = 1.0f;
    const float x0 = -2.0f, x1 = 2.0f, z0 = -2.0f, z1 = 4.0f;
    Scene scene = pointLitPlane(x0, x1, z0, z1, rho, h, intensity);
    scene.validate();
    const glm::vec3 lightPosition = scene.lights[0].position;
    const int size = 64;
    Rendered r = renderRSM(scene, size);
    REQUIRE(r.pass->layerCount() == 6);
    double gpuSum = 0.0;
    for (int face = 0; face < 6; ++face) {
        const RSMView& view = r.pass->views()[static_cast<std::size_t>(face)];
        CHECK(view.kind == shared::kRSMLightPoint);
        CHECK(view.face == face);
        // The cube faces are the shadow cubes' (light_view.h), up to the near/far planes.
        const glm::mat4 faceView = shared::lightViewCubeFaceViewFromWorld(lightPosition, face);
        CHECK(view.viewFromWorld == faceView);
        // +Y looks away from the plane; every other face sees part of it.
        const int minCovered = face == 2 ? 0 : size * size / 16; // measured 0 (+Y), 1024 or more
        gpuSum += compareWithCPU(r, face, size, x0, x1, z0, z1, 0.0f, rho, "point RSM face " + std::to_string(face),
                                 minCovered);
    }
    // Incident flux onto the plane: I Omega, with Omega the rectangle's solid angle from the light: by
    // inclusion-exclusion of rectangles with a corner below the light, each atan(a b / (h sqrt(h^2
    // + a^2 + b^2))) (odd in a and b).
    auto corner = [&](double a, double b) { return std::atan(a * b / (h * std::sqrt(h * h + a * a + b * b))); };
    const double omega = corner(x1, z1) - corner(x0, z1) - corner(x1, z0) + corner(x0, z0);
    const double closedForm = intensity * omega;
    const double relative = std::abs(gpuSum - closedForm) / closedForm;
    MEASURED("point RSM flux sum over 6 faces " << gpuSum << " W vs closed form " << closedForm << " W: relative error "
                                                << relative);
    // Measured 5.4e-5 at 64^2 per face (the midpoint rule over texel solid angles; the corners of
    // a 90-degree face curve more than a spot's narrower frustum); 1.5e-4 is 2.8x. With the edges
    // across texels instead (x0 = -2.5, z0 = -1.5, z1 = 3.5) it was 2e-3: half-covered rows.
    CHECK(relative < 1.5e-4);
}

TEST_CASE("RSM of a plane under an emissive quad: cosine sources over their hemisphere, flux against the closed form",
          "[rsm][numbers]")
{
    // A small emissive quad facing down 1 m above a 4 m x 6 m plane: its emitter samples merge into
    // at most rsm.areaSources cosine sources, each seen through the -Y face and the lower halves of
    // the side faces (+Y lies wholly behind the emitter and is skipped). Flux onto the plane from a
    // cosine source of peak intensity I at height h: I * integral of cos(theta) dOmega = I h^2 / r^4
    // dA, per rectangle with a corner below the source (X = a/h, Y = b/h)
    // 1/2 [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + Y/sqrt(1+Y^2) atan(X/sqrt(1+Y^2))] (odd in a and b:
    // inclusion-exclusion as in the point-light test).
    const float rho = 0.6f, h = 1.0f, side = 0.05f;
    const float x0 = -2.0f, x1 = 2.0f, z0 = -2.0f, z1 = 4.0f;
    Scene scene = planeScene(x0, x1, z0, z1, 0.0f, rho);
    addEmissiveQuadDown(scene, h, side);
    scene.validate();
    const int size = 64;
    Rendered r = renderRSM(scene, size);
    const RSMParams defaults;
    REQUIRE(r.pass->layerCount() > 0);
    REQUIRE(r.pass->layerCount() <= 5 * defaults.areaSources);
    double gpuSum = 0.0, closedForm = 0.0, groupIntensity = 0.0;
    auto corner = [](double a, double b, double height) {
        const double X = a / height, Y = b / height;
        const double sx = std::sqrt(1.0 + X * X), sy = std::sqrt(1.0 + Y * Y);
        return 0.5 * (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy));
    };
    for (int layer = 0; layer < r.pass->layerCount(); ++layer) {
        const RSMView& view = r.pass->views()[static_cast<std::size_t>(layer)];
        CHECK(view.kind == shared::kRSMLightArea);
        CHECK(view.face != 2); // +Y: behind the emitter
        CHECK(glm::vec3(view.source.axisCosOuter).y == Approx(-1.0f));
        // The -Y face sees the plane whole; the side faces a band below their horizon.
        gpuSum += compareWithCPU(r, layer, size, x0, x1, z0, z1, 0.0f, rho, "area RSM face " + std::to_string(view.face),
                                 view.face == 3 ? size * size / 8 : size * size / 16, 0.5f * h);
        if (view.face != 3) continue; // once per source
        const glm::dvec3 c(glm::vec3(view.source.positionProfile));
        const double I = view.source.intensity.x;
        groupIntensity += I;
        closedForm += I * (corner(x1 - c.x, z1 - c.z, c.y) - corner(x0 - c.x, z1 - c.z, c.y) -
                           corner(x1 - c.x, z0 - c.z, c.y) + corner(x0 - c.x, z0 - c.z, c.y));
    }
    // The sources carry the quad's power: pi I = pi L A.
    const double quadIntensity = 50.0 * (2.0 * side) * (2.0 * side);
    CHECK(groupIntensity == Approx(quadIntensity).epsilon(1e-5));
    const double relative = std::abs(gpuSum - closedForm) / closedForm;
    MEASURED("area RSM flux sum " << gpuSum << " W vs closed form " << closedForm << " W: relative error " << relative);
    // The same midpoint rule as the point light's faces (measured there 5.4e-5); 1.5e-4 as there.
    CHECK(relative < 1.5e-4);
}

TEST_CASE("RSM mips: a half-empty spot RSM stays on the lit plane at every level, flux is conserved", "[rsm][numbers]")
{
    // The plane covers x >= 0 only, 1 m below the light; empty texels hold position 0, off the
    // plane, so any pull towards them moves mip positions off y = -1.
    const float rho = 0.5f;
    const float y = -1.0f;
    Scene scene = planeScene(0.0f, 4.0f, -4.0f, 4.0f, y, rho);
    scene.lights.push_back(spotDown({0.0f, 0.0f, 0.0f}, 3.0f, 0.6f, 0.7f));
    scene.validate();
    const int size = 64;
    Rendered r = renderRSM(scene, size);
    REQUIRE(r.pass->levelCount() == 7);
    Level level = readAll(*r.pass, 0, 0);
    double flux0 = 0.0;
    for (const glm::vec4& f : level[shared::kRSMFlux])
        flux0 += f.r;
    Level cpu = level;
    double worstOffPlane = 0.0, worstNormal = 0.0, worstTwin = 0.0, worstFluxSum = 0.0;
    float minX = 1e30f;
    for (int l = 1; l < r.pass->levelCount(); ++l) {
        const int levelSize = size >> l;
        cpu = downsampleOnCPU(cpu, levelSize * 2);
        level = readAll(*r.pass, l, 0);
        double fluxSum = 0.0;
        int covered = 0;
        for (std::size_t k = 0; k < level[0].size(); ++k) {
            fluxSum += level[shared::kRSMFlux][k].r;
            for (int a = 0; a < shared::kRSMAttachmentCount; ++a)
                for (int c = 0; c < 4; ++c)
                    worstTwin = std::max(worstTwin, static_cast<double>(std::abs(level[a][k][c] - cpu[a][k][c]) /
                                                                        std::max(1.0f, std::abs(cpu[a][k][c]))));
            if (level[shared::kRSMNormal][k].w == 0.0f) continue;
            ++covered;
            const glm::vec4 p = level[shared::kRSMPosition][k];
            worstOffPlane = std::max(worstOffPlane, static_cast<double>(std::abs(p.y - y)));
            minX = std::min(minX, p.x);
            const glm::vec3 n(level[shared::kRSMNormal][k]);
            worstNormal = std::max(worstNormal, static_cast<double>(glm::length(n - glm::vec3(0.0f, 1.0f, 0.0f))));
        }
        CHECK(covered > 0);
        worstFluxSum = std::max(worstFluxSum, std::abs(fluxSum * std::pow(4.0, l) - flux0) / flux0);
        if (l == r.pass->levelCount() - 1) {
            // One texel: half the view is covered.
            CHECK(level[shared::kRSMNormal][0].w == Approx(0.5f).epsilon(1e-6));
        }
    }
    MEASURED("half-empty spot RSM mips: worst distance off the plane "
             << worstOffPlane << " m, smallest x " << minX << " m, worst |n - (0,1,0)| " << worstNormal
             << ", worst 4^l flux sum error " << worstFluxSum << ", worst GPU vs CPU twin " << worstTwin);
    // Measured 1.2e-7 m off the plane and 1.2e-7 normal error (float weighted means of equal
    // values; one ulp at 1); a pull towards the empty texels would be of order 1 m. 3e-7 is 2.5x.
    // Smallest x measured 0.026 m (half a texel from the edge); x < 0 is off the plane.
    CHECK(worstOffPlane < 3e-7);
    CHECK(minX >= 0.0f);
    CHECK(worstNormal < 3e-7);
    // Measured 1.7e-8: float sums of 4^l terms in a different order; 5e-8 is 3x.
    CHECK(worstFluxSum < 5e-8);
    // Measured 0 (the same operations in the same order); 1e-6 allows a driver that fuses
    // multiply-adds, which the CPU twin does not.
    CHECK(worstTwin < 1e-6);
}

TEST_CASE("RSM mips are bit-identical over runs", "[rsm][determinism]")
{
    // A plane, a glossy metal box and a dielectric box under a spot light and a sun.
    Scene scene = planeScene(-3.0f, 3.0f, -3.0f, 3.0f, 0.0f, 0.6f);
    Material metal;
    metal.baseColor = glm::vec4(0.9f, 0.6f, 0.3f, 1.0f);
    metal.metallic = 1.0f;
    metal.roughness = 0.35f;
    scene.materials.push_back(metal);
    Scene box = planeScene(-1.0f, 0.5f, -1.0f, 0.2f, 0.8f, 0.2f);
    box.meshes[0].material = 1;
    scene.meshes.push_back(box.meshes[0]);
    scene.instances.push_back(Instance{1, glm::mat4(1.0f)});
    Light spot = spotDown({0.5f, 3.0f, 1.0f}, 6.0f, 0.35f, 0.6f);
    spot.direction = glm::normalize(glm::vec3(-0.2f, -1.0f, -0.4f));
    scene.lights.push_back(spot);
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.5f, -1.0f, -0.3f));
    sun.color = {1.0f, 0.9f, 0.8f};
    sun.intensity = 1.5f;
    scene.lights.push_back(sun);
    scene.validate();

    const int size = 64;
    auto hashAll = [&](const Rendered& r) {
        std::uint64_t hash = test::hashBytes(nullptr, 0); // over every level, layer and attachment
        for (int layer = 0; layer < r.pass->layerCount(); ++layer)
            for (int l = 0; l < r.pass->levelCount(); ++l)
                for (const auto& attachment : readAll(*r.pass, l, layer))
                    hash = test::hashBytes(attachment.data(), attachment.size() * sizeof(glm::vec4), hash);
        return hash;
    };
    Rendered first = renderRSM(scene, size);
    REQUIRE(first.pass->layerCount() == 2);
    const std::uint64_t a = hashAll(first);
    first.pass->downsample(); // the mips again from the same level 0
    glFinish();
    const std::uint64_t b = hashAll(first);
    const std::uint64_t c = hashAll(renderRSM(scene, size));
    CHECK(a == b);
    CHECK(a == c);
    // tests/gl/threads_identical.sh runs this test under LP_NUM_THREADS=1 and 2 and compares the hashes.
    CHECK(test::recordHash("rsm", a));
}

TEST_CASE("rsm.size is set through visitParams and must be a power of two", "[rsm]")
{
    RSMParams params;
    CHECK(params.size == 256);
    ParamSetter setter(Settings{{"rsm.size", "96"}});
    params.visitParams(setter);
    setter.finish();
    CHECK(params.size == 96);
    Scene scene = planeScene(-1.0f, 1.0f, -1.0f, 1.0f, 0.0f, 0.5f);
    scene.lights.push_back(spotDown({0.0f, 1.0f, 0.0f}, 1.0f, 0.3f, 0.4f));
    test::ensureGLContext();
    GpuScene gpuScene(scene);
    RSMPass pass(test::shaders());
    CHECK_THROWS_AS(pass.render(gpuScene, buildDirectLights(scene, DirectLightParams{}), params), Error);
    params.size = 32;
    pass.render(gpuScene, buildDirectLights(scene, DirectLightParams{}), params);
    CHECK(pass.levelCount() == 6);
    CHECK(pass.target().width() == 32);
}

TEST_CASE("RSM without mips (vpl-brsm, LightSkin): one level, level 0 bit for bit as with mips", "[rsm]")
{
    // RSMMips::None skips the downsample pass and allocates one level; what the techniques read
    // (level 0) must not change. Compares the pass with itself (plumbing), for a spot and a point
    // light's cube faces; the images of vpl-brsm and LightSkin are held by the conform CI subset.
    Scene scene = planeScene(-2.0f, 2.0f, -2.0f, 2.0f, 0.0f, 0.5f);
    scene.lights.push_back(spotDown({0.0f, 1.0f, 0.0f}, 2.0f, 0.5f, 0.6f));
    Light point;
    point.name = "point";
    point.type = LightType::Point;
    point.position = glm::vec3(0.5f, 0.8f, 0.2f);
    point.color = glm::vec3(1.0f);
    point.intensity = 3.0f;
    scene.lights.push_back(point);
    scene.validate();
    const int size = 32;
    Rendered all = renderRSM(scene, size, RSMMips::All);
    Rendered none = renderRSM(scene, size, RSMMips::None);
    CHECK(all.pass->levelCount() == 6);
    CHECK(none.pass->levelCount() == 1);
    CHECK(none.pass->target().color(0).desc().levels == 1);
    REQUIRE(none.pass->layerCount() == 7);
    REQUIRE(all.pass->layerCount() == none.pass->layerCount());
    for (int layer = 0; layer < none.pass->layerCount(); ++layer) {
        const Level a = readAll(*all.pass, 0, layer);
        const Level b = readAll(*none.pass, 0, layer);
        for (int k = 0; k < shared::kRSMAttachmentCount; ++k) {
            INFO("layer " << layer << ", attachment " << k);
            CHECK(std::memcmp(a[static_cast<std::size_t>(k)].data(), b[static_cast<std::size_t>(k)].data(),
                              a[static_cast<std::size_t>(k)].size() * sizeof(glm::vec4)) == 0);
        }
    }
}

TEST_CASE("RSM cube faces within one light's budget (LightSkin): each face floor(size / sqrt(faces)) wide in its "
          "layer's corner, flux against the CPU rasterisation and the closed form",
          "[rsm][numbers]")
{
    // The point-light plane above, with RSMCubeFaces::LightBudget at 128^2: the six faces share
    // 128^2 texels, 52 wide each (6 x 52^2 = 16224 <= 16384), drawn into texels [0, 52)^2 of their
    // layers; a spot light beside it keeps its whole layer. The rest of a face's layer must hold no
    // surface and no flux (every per-texel reader skips it), the square must match the CPU
    // rasterisation at 52^2 texel for texel, and the flux onto the plane the closed form.
    const float rho = 0.6f, intensity = 4.0f, h = 1.0f;
    const float x0 = -2.0f, x1 = 2.0f, z0 = -2.0f, z1 = 4.0f;
    Scene scene = pointLitPlane(x0, x1, z0, z1, rho, h, intensity);
    scene.lights.push_back(spotDown({0.0f, 2.0f, 0.0f}, 1.0f, 0.35f, 0.5f));
    scene.validate();
    const int size = 128, faceSize = 52;
    Rendered r = renderRSM(scene, size, RSMMips::None, RSMCubeFaces::LightBudget);
    REQUIRE(r.pass->layerCount() == 7);
    double pointSum = 0.0;
    int outsideCovered = 0, coverageMismatches = 0, covered = 0;
    double worstFlux = 0.0, mismatchedFlux = 0.0, cpuSum = 0.0;
    for (int layer = 0; layer < 7; ++layer) {
        const RSMView& view = r.pass->views()[static_cast<std::size_t>(layer)];
        const bool isPoint = view.kind == shared::kRSMLightPoint;
        CHECK(view.size == (isPoint ? faceSize : size));
        CHECK(view.texelFactor ==
              Approx(4.0 / (view.clipFromView[0][0] * view.clipFromView[1][1] * double(view.size) * view.size))
                  .epsilon(1e-6));
        if (!isPoint) continue;
        const Level gpu = readAll(*r.pass, 0, layer);
        const std::vector<CPUTexel> cpu = rasterisePlane(view, r.lights, faceSize, x0, x1, z0, z1, 0.0f);
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const std::size_t k = static_cast<std::size_t>(y * size + x);
                const bool gpuCovered = gpu[shared::kRSMNormal][k].w > 0.5f;
                const float flux = gpu[shared::kRSMFlux][k].r;
                if (x >= faceSize || y >= faceSize) {
                    if (gpuCovered || flux != 0.0f) ++outsideCovered;
                    continue;
                }
                const CPUTexel& c = cpu[static_cast<std::size_t>(y * faceSize + x)];
                pointSum += flux;
                cpuSum += c.flux;
                if (gpuCovered != c.covered) {
                    ++coverageMismatches;
                    mismatchedFlux += std::max(static_cast<double>(flux), static_cast<double>(c.flux));
                    continue;
                }
                if (!gpuCovered) continue;
                ++covered;
                worstFlux = std::max(worstFlux, std::abs(static_cast<double>(flux) - c.flux) / c.flux);
            }
    }
    auto corner = [&](double a, double b) { return std::atan(a * b / (h * std::sqrt(h * h + a * a + b * b))); };
    const double closedForm = intensity * (corner(x1, z1) - corner(x0, z1) - corner(x1, z0) + corner(x0, z0));
    const double relative = std::abs(pointSum - closedForm) / closedForm;
    MEASURED("point light in one budget: 6 faces of " << faceSize << "^2, " << covered << " covered texels, "
             << coverageMismatches << " coverage mismatches with the CPU, worst texel flux error " << worstFlux
             << ", " << outsideCovered << " texels covered outside the squares; flux sum " << pointSum
             << " W vs closed form " << closedForm << " W: relative error " << relative);
    CHECK(outsideCovered == 0);
    // As the full-size faces above: texel centres on the rectangle's edges may rasterise either way.
    // Measured 0 mismatches and 5674 covered texels (the 64^2 faces above: 9000-odd of 6 x 4096).
    CHECK(coverageMismatches <= 8);
    CHECK(covered > 5000);
    CHECK(worstFlux < test::twinTolerance(1e-5, 3e-4));
    CHECK(std::abs(pointSum - cpuSum) <= test::twinTolerance(1e-5, 4e-5) * cpuSum + mismatchedFlux);
    // At 52 texels the plane's edges cut texel rows (unlike the 64^2 test above, where they lie on
    // row boundaries): measured 4.0e-3, the half-covered rows (2e-3 at 64^2 with its edges moved
    // across texels, above); 1e-2 is 2.5x. The texel-for-texel CPU agreement is the sharp check.
    CHECK(relative < 1e-2);

    // An emissive quad's hemisphere: its faces (5, +Y is behind it) share one budget too.
    Scene lamp = planeScene(x0, x1, z0, z1, 0.0f, rho);
    addEmissiveQuadDown(lamp, h, 0.05f);
    lamp.validate();
    Rendered area = renderRSM(lamp, size, RSMMips::None, RSMCubeFaces::LightBudget);
    REQUIRE(area.pass->layerCount() == 5);
    for (const RSMView& view : area.pass->views()) CHECK(view.size == 57); // floor(128 / sqrt(5))

    // Mips take whole layers: the pass refuses the budget with them.
    test::ensureGLContext();
    GpuScene gpuScene(scene);
    RSMPass withMips(test::shaders(), RSMMips::All);
    RSMParams params;
    params.size = size;
    CHECK_THROWS_AS(withMips.render(gpuScene, buildDirectLights(scene, DirectLightParams{}), params, nullptr,
                                    RSMCubeFaces::LightBudget),
                    Error);
}
