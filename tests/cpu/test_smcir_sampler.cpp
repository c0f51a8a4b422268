// The SMCIR VPL sampler (core/vpl/smcir_sampler.h, Algorithm 1) and the reflected-radiance estimator it
// uses (core/trace/path_tracer.h): closed forms in the furnace, exact indirect visibility in sealed rooms,
// the M_max bound and stable slots, convergence, caching and determinism.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

#include <tbb/global_control.h>

#include "core/scene/builtin_scenes.h"
#include "core/util/error.h"
#include "core/util/knn.h"
#include "core/util/params.h"
#include "core/trace/path_tracer.h"
#include "core/trace/ray_scene.h"
#include "core/vpl/smcir_sampler.h"
#include "core/scene/surface.h"
#include "measured.h"

using namespace vplgi;

namespace {

constexpr double kPi = 3.14159265358979323846;

float luminance(const glm::vec3& c)
{
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

// Coefficient of variation of the VPL intensities' luminances, L/p (eq. 6).
double intensityCoV(const VPLSet& set)
{
    double sum = 0.0, sum2 = 0.0;
    int n = 0;
    for (const VPL& v : set.slots) {
        if (!v.valid) continue;
        const double i = luminance(v.intensity());
        sum += i;
        sum2 += i * i;
        ++n;
    }
    const double mean = sum / n;
    return std::sqrt(std::max(0.0, sum2 / n - mean * mean)) / mean;
}

bool sameVPL(const VPL& a, const VPL& b)
{
    return a.valid == b.valid && a.position == b.position && a.normal == b.normal && a.radiance == b.radiance &&
           a.density == b.density;
}

bool identicalSets(const VPLSet& a, const VPLSet& b)
{
    if (a.slots.size() != b.slots.size() || a.changed != b.changed) return false;
    for (std::size_t i = 0; i < a.slots.size(); ++i)
        if (!sameVPL(a.slots[i], b.slots[i])) return false;
    return true;
}

// The six faces of the box [lower, upper] as cells x cells quads each, facing out (or in), one
// Lambertian material. Vertex normals and counter-clockwise winding on the facing side.
void addBoxFaces(Mesh& mesh, const glm::vec3& lower, const glm::vec3& upper, bool inward, int cells)
{
    for (int axis = 0; axis < 3; ++axis) {
        for (int side = 0; side < 2; ++side) {
            glm::vec3 normal(0.0f);
            normal[axis] = (side == 1 ? 1.0f : -1.0f) * (inward ? -1.0f : 1.0f);
            glm::vec3 corner = lower;
            corner[axis] = side == 1 ? upper[axis] : lower[axis];
            glm::vec3 edgeU(0.0f), edgeV(0.0f);
            edgeU[(axis + 1) % 3] = upper[(axis + 1) % 3] - lower[(axis + 1) % 3];
            edgeV[(axis + 2) % 3] = upper[(axis + 2) % 3] - lower[(axis + 2) % 3];
            if (glm::dot(glm::cross(edgeU, edgeV), normal) < 0.0f) std::swap(edgeU, edgeV);
            const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
            for (int j = 0; j <= cells; ++j) {
                for (int i = 0; i <= cells; ++i) {
                    Vertex v;
                    v.position = corner + edgeU * (float(i) / cells) + edgeV * (float(j) / cells);
                    v.normal = normal;
                    mesh.vertices.push_back(v);
                }
            }
            for (int j = 0; j < cells; ++j) {
                for (int i = 0; i < cells; ++i) {
                    const std::uint32_t a = base + j * (cells + 1) + i, b = a + 1, c = a + (cells + 1), d = c + 1;
                    mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
                }
            }
        }
    }
}

Light pointLight(const glm::vec3& position, float intensity)
{
    Light light;
    light.type = LightType::Point;
    light.position = position;
    light.intensity = intensity;
    return light;
}

Camera lookAt(const glm::vec3& position, const glm::vec3& target)
{
    Camera camera;
    camera.position = position;
    camera.target = target;
    camera.fovY = 1.0f;
    camera.zNear = 0.05f;
    camera.zFar = 100.0f;
    return camera;
}

// Two closed rooms with no opening between them: A = [-6, -0.5] x [0, 3] x [-3, 3] and
// B = [0.5, 6] x [0, 3] x [-3, 3] (walls facing inwards), and inside B a sealed solid box C
// (outer faces out, inner faces in, walls 0.1 m thick) floating above the floor. One light in each
// room and a bright one inside C. Nothing in A can see B, and nothing outside C can see into it.
struct SealedRooms {
    Scene scene;
    glm::vec3 roomALower{-6.0f, 0.0f, -3.0f}, roomAUpper{-0.5f, 3.0f, 3.0f};
    glm::vec3 roomBLower{0.5f, 0.0f, -3.0f}, roomBUpper{6.0f, 3.0f, 3.0f};
    glm::vec3 boxLower{2.5f, 0.6f, -0.8f}, boxUpper{4.1f, 2.0f, 0.8f}; // C's outer faces
    Camera inA, inB;

    SealedRooms()
    {
        scene.name = "sealed rooms";
        Material wall;
        wall.baseColor = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
        wall.metallic = 0.0f;
        wall.roughness = 1.0f;
        wall.specular = 0.0f;
        scene.materials.push_back(wall);
        Mesh mesh;
        mesh.material = 0;
        addBoxFaces(mesh, roomALower, roomAUpper, true, 8);
        addBoxFaces(mesh, roomBLower, roomBUpper, true, 8);
        addBoxFaces(mesh, boxLower, boxUpper, false, 4);
        addBoxFaces(mesh, boxLower + glm::vec3(0.1f), boxUpper - glm::vec3(0.1f), true, 4);
        scene.meshes.push_back(mesh);
        scene.instances.push_back(Instance{});
        scene.lights.push_back(pointLight({-3.0f, 2.5f, 1.0f}, 10.0f));
        scene.lights.push_back(pointLight({1.5f, 2.6f, -2.0f}, 10.0f));
        scene.lights.push_back(pointLight(0.5f * (boxLower + boxUpper), 200.0f)); // inside C
        inA = lookAt({-5.5f, 1.6f, -2.5f}, {-1.0f, 1.0f, 2.0f});
        inB = lookAt({0.9f, 1.6f, 2.5f}, {3.3f, 1.3f, 0.0f});
        scene.cameras.push_back(inA);
        scene.validate();
    }

    static bool inside(const glm::vec3& p, const glm::vec3& lower, const glm::vec3& upper)
    {
        return glm::all(glm::greaterThan(p, lower)) && glm::all(glm::lessThan(p, upper));
    }
    bool inRoomA(const glm::vec3& p) const { return inside(p, roomALower - 0.01f, roomAUpper + 0.01f); }
    bool inRoomB(const glm::vec3& p) const { return inside(p, roomBLower - 0.01f, roomBUpper + 0.01f); }
    // Strictly inside C's walls: only C's inner faces are there.
    bool inBox(const glm::vec3& p) const { return inside(p, boxLower + 0.05f, boxUpper - 0.05f); }
    bool onBoxOutside(const glm::vec3& p) const
    {
        return inside(p, boxLower - 0.01f, boxUpper + 0.01f) && !inBox(p);
    }
};

// A point on the inside of the furnace sphere with its inward normal, as the sampler sees walls.
SurfacePoint furnaceWallPoint(const Scene& scene, const RayScene& rays, const glm::vec3& direction)
{
    Ray ray;
    ray.origin = glm::vec3(0.0f);
    ray.direction = glm::normalize(direction);
    const Hit hit = rays.intersect(ray);
    REQUIRE(hit.valid());
    return surfaceAt(scene, hit, -ray.direction);
}

SMCIRParams smallParams(int vplCount, int warmup)
{
    SMCIRParams params;
    params.vplCount = vplCount;
    params.warmupIterations = warmup;
    return params;
}

} // namespace

TEST_CASE("reflected radiance at a furnace wall point: closed forms per bounce, diffuse lobe only", "[smcir][reference]")
{
    FurnaceParams furnace; // R = 1, rho = 0.5, I0 = pi: L_n = 0.5^n, L_all = 1
    const Scene scene = makeFurnace(furnace);
    const RayScene rays(scene);
    const SurfacePoint y = furnaceWallPoint(scene, rays, {0.3f, -0.5f, 0.8f});

    // One bounce: direct light at y only, no randomness left. Embree rays counted exactly: the
    // punctual light's shadow ray from y is the same for every path, so it is cast once per
    // estimate, and the continuation ray is not cast at all (it could only find emission, and the
    // furnace has no emissive triangles).
    std::uint64_t count = 0;
    const glm::vec3 direct = estimateReflectedRadiance(scene, rays, y, 8, 1, 3u, &count);
    CHECK(direct.g == Approx(furnaceRadianceBounce(furnace, 1)).epsilon(2e-3));
    CHECK(count == 1u);
    // Two bounces: the shared shadow ray, then per path the continuation ray to vertex 1 and its
    // shadow ray (a ray from inside the sphere always hits, and the light faces every wall point);
    // the ray to vertex 2 is skipped as above.
    count = 0;
    estimateReflectedRadiance(scene, rays, y, 8, 2, 3u, &count);
    CHECK(count == 1u + 2u * 8u);
    // Three bounces, the SMCIR default: L_1 + L_2 + L_3 (Russian roulette only past vertex 3).
    const double three = furnaceRadianceBounce(furnace, 1) + furnaceRadianceBounce(furnace, 2) +
                         furnaceRadianceBounce(furnace, 3);
    CHECK(estimateReflectedRadiance(scene, rays, y, 16, 3, 3u).g == Approx(three).epsilon(2e-3));
    // Many bounces: L_all (Russian roulette noise averages out over 2000 paths).
    CHECK(estimateReflectedRadiance(scene, rays, y, 2000, 60, 3u).g == Approx(furnaceRadianceAll(furnace)).epsilon(0.01));
    // The same seed gives the same value; another seed another one.
    CHECK(estimateReflectedRadiance(scene, rays, y, 16, 60, 5u) == estimateReflectedRadiance(scene, rays, y, 16, 60, 5u));
    CHECK(estimateReflectedRadiance(scene, rays, y, 16, 60, 5u) != estimateReflectedRadiance(scene, rays, y, 16, 60, 6u));

    // Only the diffuse lobe at y: (1 - metallic) * baseColor / pi; a dielectric specular lobe or a
    // metallic part reflects nothing into L(y) (SMCIR 3.1's Lambert assumption).
    SurfacePoint glossy = y;
    glossy.material.specular = 1.0f;
    glossy.material.roughness = 0.2f;
    CHECK(estimateReflectedRadiance(scene, rays, glossy, 8, 1, 3u).g == Approx(direct.g).epsilon(1e-6));
    SurfacePoint metal = y;
    metal.material.metallic = 0.5f;
    CHECK(estimateReflectedRadiance(scene, rays, metal, 8, 1, 3u).g == Approx(0.5 * direct.g).epsilon(1e-6));
    CHECK_THROWS_AS(estimateReflectedRadiance(scene, rays, y, 0, 3, 1u), Error);
    CHECK_THROWS_AS(ReflectedRadianceEstimator(scene, rays, 0), Error);
}

TEST_CASE("smcir parameters: paper defaults, one field list, eq. (8)", "[smcir][params]")
{
    const SMCIRParams defaults;
    CHECK(defaults.vplCount == 2048);       // I (4 Implementation / 3.2)
    CHECK(defaults.maxMoves == 16);         // M_max
    CHECK(defaults.validationRays == 16);   // V (3.2.2)
    CHECK(defaults.validationIterations == 2);
    CHECK(defaults.candidateFactor == 16);  // 16:1 (3.2.1)
    CHECK(defaults.resampleRetries == 8);
    CHECK(defaults.radiositySamples == 16); // 3.2.3
    CHECK(defaults.radiosityBounces == 3);
    CHECK(defaults.knnRender == 0);         // eq. (8)
    CHECK(defaults.strongFraction == 0.95f); // eq. (9)
    CHECK(defaults.warmupIterations == 100);
    CHECK(computeRenderingK(2048) == 8);
    CHECK(computeRenderingK(512) == 4);
    CHECK(computeRenderingK(8192) == 16);
    CHECK(computeRenderingK(256) == 2);
    CHECK(computeRenderingK(31) == 1);
    CHECK(computeRenderingK(1) == 1);

    SMCIRParams params;
    ParamDumper dump;
    params.visitParams(dump);
    const auto& values = dump.values();
    for (const char* key : {"smcir.vplCount", "smcir.maxMoves", "smcir.validationRays", "smcir.validationIterations",
                            "smcir.candidateFactor", "smcir.resampleRetries", "smcir.candidateDensityK",
                            "smcir.radiositySamples", "smcir.radiosityBounces", "smcir.knnRender",
                            "smcir.strongFraction", "smcir.cameraSamplesX", "smcir.cameraSamplesY",
                            "smcir.warmupIterations", "smcir.seed", "smcir.candidateRadianceSamples",
                            "smcir.candidateDensityGrid", "smcir.texturedVPLs", "smcir.clampScale",
                            "smcir.invalidateEveryFrame", "smcir.independentRadiance", "smcir.rankRadiance",
                            "smcir.knnCountsSelf", "smcir.knnRank"})
        CHECK(values.count(key) == 1);
    CHECK(values.size() == 24);
    CHECK(defaults.candidateDensityK == 1);   // 3.2.4: "We set k = 1" (lines 6 and 8)
    CHECK(defaults.texturedVPLs == false);     // 5: "an untextured version of the scene for the VPL generation"
    CHECK(defaults.clampScale > 0.0f);         // 5.4: always clamped
    CHECK(defaults.reestimateEveryFrame == false);
    CHECK(values.at("smcir.candidateDensityGrid") == "false"); // the paper: kNN
    CHECK(values.at("smcir.candidateRadianceSamples") == "0"); // 0 = the paper: radiositySamples
    CHECK(values.at("smcir.vplCount") == "2048");

    ParamSetter setter(Settings{{"smcir.vplCount", "512"}, {"smcir.maxMoves", "8"}, {"smcir.seed", "7"}});
    params.visitParams(setter);
    setter.finish();
    CHECK(params.vplCount == 512);
    CHECK(params.maxMoves == 8);
    CHECK(params.seed == 7u);
    CHECK(params.radiositySamples == 16); // untouched
    SMCIRParams other;
    ParamSetter bad(Settings{{"smcir.strongFraction", "1.5"}});
    CHECK_THROWS_AS(other.visitParams(bad), Error);

    const Scene scene = makeFurnace(FurnaceParams{});
    const RayScene rays(scene);
    SMCIRParams zero;
    zero.vplCount = 0;
    CHECK_THROWS_AS(SMCIRSampler(scene, rays, zero), Error);
    SMCIRSampler sampler(scene, rays, smallParams(16, 0));
    CHECK_THROWS_AS(sampler.step(scene.cameras[0]), Error); // before initialize()
}

namespace {

struct FurnaceSummary {
    double meanRadiance = 0.0;       // mean of L(y) (green)
    double meanInverseDensity = 0.0; // mean of 1/p(y) [m^2]
    double worstEq5 = 0.0;           // worst relative error of eq. (5) against rho L_all over 6 wall points
    double meanEq5 = 0.0;            // mean of eq. (5) / (rho L_all)
};

// Eq. (5) at wall points x: (1/I) sum_i (rho/pi) G(x, y_i) I(y_i), G = 1/(4R^2) for every pair
// (MATH.md 3), so it must give rho L_all when the intensities are right on average.
FurnaceSummary summarizeFurnace(const Scene& scene, const RayScene& rays, const FurnaceParams& furnace, const VPLSet& set)
{
    FurnaceSummary summary;
    const double count = static_cast<double>(set.validCount());
    for (const VPL& v : set.slots) {
        summary.meanRadiance += v.radiance.g / count;
        summary.meanInverseDensity += 1.0 / v.density / count;
    }
    const double expected = furnace.albedo * furnaceRadianceAll(furnace);
    const std::array<glm::vec3, 6> directions{
        {{1, 0, 0}, {-1, 0.2f, 0}, {0, 1, 0}, {0.3f, -1, 0.1f}, {0, 0, 1}, {0.2f, 0.1f, -1}}};
    for (const glm::vec3& direction : directions) {
        const SurfacePoint x = furnaceWallPoint(scene, rays, direction);
        double sum = 0.0;
        for (const VPL& v : set.slots) {
            const glm::vec3 d = v.position - x.position;
            const double d2 = glm::dot(d, d);
            const glm::vec3 w = d / static_cast<float>(std::sqrt(d2));
            const double geometry = std::max(0.0f, glm::dot(x.normal, w)) * std::max(0.0f, -glm::dot(v.normal, w)) / d2;
            sum += furnace.albedo / kPi * geometry * v.intensity().g;
        }
        const double ratio = sum / count / expected;
        summary.meanEq5 += ratio / directions.size();
        summary.worstEq5 = std::max(summary.worstEq5, std::abs(ratio - 1.0));
    }
    return summary;
}

} // namespace

TEST_CASE("smcir furnace: radiance = closed forms, mean 1/p = sphere area, eq. (5) = rho L_all", "[smcir][numbers]")
{
    FurnaceParams furnace; // R = 1, rho = 0.5, I0 = pi: L_n = 0.5^n, L_all = 1
    const Scene scene = makeFurnace(furnace);
    const RayScene rays(scene);
    const double area = 4.0 * kPi * furnace.radius * furnace.radius;
    const double all = furnaceRadianceAll(furnace);

    // radiosityBounces = 3 (the default): every VPL carries L_1 + L_2 + L_3. Nothing is random in the
    // furnace except at the facets: a cosine direction about the smooth normal that falls below the
    // flat triangle's horizon ends its path (path tracer rule), which costs 1/16 of L_2 + L_3 = 2.7 %.
    {
        SMCIRSampler sampler(scene, rays, smallParams(256, 0));
        sampler.initialize(scene.cameras[0]);
        const double three = furnaceRadianceBounce(furnace, 1) + furnaceRadianceBounce(furnace, 2) +
                             furnaceRadianceBounce(furnace, 3);
        double worst = 0.0, mean = 0.0;
        for (const VPL& v : sampler.vpls().slots) {
            REQUIRE(v.valid);
            CHECK(std::abs(glm::length(v.position) - furnace.radius) < 1e-3f); // on the wall
            worst = std::max(worst, std::abs(v.radiance.g / three - 1.0));
            mean += v.radiance.g / three / 256.0;
        }
        MEASURED("smcir furnace, VPL radiance (16 samples, 3 bounces) / (L1 + L2 + L3): mean " << mean << ", worst "
                 << worst);
        CHECK(mean == Approx(1.0).epsilon(3e-3));
        CHECK(worst < 0.03);
    }

    // All bounces, right after initialization (line 1: candidates resampled to uniform in area, no
    // selection yet): radiance L_all, mean 1/p = 4 pi R^2 (E[1/p] is exact, MATH.md 2) and eq. (5)
    // = rho L_all. A large rendering k keeps the kNN noise small. This pins the normalisation:
    // 1/I, L (not B = pi L), p integrating to 1. Eq. (7) as MATH.md 2 reads it (self excluded).
    SMCIRParams params = smallParams(512, 0);
    params.radiosityBounces = 40;
    params.radiositySamples = 64;
    params.knnRender = 32;
    params.knnCountsSelf = false;
    {
        SMCIRSampler sampler(scene, rays, params);
        sampler.initialize(scene.cameras[0]);
        REQUIRE(sampler.vpls().validCount() == 512);
        const FurnaceSummary initial = summarizeFurnace(scene, rays, furnace, sampler.vpls());
        std::printf("measured: smcir furnace, initialized (I = 512, k = 32): mean L = %.4f (L_all %.4f), mean 1/p = %.3f m^2 "
                    "(4 pi R^2 = %.3f), eq. (5) / (rho L_all) = %.4f, worst error %.2f %%\n",
                    initial.meanRadiance, all, initial.meanInverseDensity, area, initial.meanEq5,
                    100.0 * initial.worstEq5);
        CHECK(initial.meanRadiance == Approx(all).epsilon(0.01));
        CHECK(initial.meanInverseDensity == Approx(area).epsilon(0.03));
        CHECK(initial.worstEq5 < 0.03);
    }
    // smcir.knnCountsSelf (the default): y is its own first neighbour, r the distance to the
    // (k-1)-th other, so on a fresh (Poisson) set E[1/p] = (k-1)/k of the area: 0.75 at k = 4.
    {
        SMCIRParams self = params;
        self.knnCountsSelf = true;
        self.knnRender = 4;
        SMCIRSampler sampler(scene, rays, self);
        sampler.initialize(scene.cameras[0]);
        const double ratio = summarizeFurnace(scene, rays, furnace, sampler.vpls()).meanInverseDensity / area;
        MEASURED("smcir furnace, initialized (I = 512, k = 4, y counted): mean 1/p / area " << ratio << " (closed form 0.75)");
        // The k = 4 estimate's noise over 512 VPLs is about 1/sqrt(4 * 512) = 2%; 0.04 is 2x it, and
        // far from the self-excluded 1.
        CHECK(std::abs(ratio - 0.75) < 0.04);
    }

    // After 20 frames the set is blue noise (candidates are ranked with k = 1, 3.2.4), and kNN on a
    // repulsive set over-estimates 1/p: the paper's estimator is biased, though consistent (3.3),
    // and the bias falls as k grows. It also keeps the VPLs whose frozen radiance estimate came out
    // high (ranking by a noisy L). Measured: 1/p +14 % at k = 4 (eq. 8 at I = 512), +3 % at k = 32.
    // The paper's selection (ranked by the rendered values, self excluded); core/vpl/smcir_selection.h
    // and tests/cpu/test_smcir_selection.cpp measure the default one.
    auto warmed = [&](int knnRender) {
        SMCIRParams p = params;
        p.rankRadiance = kRankByRenderedRadiance;
        p.warmupIterations = 20;
        p.radiositySamples = 16;
        p.knnRender = knnRender;
        SMCIRSampler sampler(scene, rays, p);
        sampler.initialize(scene.cameras[0]);
        return summarizeFurnace(scene, rays, furnace, sampler.vpls());
    };
    const FurnaceSummary eq8 = warmed(0), wide = warmed(32);
    std::printf("measured: smcir furnace, 20 warm-up frames (I = 512): k = 4: mean L %.4f, mean 1/p / area %.4f, eq. (5) %.4f;"
                " k = 32: mean L %.4f, mean 1/p / area %.4f, eq. (5) %.4f\n",
                eq8.meanRadiance / all, eq8.meanInverseDensity / area, eq8.meanEq5, wide.meanRadiance / all,
                wide.meanInverseDensity / area, wide.meanEq5);
    CHECK(eq8.meanInverseDensity / area > 1.0);
    CHECK(eq8.meanInverseDensity / area < 1.25);
    CHECK(wide.meanInverseDensity / area < eq8.meanInverseDensity / area);
    CHECK(wide.meanInverseDensity / area == Approx(1.0).epsilon(0.06));
    CHECK(eq8.meanRadiance / all == Approx(1.0).epsilon(0.1));
    CHECK(eq8.meanEq5 > 1.0);
    CHECK(eq8.meanEq5 < 1.35);
}

TEST_CASE("smcir indirect visibility: no VPL where no camera-visible point can see (sealed rooms)", "[smcir]")
{
    const SealedRooms rooms;
    const RayScene rays(rooms.scene);
    SMCIRParams params = smallParams(256, 3);
    params.maxMoves = 32;
    SMCIRSampler sampler(rooms.scene, rays, params);
    sampler.initialize(rooms.inA);
    auto count = [&](auto predicate) {
        int n = 0;
        for (const VPL& v : sampler.vpls().slots)
            if (v.valid && predicate(v.position)) ++n;
        return n;
    };
    REQUIRE(sampler.vpls().validCount() == 256);
    CHECK(count([&](const glm::vec3& p) { return rooms.inRoomA(p); }) == 256);

    // Teleport into room B: no point of B sees a VPL of A, so every VPL of A is invalid, and each
    // frame removes exactly min(M_max, |A|) of them (CLAMPSIZE), invalid ones first.
    int inA = 256;
    int frames = 0;
    while (inA > 0 && frames < 20) {
        sampler.step(rooms.inB);
        ++frames;
        const SMCIRStageTimes& times = sampler.lastTimes();
        CHECK(times.invalidated == inA);
        const int nowInA = count([&](const glm::vec3& p) { return rooms.inRoomA(p); });
        CHECK(nowInA == std::max(0, inA - params.maxMoves));
        CHECK(times.moved <= params.maxMoves);
        CHECK(times.moved >= std::min(params.maxMoves, inA));
        inA = nowInA;
    }
    CHECK(frames == 256 / 32);
    for (int i = 0; i < 5; ++i)
        sampler.step(rooms.inB);
    CHECK(sampler.lastTimes().invalidated == 0); // a static camera keeps every VPL's mail box valid
    CHECK(count([&](const glm::vec3& p) { return rooms.inRoomB(p); }) == 256);
    // C is lit from inside by the brightest light, but no ray from B gets in.
    CHECK(count([&](const glm::vec3& p) { return rooms.inBox(p); }) == 0);
    CHECK(count([&](const glm::vec3& p) { return rooms.onBoxOutside(p); }) > 0);
}

TEST_CASE("smcir validation rays re-validate VPLs that lost their mail box (3.2.2)", "[smcir]")
{
    // Inside room B the camera turns round: most associated points leave the view, but every wall
    // of the closed room still sees almost every VPL, so the validation rays must find them again
    // and re-associate them with points the camera sees now.
    const SealedRooms rooms;
    const RayScene rays(rooms.scene);
    SMCIRSampler sampler(rooms.scene, rays, smallParams(256, 3));
    sampler.initialize(rooms.inB);
    sampler.step(rooms.inB);
    CHECK(sampler.lastTimes().mailboxMisses == 0);
    const Camera turned = lookAt({5.5f, 1.6f, -2.5f}, {0.6f, 1.2f, 2.9f});
    sampler.step(turned);
    const SMCIRStageTimes first = sampler.lastTimes();
    sampler.step(turned);
    const SMCIRStageTimes second = sampler.lastTimes();
    std::printf("smcir validation: after turning, %d of 256 mail boxes missed, %d still invalid after the rays;"
                " next frame %d missed\n",
                first.mailboxMisses, first.invalidated, second.mailboxMisses);
    CHECK(first.mailboxMisses > 64);
    CHECK(first.invalidated < first.mailboxMisses / 5);
    // Re-validated VPLs hold a point the camera sees: only the still-invalid ones miss again.
    CHECK(second.mailboxMisses <= first.invalidated);
    // No validation rays: every miss stays invalid.
    SMCIRParams noRays = smallParams(256, 3);
    noRays.validationIterations = 0;
    SMCIRSampler blind(rooms.scene, rays, noRays);
    blind.initialize(rooms.inB);
    blind.step(turned);
    CHECK(blind.lastTimes().invalidated == blind.lastTimes().mailboxMisses);
    CHECK(blind.lastTimes().mailboxMisses > 64);
}

TEST_CASE("smcir stable slots: at most M_max slots change per frame, others keep their VPL (maze)", "[smcir]")
{
    const Scene scene = makeBuiltinScene("maze");
    const RayScene rays(scene);
    SMCIRParams params = smallParams(512, 3);
    SMCIRSampler sampler(scene, rays, params);
    const Camera base = scene.cameras[0];
    sampler.initialize(base);
    REQUIRE(sampler.vpls().changed.size() == 512); // everything is new to the renderer
    REQUIRE(sampler.vpls().validCount() == 512);

    int invalidated = 0, violations = 0;
    for (int frame = 0; frame < 24; ++frame) {
        // 12 frames with a static camera, then 12 walking through the door and turning.
        Camera camera = base;
        if (frame >= 12) {
            const float t = static_cast<float>(frame - 11) / 12.0f;
            camera.position = base.position + (base.target - base.position) * (0.9f * t);
            camera.target = base.target + glm::vec3(3.0f * std::sin(2.0f * t), 0.0f, 3.0f * std::cos(2.0f * t) - 3.0f);
        }
        const std::vector<VPL> before = sampler.vpls().slots;
        const std::uint64_t generation = sampler.vpls().generation;
        sampler.step(camera);
        const VPLSet& set = sampler.vpls();
        const std::set<std::uint32_t> changed(set.changed.begin(), set.changed.end());
        CHECK(set.changed.size() <= static_cast<std::size_t>(params.maxMoves));
        CHECK(changed.size() == set.changed.size());                       // no duplicates
        CHECK(std::is_sorted(set.changed.begin(), set.changed.end()));
        CHECK(static_cast<int>(set.changed.size()) == sampler.lastTimes().moved);
        CHECK(set.generation == generation + 1);
        for (std::size_t slot = 0; slot < set.slots.size(); ++slot) {
            if (changed.count(static_cast<std::uint32_t>(slot))) continue;
            const VPL& a = before[slot];
            const VPL& b = set.slots[slot];
            // Unchanged slots: same VPL, same cached radiance; only the density is re-estimated.
            if (a.valid != b.valid || a.position != b.position || a.normal != b.normal || a.radiance != b.radiance)
                ++violations;
        }
        if (frame < 12) CHECK(sampler.lastTimes().invalidated == 0);
        invalidated += sampler.lastTimes().invalidated;

        // Line 19 updates densities incrementally; it must equal a full kNN re-estimate bit for bit.
        std::vector<glm::vec3> positions;
        for (const VPL& v : set.slots)
            if (v.valid) positions.push_back(v.position);
        const std::size_t n = positions.size();
        // k of eq. (8); r to the k-th other VPL, or with knnCountsSelf (y its own first neighbour, k >= 2)
        // to the (k-1)-th other: the index holds y itself at distance 0.
        std::size_t k = static_cast<std::size_t>(computeRenderingK(params.vplCount));
        std::size_t neighbour = k + 1;
        if (params.knnCountsSelf) neighbour = k = std::max<std::size_t>(k, 2);
        const KNNIndex index(positions);
        int densityMismatches = 0;
        for (const VPL& v : set.slots)
            if (v.valid && v.density != estimateKNNDensity(k, n, index.kthDistanceSquared(v.position, neighbour)))
                ++densityMismatches;
        CHECK(densityMismatches == 0);
    }
    CHECK(violations == 0);
    CHECK(invalidated > 0); // the walk did exercise 3.2.2
    CHECK(sampler.vpls().validCount() == 512);
}

TEST_CASE("smcir converges in a static scene: intensities even out, then stay even (maze)", "[smcir][numbers]")
{
    // The initial VPLs are uniform in area, so their intensities L/p spread over orders of magnitude
    // (lit and unlit rooms). Each frame replaces up to M_max of the weakest with candidates stronger
    // than 95 % of the set (eq. 9); the spread must shrink, and once few candidates are strong the
    // set must stay put. The CoV of I is dominated by its few largest values; the standard deviation
    // of log I shows the bulk.
    const Scene scene = makeBuiltinScene("maze");
    const RayScene rays(scene);
    SMCIRSampler sampler(scene, rays, smallParams(512, 0));
    const Camera camera = scene.cameras[0];
    sampler.initialize(camera);
    // The spread of log I over the valid VPLs, robust: the interquartile range / 1.349 (the standard
    // deviation for a normal distribution). Not the plain standard deviation: a new VPL whose
    // independent radiance estimate came out 0 (log I = -27.6 at the floor) lifts it from 0.54 to
    // 1.53 for one frame (measured on frame 46 of this run), which says nothing about the bulk.
    auto spreadOfLog = [](const VPLSet& set) {
        std::vector<double> logs;
        for (const VPL& v : set.slots)
            if (v.valid) logs.push_back(std::log(std::max(1e-12, static_cast<double>(luminance(v.intensity())))));
        std::sort(logs.begin(), logs.end());
        const auto quantile = [&](double q) { return logs[static_cast<std::size_t>(q * (logs.size() - 1))]; };
        return (quantile(0.75) - quantile(0.25)) / 1.349;
    };
    sampler.step(camera);
    const double firstCoV = intensityCoV(sampler.vpls()), firstLog = spreadOfLog(sampler.vpls());
    for (int i = 1; i < 30; ++i)
        sampler.step(camera);
    const double thirtyCoV = intensityCoV(sampler.vpls()), thirtyLog = spreadOfLog(sampler.vpls());
    double laterCoV = 0.0, worstLog = 0.0, moved = 0.0;
    for (int i = 0; i < 30; ++i) {
        sampler.step(camera);
        laterCoV += intensityCoV(sampler.vpls()) / 30.0;
        worstLog = std::max(worstLog, spreadOfLog(sampler.vpls()));
        moved += sampler.lastTimes().moved / 30.0;
    }
    std::printf("measured: smcir maze convergence (I = 512): CoV of I after 1 frame %.3f, after 30 %.3f, frames 31-60 mean %.3f;"
                " sd(log I) %.3f, %.3f, worst of 31-60 %.3f; moved per frame in 31-60 %.2f\n",
                firstCoV, thirtyCoV, laterCoV, firstLog, thirtyLog, worstLog, moved);
    // The bulk evens out (sd of log I). The CoV is ruled by the few largest intensities, i.e. by the
    // noise of the VPLs' own radiance estimates, which since independentRadiance the selection no
    // longer hides by keeping the estimates that came out high (measured 2.71 after 1 frame, 4.12
    // after 30, 2.98 over frames 31-60 on an AVX2 AMD EPYC; 3.31, 3.87, 3.34 where Embree took
    // another code path: one trajectory, which moves with the CPU): no check on it across the
    // first 30 frames. Robust sd(log I) measured 2.22, 0.49, worst of 31-60 0.47; moved 3.4 a frame.
    // On an AVX-512 EPYC (Embree's wider code path, the kd-tree and the grid kNN alike): 2.08, 0.49,
    // worst 0.53, i.e. worst / after-30 from 0.96 to 1.07 over the two trajectories; the bound 1.25 is
    // about 3x that spread above 1, and a set whose bulk spread regrew (2.1 at frame 1) still fails.
    CHECK(thirtyLog < 0.6 * firstLog);
    CHECK(laterCoV < thirtyCoV);
    CHECK(worstLog < 1.25 * thirtyLog);
    CHECK(moved < 0.25 * SMCIRParams{}.maxMoves); // few strong candidates left: the set settles
}

TEST_CASE("smcir caches radiance keyed by the lights, and a light change re-estimates with each VPL's seed", "[smcir]")
{
    FurnaceParams furnace;
    Scene scene = makeFurnace(furnace);
    const RayScene rays(scene);
    SMCIRParams params = smallParams(256, 2);
    params.radiosityBounces = 8; // some Russian roulette: radiance values differ between VPLs
    SMCIRSampler sampler(scene, rays, params);
    sampler.initialize(scene.cameras[0]);

    // Same lights: surviving VPLs keep their values bit for bit, and only the candidates and the new
    // VPLs (their own line-18 estimate: independentRadiance) are traced.
    const std::vector<VPL> before = sampler.vpls().slots;
    sampler.step(scene.cameras[0]);
    const SMCIRStageTimes cached = sampler.lastTimes();
    std::set<std::uint32_t> changed(sampler.vpls().changed.begin(), sampler.vpls().changed.end());
    CHECK(cached.radianceEstimates == cached.candidates + static_cast<int>(changed.size()));
    int survivors = 0, differ = 0;
    for (std::uint32_t slot = 0; slot < 256; ++slot) {
        if (changed.count(slot)) continue;
        ++survivors;
        if (sampler.vpls().slots[slot].radiance != before[slot].radiance) ++differ;
    }
    CHECK(survivors >= 256 - params.maxMoves);
    CHECK(differ == 0);

    // The light doubles in the next snapshot: nobody calls an "invalidate"; every VPL is traced again
    // with its own seed in that very step, so each survivor's value is exactly twice the old one (the
    // estimate is linear in the light, and the paths are the same).
    const std::vector<VPL> middle = sampler.vpls().slots;
    scene.lights[0].intensity *= 2.0f;
    sampler.step(FrameSnapshot::of(scene, scene.cameras[0], 16.0f / 9.0f));
    const SMCIRStageTimes fresh = sampler.lastTimes();
    changed = std::set<std::uint32_t>(sampler.vpls().changed.begin(), sampler.vpls().changed.end());
    // Survivors (new lights) and new VPLs, and the survivors' ranking values (smcir.rankRadiance =
    // candidate: re-estimated with their candidate seeds; the new VPLs' are this frame's candidates').
    const int survivorsNow = 256 - static_cast<int>(changed.size());
    CHECK(fresh.radianceEstimates == fresh.candidates + 256 + survivorsNow);
    int notDoubled = 0;
    for (std::uint32_t slot = 0; slot < 256; ++slot) {
        if (changed.count(slot)) continue;
        if (!(glm::vec3(2.0f) * middle[slot].radiance == sampler.vpls().slots[slot].radiance)) ++notDoubled;
    }
    CHECK(notDoubled == 0);
    // The same (doubled) lights again: the cache holds.
    sampler.step(scene.cameras[0]);
    CHECK(sampler.lastTimes().radianceEstimates ==
          sampler.lastTimes().candidates + static_cast<int>(sampler.vpls().changed.size()));
    // A snapshot with other lights than the scene's is what the sampler sees (it never reads
    // scene.lights during a step): halving them there re-estimates again.
    FrameSnapshot halved = FrameSnapshot::of(scene, scene.cameras[0], 16.0f / 9.0f);
    halved.lights[0].intensity *= 0.5f;
    sampler.step(halved);
    CHECK(sampler.lastTimes().radianceEstimates ==
          sampler.lastTimes().candidates + 256 + 256 - static_cast<int>(sampler.vpls().changed.size()));
}

TEST_CASE("smcir is deterministic: same seed and cameras give the same set at 1 and 2 threads", "[smcir]")
{
    const Scene scene = makeBuiltinScene("cornell");
    const RayScene rays(scene);
    const Camera base = scene.cameras[0];
    auto run = [&](int threads, std::uint32_t seed) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
        SMCIRParams params = smallParams(256, 2);
        params.seed = seed;
        SMCIRSampler sampler(scene, rays, params);
        sampler.initialize(base);
        std::vector<VPLSet> sets;
        for (int frame = 0; frame < 6; ++frame) {
            Camera camera = base;
            camera.position += glm::vec3(0.1f * frame, 0.05f * frame, -0.1f * frame);
            camera.target += glm::vec3(-0.2f * frame, 0.0f, 0.0f);
            sampler.step(camera);
            sets.push_back(sampler.vpls());
        }
        return sets;
    };
    const std::vector<VPLSet> two = run(2, 7u);
    const std::vector<VPLSet> again = run(2, 7u);
    const std::vector<VPLSet> one = run(1, 7u);
    const std::vector<VPLSet> otherSeed = run(2, 8u);
    bool sameAgain = true, sameOne = true, sameOther = true;
    for (std::size_t i = 0; i < two.size(); ++i) {
        sameAgain = sameAgain && identicalSets(two[i], again[i]);
        sameOne = sameOne && identicalSets(two[i], one[i]);
        sameOther = sameOther && identicalSets(two[i], otherSeed[i]);
    }
    CHECK(sameAgain);
    CHECK(sameOne);
    CHECK_FALSE(sameOther);
    CHECK(two.back().validCount() == 256);
}

namespace {

// A wall at x = 0 (facing +x, 10 m tall, 20 m wide) standing on a 10 x 20 m floor at y = 0 (facing
// up). A camera 4 m from the wall at 1.2 m height with a narrow field of view sees only the wall, so
// every candidate ray starts on the wall and meets the floor at a grazing angle: the raw hit density
// on the floor falls off as h / d^3 (about 40x between 0.5 m and 3 m from the wall).
Scene grazingFloor()
{
    Scene scene;
    scene.name = "grazing floor";
    Material m;
    m.baseColor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    m.specular = 0.0f;
    scene.materials.push_back(m);
    auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 n, int cells) {
        Mesh mesh;
        for (int j = 0; j <= cells; ++j)
            for (int i = 0; i <= cells; ++i) {
                Vertex v;
                const float u = float(i) / cells, w = float(j) / cells;
                v.position = glm::mix(glm::mix(a, b, u), glm::mix(d, c, u), w);
                v.normal = n;
                mesh.vertices.push_back(v);
            }
        for (int j = 0; j < cells; ++j)
            for (int i = 0; i < cells; ++i) {
                const std::uint32_t p = j * (cells + 1) + i, q = p + 1, r = p + (cells + 1), s = r + 1;
                mesh.indices.insert(mesh.indices.end(), {p, q, s, p, s, r});
            }
        // Counter-clockwise seen from the side `n` points to.
        const glm::vec3 e = glm::cross(mesh.vertices[1].position - mesh.vertices[0].position,
                                       mesh.vertices[cells + 2].position - mesh.vertices[0].position);
        if (glm::dot(e, n) < 0.0f)
            for (std::size_t t = 0; t < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
        scene.meshes.push_back(mesh);
        scene.instances.push_back(Instance{static_cast<int>(scene.meshes.size()) - 1, glm::mat4(1.0f)});
    };
    quad({0, 0, -10}, {10, 0, -10}, {10, 0, 10}, {0, 0, 10}, {0, 1, 0}, 8);  // floor
    quad({0, 0, -10}, {0, 10, -10}, {0, 10, 10}, {0, 0, 10}, {1, 0, 0}, 8);  // wall
    Camera camera = lookAt({4.0f, 1.2f, 0.0f}, {0.0f, 1.2f, 0.0f});
    camera.fovY = 0.17f; // ~10 degrees: the lowest ray meets the wall at y ~ 0.85, long before the floor
    scene.cameras.push_back(camera);
    scene.validate();
    return scene;
}

// Chi-square of the VPL counts on the floor in four equal-area bands x in [0.5, 3.5) (|z| < 1.5)
// against a uniform distribution, over several seeds; returns it with the total count.
std::pair<double, int> floorBandChiSquare(const Scene& scene, const RayScene& rays, SMCIRParams params)
{
    std::array<int, 4> counts{};
    for (std::uint32_t seed = 1; seed <= 6; ++seed) {
        params.seed = seed;
        SMCIRSampler sampler(scene, rays, params);
        sampler.initialize(scene.cameras[0]); // line 1: the VPLs are exactly the resampled candidates
        for (const VPL& v : sampler.vpls().slots) {
            if (!v.valid || v.position.y > 1e-3f || std::abs(v.position.z) >= 1.5f) continue;
            const float x = v.position.x;
            if (x >= 0.5f && x < 3.5f) ++counts[static_cast<std::size_t>((x - 0.5f) / 0.75f)];
        }
    }
    const int total = counts[0] + counts[1] + counts[2] + counts[3];
    const double expected = total / 4.0;
    double chi2 = 0.0;
    for (int c : counts) chi2 += (c - expected) * (c - expected) / expected;
    MEASURED("grazing floor, VPLs in four equal-area bands " << counts[0] << " " << counts[1] << " " << counts[2] << " "
             << counts[3] << ": chi-square " << chi2 << (params.candidateFactor == 1 ? " (no resampling)" : " (16:1 resampling)"));
    return {chi2, total};
}

} // namespace

TEST_CASE("smcir candidate resampling (3.2.1) is uniform in area on a floor seen at a grazing angle", "[smcir][numbers]")
{
    const Scene scene = grazingFloor();
    const RayScene rays(scene);
    SMCIRParams params = smallParams(2048, 0);
    // The floor receives no light: radiance is 0 and the sampler's selection plays no part; line 1
    // fills the slots with the resampled candidates, which is what is measured.
    // 16:1 resampling with weights 1/p_raw (k = 1, the paper's default): chi-square with 3 degrees of
    // freedom below 16.3 (p = 0.001) for a uniform distribution. Measured: 1.1-5 over seeds.
    const auto [chi2, total] = floorBandChiSquare(scene, rays, params);
    CHECK(total > 200);
    CHECK(chi2 < 16.3);
    // The test can fail: without resampling (candidateFactor 1: every raw hit is a candidate) the
    // bands hold the raw density, h / d^3, far from uniform (measured chi-square ~ 900).
    params.candidateFactor = 1;
    const auto raw = floorBandChiSquare(scene, rays, params);
    CHECK(raw.first > 100.0);
}

TEST_CASE("smcir VPLs see the untextured scene: mean material albedos, as section 5 says", "[smcir]")
{
    // The furnace sphere with a checker texture (sRGB 0.2 / 0.8 texels) on its wall: by default the
    // sampler must produce exactly the VPL set of the same sphere with the texture's mean albedo as
    // a plain factor; with smcir.texturedVPLs it must not.
    FurnaceParams furnace;
    Scene textured = makeFurnace(furnace);
    Image checker;
    checker.width = 2;
    checker.height = 2;
    const std::uint8_t dark = 51, light = 204; // 0.2 and 0.8 in sRGB
    checker.rgba = {dark, dark, dark, 255, light, light, light, 255, light, light, light, 255, dark, dark, dark, 255};
    textured.images.push_back(checker);
    for (Material& m : textured.materials) {
        m.baseColor = glm::vec4(1.0f);
        m.baseColorTexture.image = 0;
    }
    const UntexturedMaterials means = computeUntexturedMaterials(textured);
    auto srgb = [](float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); };
    const float expectedMean = 0.5f * (srgb(51.0f / 255.0f) + srgb(204.0f / 255.0f));
    CHECK(means.baseColor[0].g == Approx(expectedMean).epsilon(1e-6));

    Scene plain = makeFurnace(furnace);
    for (std::size_t i = 0; i < plain.materials.size(); ++i)
        plain.materials[i].baseColor = glm::vec4(means.baseColor[i], 1.0f);
    const RayScene texturedRays(textured), plainRays(plain);
    SMCIRParams params = smallParams(128, 2);
    SMCIRSampler a(textured, texturedRays, params), b(plain, plainRays, params);
    a.initialize(textured.cameras[0]);
    b.initialize(plain.cameras[0]);
    CHECK(identicalSets(a.vpls(), b.vpls()));
    params.texturedVPLs = true;
    SMCIRSampler c(textured, texturedRays, params);
    c.initialize(textured.cameras[0]);
    CHECK_FALSE(identicalSets(c.vpls(), b.vpls()));
}

TEST_CASE("smcir clamping: G_max = I / (clampScale D)^2 relaxes as I grows", "[smcir]")
{
    SMCIRParams params;
    CHECK(params.clampScale == 2.0f); // the measured default (core/vpl/smcir_sampler.h)
    params.clampScale = 1.0f;
    CHECK(computeClampGeometry(params, 2.0f) == Approx(2048.0 / 4.0).epsilon(1e-6)); // d = 2/sqrt(2048)
    params.vplCount = 8192;
    CHECK(computeClampGeometry(params, 2.0f) == Approx(8192.0 / 4.0).epsilon(1e-6));
    params.clampScale = 0.0f;
    CHECK(computeClampGeometry(params, 2.0f) == 0.0f);
}

TEST_CASE("smcir: VPLs render with radiance estimates independent of the ones they were selected on",
          "[smcir][numbers]")
{
    // Lines 9-17 keep the candidates whose (noisy, 16-sample) estimate came out high. Rendering with
    // that same value is biased high; line 18 with a fresh lifetime seed (independentRadiance) is not.
    // Measured: the published radiances against a 512-sample estimate at the same points.
    const Scene scene = makeBuiltinScene("cornell");
    const RayScene rays(scene);
    const ReflectedRadianceEstimator accurate(scene, rays, SMCIRParams{}.radiosityBounces);
    auto publishedOverAccurate = [&](bool independent) {
        SMCIRParams params = smallParams(256, 100); // the paper's warm-up
        params.independentRadiance = independent;
        SMCIRSampler sampler(scene, rays, params);
        sampler.initialize(scene.cameras[0]);
        double published = 0.0, truth = 0.0;
        std::uint32_t seed = 7000;
        for (const VPL& v : sampler.vpls().slots) {
            if (!v.valid) continue;
            Ray ray;
            ray.origin = v.position + v.normal * (1e-3f * rays.sceneScale());
            ray.direction = -v.normal;
            const Hit hit = rays.intersect(ray);
            REQUIRE(hit.valid());
            published += luminance(v.radiance);
            truth += luminance(accurate.estimate(surfaceAt(scene, hit, v.normal), 512, ++seed));
        }
        return published / truth - 1.0;
    };
    const double coupled = publishedOverAccurate(false);
    const double independent = publishedOverAccurate(true);
    MEASURED("smcir VPL radiance after 100 warm-up frames (I = 256), mean published / 512-sample estimate - 1: selected-on "
             << coupled << ", independent " << independent);
    // Measured +4.9% selected-on, +0.24% independent. The 512-sample reference has a relative error
    // of about 1% over 256 VPLs: 3% is 3x that; the coupled value must stand 3% above.
    CHECK(std::abs(independent) < 0.03);
    CHECK(coupled > independent + 0.03);
}
