// The IR sampler (core/vpl/ir_sampler.h, Keller's instant radiosity): the furnace closed forms through
// the CPU gather, exact flux bookkeeping for every emitter kind, the budget accounting in open and
// closed scenes, frames (re-seeded or fixed) and determinism.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include <tbb/global_control.h>

#include "core/scene/builtin_scenes.h"
#include "core/util/error.h"
#include "core/util/params.h"
#include "core/trace/ray_scene.h"
#include "core/vpl/ir_sampler.h"
#include "core/vpl/vpl_gather.h"
#include "core/vpl/vpl_pipeline.h"
#include "glsl/shared/lights.h"
#include "measured.h"
#include "vpl_sets.h"

using namespace vplgi;

namespace {

constexpr double kPi = 3.14159265358979323846;

using test::identicalSets;
using test::meanGreen;

IRParams irParams(int vplCount, int bounces, std::uint32_t seed = 1)
{
    IRParams params;
    params.vplCount = vplCount;
    params.bounces = bounces;
    params.seed = seed;
    return params;
}

// Flux the VPLs re-emit, sum_i pi I(y_i) / n [W] (core/vpl/ir_sampler.h: a VPL is a cosine emitter
// of flux rho_d alpha_i = pi I / n), green channel.
double reemittedFlux(const VPLSet& set)
{
    const double n = static_cast<double>(set.validCount());
    double sum = 0.0;
    for (const VPL& v : set.slots)
        if (v.valid) sum += kPi * v.intensity().g / n;
    return sum;
}

// The scene's first camera with one point light of intensity i0 [W/sr] at height h above the origin.
FrameSnapshot pointAbove(const Scene& scene, float h, float i0)
{
    FrameSnapshot snapshot = FrameSnapshot::of(scene, scene.cameras[0], 1.0f);
    Light point;
    point.type = LightType::Point;
    point.position = {0.0f, h, 0.0f};
    point.intensity = i0;
    snapshot.lights = {point};
    return snapshot;
}

// A single-sided floor [-a, a]^2 at y = 0 facing up (Lambert, albedo rho), nothing else: an open scene.
Scene openFloor(float a, float rho)
{
    Scene scene;
    scene.name = "open floor";
    Material m;
    m.baseColor = glm::vec4(rho, rho, rho, 1.0f);
    m.specular = 0.0f;
    scene.materials.push_back(m);
    Mesh mesh;
    for (glm::vec3 p : {glm::vec3(-a, 0, a), glm::vec3(a, 0, a), glm::vec3(a, 0, -a), glm::vec3(-a, 0, -a)}) {
        Vertex v;
        v.position = p;
        v.normal = {0, 1, 0};
        mesh.vertices.push_back(v);
    }
    mesh.indices = {0, 1, 2, 0, 2, 3};
    scene.meshes.push_back(mesh);
    scene.instances.push_back(Instance{0, glm::mat4(1.0f)});
    Camera camera;
    camera.position = {0.0f, 3.0f, 3.0f};
    scene.cameras.push_back(camera);
    scene.validate();
    return scene;
}

} // namespace

TEST_CASE("ir parameters: defaults, one field list, range checks", "[ir][params]")
{
    const IRParams defaults;
    CHECK(defaults.vplCount == 2048);
    CHECK(defaults.bounces == 3); // the paper's experiments
    CHECK(defaults.fixedSequence == false); // the paper's IR: re-seeded every frame
    CHECK(defaults.texturedVPLs == false);  // SMCIR section 5: untextured for all methods
    IRParams params;
    ParamDumper dump;
    params.visitParams(dump);
    CHECK(defaults.fillBudget == true);     // ours: a stronger baseline in open scenes (SMCIR 730-733)
    for (const char* key : {"ir.vplCount", "ir.bounces", "ir.pathCap", "ir.seed", "ir.fixedSequence", "ir.texturedVPLs",
                            "ir.fillBudget"})
        CHECK(dump.values().count(key) == 1);
    CHECK(dump.values().size() == 7);
    ParamSetter setter(Settings{{"ir.vplCount", "512"}, {"ir.fixedSequence", "true"}});
    params.visitParams(setter);
    setter.finish();
    CHECK(params.vplCount == 512);
    CHECK(params.fixedSequence);
    ParamSetter bad(Settings{{"ir.bounces", "0"}});
    CHECK_THROWS_AS(params.visitParams(bad), Error);

    const Scene scene = makeFurnace(FurnaceParams{});
    const RayScene rays(scene);
    CHECK_THROWS_AS(IRSampler(scene, rays, irParams(0, 3)), Error);
    IRSampler sampler(scene, rays, irParams(16, 3));
    CHECK_THROWS_AS(sampler.step(FrameSnapshot::of(scene, scene.cameras[0], 1.0f)), Error); // before initialize()
}

TEST_CASE("ir furnace: the gathered image is the closed form, bounces 1 and 3 (MATH.md 3)", "[ir][furnace][numbers]")
{
    // Deposits at hits 1..B carry the flux reaching them; a wall point gathers
    // (rho/pi)^2 / (4R^2) sum_i alpha_i, so B = 1 gives L_2 = rho^2 I0 / (pi R^2) (one-bounce
    // indirect) and B = 3 gives L_2 + L_3 + L_4 = rho (L_1 + L_2 + L_3) = 0.4375 (R = 1, rho = 0.5,
    // I0 = pi). No clamping: G = 1/(4R^2) for every pair.
    FurnaceParams furnace;
    const Scene scene = makeFurnace(furnace);
    const RayScene rays(scene);
    const FrameSnapshot snapshot = FrameSnapshot::of(scene, scene.cameras[0], 16.0f / 9.0f);
    auto relativeError = [&](int bounces, std::uint32_t seed, IRStats* stats) {
        IRSampler sampler(scene, rays, irParams(4096, bounces, seed));
        sampler.initialize(snapshot);
        if (stats) *stats = sampler.lastStats();
        const ImageRGBA32F image = renderVPLGather(scene, rays, scene.cameras[0], 12, 8, sampler.vpls(), VPLGatherParams{});
        double expected = 0.0;
        for (int n = 2; n <= bounces + 1; ++n) expected += furnaceRadianceBounce(furnace, n);
        return meanGreen(image) / expected - 1.0;
    };

    // One bounce: every path deposits exactly once with alpha = Phi / N and N = I: nothing random is
    // left but the VPL positions, and G is the same for all of them. What remains is the tessellation.
    IRStats stats;
    const double one = relativeError(1, 1u, &stats);
    CHECK(stats.paths == 4096u);
    CHECK(stats.pathsEscaped == 0u);
    CHECK(stats.vpls == 4096);
    // Three bounces: N is random (1 + rho + rho^2 = 1.75 deposits per path on average), so the
    // estimate has Monte Carlo noise of about sd(deposits) / (mean sqrt(N)) = 0.83 / (1.75 sqrt(2340))
    // ~ 1 %. Over 8 seeds: the mean error and the spread.
    double mean = 0.0, worst = 0.0;
    const int seeds = 8;
    for (std::uint32_t seed = 1; seed <= seeds; ++seed) {
        const double e = relativeError(3, seed, seed == 1 ? &stats : nullptr);
        mean += e / seeds;
        worst = std::max(worst, std::abs(e));
    }
    MEASURED("ir furnace (I = 4096, no clamping), relative error of the gathered image: bounces 1: "
             << one << "; bounces 3: mean over 8 seeds " << mean << ", worst " << worst << " (seed 1: N = "
             << stats.paths << " paths, escaped " << stats.pathsEscaped << ")");
    CHECK(stats.pathsEscaped == 0u); // closed: the budget is spent on deposits only
    CHECK(stats.escapedFraction() == 0.0);
    // Measured: bounces 1 +2.9e-4 (the tessellation: G is 1/(4R^2) only on the true sphere);
    // bounces 3, mean of 8 seeds +1.5e-3, worst seed 7.0e-3. Bounds about 3x those.
    CHECK(std::abs(one) < 1e-3);
    CHECK(std::abs(mean) < 5e-3);
    CHECK(worst < 0.02);
}

TEST_CASE("ir budget: an open floor under a point or a directional light reports the escaped paths", "[ir][numbers]")
{
    // A 4 x 4 m floor, nothing else. Point light 1 m above its centre: a path deposits (once: the
    // next ray goes up and leaves) exactly when its first direction meets the floor, with
    // probability Omega / (4 pi), Omega = 4 asin(a^2 / (a^2 + h^2)) the floor's solid angle. The
    // re-emitted flux sum pi I / n = rho I0 Omega in expectation. Directional light: the disk of
    // the bounding sphere (radius r = sqrt(8) m) sends E pi r^2, the floor intercepts E A cos(theta).
    const float a = 2.0f, h = 1.0f, rho = 0.6f, i0 = 5.0f, irradiance = 2.0f;
    Scene scene = openFloor(a, rho);
    const RayScene rays(scene);
    FrameSnapshot snapshot = pointAbove(scene, h, i0);
    IRSampler sampler(scene, rays, irParams(4096, 3));
    sampler.initialize(snapshot);
    const IRStats pointStats = sampler.lastStats();
    const double omega = 4.0 * std::asin(a * a / (a * a + h * h));
    const double hit = omega / (4.0 * kPi);
    const double pointSigma = std::sqrt(hit * (1.0 - hit) / static_cast<double>(pointStats.paths));
    const double pointFlux = reemittedFlux(sampler.vpls());
    const double pointFluxExpected = rho * i0 * omega;

    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    sun.intensity = irradiance;
    snapshot.lights = {sun};
    sampler.step(snapshot);
    const IRStats sunStats = sampler.lastStats();
    const double r2 = 2.0 * a * a; // bounding-sphere radius squared: half the diagonal of (2a, 0, 2a)
    const double cosTheta = -sun.direction.y;
    const double sunHit = (4.0 * a * a * cosTheta) / (kPi * r2);
    const double sunSigma = std::sqrt(sunHit * (1.0 - sunHit) / static_cast<double>(sunStats.paths));
    const double sunFlux = reemittedFlux(sampler.vpls());
    const double sunFluxExpected = rho * irradiance * 4.0 * a * a * cosTheta;

    MEASURED("ir open floor, point light: escaped fraction " << pointStats.escapedFraction() << " (closed form "
             << 1.0 - hit << ", sd " << pointSigma << "), N = " << pointStats.paths << ", re-emitted flux / rho I0 Omega = "
             << pointFlux / pointFluxExpected << "; directional: escaped " << sunStats.escapedFraction()
             << " (closed form " << 1.0 - sunHit << ", sd " << sunSigma << "), flux ratio " << sunFlux / sunFluxExpected);
    CHECK(pointStats.vpls == 4096);
    CHECK(pointStats.escapedFraction() > 0.5); // the upper half of the sphere alone
    // 4 sd of the binomial. Measured with seed 1: the point light 2.2 sd from the closed form, the
    // directional 1.2 sd (over 200 seeds the mean escaped fraction of the point light is 0.6 sd of
    // that mean from it: no bias). A wrong flux, solid angle or disk misses by far more.
    CHECK(std::abs(pointStats.escapedFraction() - (1.0 - hit)) < 4.0 * pointSigma);
    CHECK(std::abs(pointFlux / pointFluxExpected - 1.0) < 4.0 * pointSigma / hit);
    CHECK(std::abs(sunStats.escapedFraction() - (1.0 - sunHit)) < 4.0 * sunSigma);
    CHECK(std::abs(sunFlux / sunFluxExpected - 1.0) < 4.0 * sunSigma / sunHit);
}

TEST_CASE("ir.fillBudget=false, the paper's IR: escaping photons leave slots empty, a closed scene fills them",
          "[ir][numbers]")
{
    // The open floor under a point light 1 m up: a path deposits once, with probability
    // hit = Omega / (4 pi), or escapes. The paper's IR emits the N that fills the budget had no path
    // escaped, N = I here, so hit I slots are used; the flux estimate is unbiased either way.
    const float a = 2.0f, h = 1.0f, rho = 0.6f, i0 = 5.0f;
    Scene scene = openFloor(a, rho);
    const RayScene rays(scene);
    FrameSnapshot snapshot = pointAbove(scene, h, i0);
    IRParams params = irParams(4096, 3);
    params.fillBudget = false;
    IRSampler sampler(scene, rays, params);
    sampler.initialize(snapshot);
    const IRStats stats = sampler.lastStats();
    const double hit = 4.0 * std::asin(a * a / (a * a + h * h)) / (4.0 * kPi);
    const double used = static_cast<double>(stats.vpls) / 4096.0;
    const double sigma = std::sqrt(hit * (1.0 - hit) / 4096.0);
    const double flux = reemittedFlux(sampler.vpls()) / (rho * i0 * 4.0 * std::asin(a * a / (a * a + h * h)));
    MEASURED("ir.fillBudget=false, open floor: N = " << stats.paths << ", slots used " << used << " (closed form " << hit
             << ", sd " << sigma << "), re-emitted flux / closed form " << flux);
    CHECK(stats.paths == 4096u); // every path that stays deposits once: N = I
    CHECK(std::abs(used - hit) < 4.0 * sigma); // 4 sd of the binomial, as the test above
    CHECK(std::abs(flux - 1.0) < 4.0 * sigma / hit);

    // A closed scene: nothing escapes, so both readings stop at the same path, bit for bit.
    const Scene furnace = makeFurnace(FurnaceParams{});
    const RayScene furnaceRays(furnace);
    const FrameSnapshot inside = FrameSnapshot::of(furnace, furnace.cameras[0], 1.0f);
    IRSampler ours(furnace, furnaceRays, irParams(1024, 3));
    IRParams paperParams = irParams(1024, 3);
    paperParams.fillBudget = false;
    IRSampler paper(furnace, furnaceRays, paperParams);
    ours.initialize(inside);
    paper.initialize(inside);
    CHECK(paper.lastStats().vpls == 1024);
    CHECK(paper.lastStats().paths == ours.lastStats().paths);
    bool same = true;
    for (std::size_t i = 0; i < 1024; ++i)
        same = same && paper.vpls().slots[i].position == ours.vpls().slots[i].position &&
               paper.vpls().slots[i].radiance == ours.vpls().slots[i].radiance;
    CHECK(same);
}

TEST_CASE("ir spot and emissive-triangle emitters: flux and direction distribution in the furnace", "[ir][numbers]")
{
    // In the closed furnace with bounces = 1 every path deposits exactly once with alpha = Phi / N,
    // so the re-emitted flux is rho Phi up to rounding, and the VPL directions from the centre are
    // the emitter's direction distribution.
    FurnaceParams furnace;
    const Scene scene = makeFurnace(furnace);
    const RayScene rays(scene);
    FrameSnapshot snapshot = FrameSnapshot::of(scene, scene.cameras[0], 1.0f);
    Light spot;
    spot.type = LightType::Spot;
    spot.position = glm::vec3(0.0f);
    spot.direction = glm::normalize(glm::vec3(0.2f, 0.3f, -1.0f));
    spot.intensity = 3.0f;
    spot.innerConeAngle = 0.3f;
    spot.outerConeAngle = 0.7f;
    snapshot.lights = {spot};
    IRSampler sampler(scene, rays, irParams(8192, 1));
    sampler.initialize(snapshot);
    REQUIRE(sampler.lastStats().paths == 8192u);

    // The spot's flux by quadrature of the shared profile (glsl/shared/lights.h) over cos theta.
    shared::PointEmitter e{};
    e.positionProfile = glm::vec4(0.0f, 0.0f, 0.0f, float(shared::kProfileSpot));
    e.axisCosOuter = glm::vec4(0.0f, 0.0f, 1.0f, std::cos(spot.outerConeAngle));
    e.cosInner = glm::vec4(std::cos(spot.innerConeAngle), 0.0f, 0.0f, 0.0f);
    const int steps = 200000;
    double integral = 0.0, innerShare = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double c = -1.0 + 2.0 * (i + 0.5) / steps;
        const double s = std::sqrt(1.0 - c * c);
        const double profile = shared::emitterProfile(e, glm::vec3(static_cast<float>(s), 0.0f, static_cast<float>(c)));
        integral += profile * 2.0 / steps;
        if (c >= std::cos(spot.innerConeAngle)) innerShare += profile * 2.0 / steps;
    }
    const double spotFlux = 2.0 * kPi * spot.intensity * integral;
    innerShare /= integral;
    int inner = 0;
    for (const VPL& v : sampler.vpls().slots)
        if (glm::dot(glm::normalize(v.position), spot.direction) >= std::cos(spot.innerConeAngle)) ++inner;
    const double innerFraction = inner / 8192.0;
    const double innerSigma = std::sqrt(innerShare * (1.0 - innerShare) / 8192.0);
    const double spotRatio = reemittedFlux(sampler.vpls()) / (furnace.albedo * spotFlux);

    // A Lambertian emissive triangle at the centre facing +z (single-sided, then double-sided).
    auto withTriangle = [&](bool doubleSided) {
        Scene s = makeFurnace(furnace);
        Material glow;
        glow.baseColor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
        glow.emission = glm::vec3(2.0f);
        glow.doubleSided = doubleSided;
        s.materials.push_back(glow);
        Mesh mesh;
        mesh.material = static_cast<int>(s.materials.size()) - 1;
        for (glm::vec3 p : {glm::vec3(-0.05f, -0.05f, 0.0f), glm::vec3(0.05f, -0.05f, 0.0f), glm::vec3(0.0f, 0.05f, 0.0f)}) {
            Vertex v;
            v.position = p;
            v.normal = {0, 0, 1};
            mesh.vertices.push_back(v);
        }
        mesh.indices = {0, 1, 2};
        s.meshes.push_back(mesh);
        s.instances.push_back(Instance{static_cast<int>(s.meshes.size()) - 1, glm::mat4(1.0f)});
        s.lights.clear();
        return s;
    };
    const double area = 0.5 * 0.1 * 0.1;
    struct TriangleResult {
        double fluxRatio = 0.0, share = 0.0;
    };
    auto runTriangle = [&](bool doubleSided) {
        const Scene s = withTriangle(doubleSided);
        const RayScene r(s);
        IRSampler triangleSampler(s, r, irParams(8192, 1));
        triangleSampler.initialize(FrameSnapshot::of(s, s.cameras[0], 1.0f));
        const VPLSet& set = triangleSampler.vpls();
        int count = 0;
        for (const VPL& v : set.slots) // single-sided: within 60 degrees of +z; double-sided: z > 0
            if (doubleSided ? v.position.z > 0.0f : glm::normalize(v.position).z >= 0.5f) ++count;
        TriangleResult result;
        result.fluxRatio = reemittedFlux(set) / (furnace.albedo * kPi * 2.0 * area * (doubleSided ? 2.0 : 1.0));
        result.share = count / static_cast<double>(set.validCount());
        return result;
    };
    const TriangleResult single = runTriangle(false), both = runTriangle(true);
    // Cosine emission: the share within 60 degrees of the normal is sin^2(60) = 0.75.
    const double singleSigma = std::sqrt(0.75 * 0.25 / 8192.0), bothSigma = std::sqrt(0.25 / 8192.0);
    MEASURED("ir furnace emitters (I = 8192, bounces 1): spot flux / rho Phi - 1 = " << spotRatio - 1.0 << ", share inside the inner cone "
             << innerFraction << " (profile " << innerShare << ", sd " << innerSigma << "); emissive triangle flux ratio - 1 "
             << single.fluxRatio - 1.0 << ", share within 60 deg " << single.share << " (0.75, sd " << singleSigma
             << "); double-sided flux ratio - 1 " << both.fluxRatio - 1.0 << ", front share " << both.share << " (0.5)");
    // Every path deposits once with the same alpha: the flux is exact up to float rounding of the
    // VPL intensities (measured: 9e-8 spot, -2e-8 triangles, float rounding); the bound 1e-6 leaves
    // room for rounding only, and the spot quadrature (200k midpoints) is good to ~1e-9 there.
    // The shares: measured 0.4, 0.5 and 0.5 sd of the binomial from the profile; bound 4 sd.
    CHECK(std::abs(spotRatio - 1.0) < 1e-6);
    CHECK(std::abs(single.fluxRatio - 1.0) < 1e-6);
    CHECK(std::abs(both.fluxRatio - 1.0) < 1e-6);
    CHECK(std::abs(innerFraction - innerShare) < 4.0 * innerSigma);
    CHECK(std::abs(single.share - 0.75) < 4.0 * singleSigma);
    CHECK(std::abs(both.share - 0.5) < 4.0 * bothSigma);
}

TEST_CASE("ir frames: re-seeded sets differ, fixed sequences repeat, changed lists moved slots only", "[ir]")
{
    const Scene scene = makeBuiltinScene("cornell");
    const RayScene rays(scene);
    const FrameSnapshot snapshot = FrameSnapshot::of(scene, scene.cameras[0], 16.0f / 9.0f);

    IRSampler sampler(scene, rays, irParams(512, 3));
    sampler.initialize(snapshot);
    REQUIRE(sampler.vpls().validCount() == 512);
    CHECK(sampler.vpls().changed.size() == 512); // everything is new to the renderer
    const VPLSet first = sampler.vpls();
    sampler.step(snapshot);
    const VPLSet second = sampler.vpls();
    CHECK_FALSE(identicalSets(first, second));
    CHECK(second.changed.size() > 500); // a new sequence moves (nearly) every slot
    CHECK(second.generation == first.generation + 1);

    IRParams fixed = irParams(512, 3);
    fixed.fixedSequence = true;
    IRSampler still(scene, rays, fixed);
    still.initialize(snapshot);
    const VPLSet a = still.vpls();
    still.step(snapshot);
    const VPLSet b = still.vpls();
    still.step(snapshot);
    CHECK(identicalSets(a, b));
    CHECK(identicalSets(b, still.vpls()));
    CHECK(b.changed.empty());
    CHECK(still.vpls().changed.empty());
    CHECK(identicalSets(a, first)); // frame 0 of the re-seeded sampler is the same sequence

    // A moving light moves the VPLs of a fixed sequence too: the paths start elsewhere.
    FrameSnapshot moved = snapshot;
    Light lamp; // above the blocks
    lamp.type = LightType::Point;
    lamp.position = scene.worldBounds().center() + glm::vec3(0.0f, 0.25f * scene.worldBounds().extent().y, 0.0f);
    lamp.intensity = 1.0f;
    moved.lights.push_back(lamp);
    still.step(moved);
    CHECK_FALSE(still.vpls().changed.empty());
}

TEST_CASE("ir is deterministic: same seed, same sets at 1 and 2 threads, other seed differs", "[ir]")
{
    const Scene scene = makeBuiltinScene("cornell");
    const RayScene rays(scene);
    const FrameSnapshot snapshot = FrameSnapshot::of(scene, scene.cameras[0], 16.0f / 9.0f);
    auto run = [&](int threads, std::uint32_t seed) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
        IRSampler sampler(scene, rays, irParams(1024, 3, seed));
        sampler.initialize(snapshot);
        std::vector<VPLSet> sets{sampler.vpls()};
        for (int frame = 0; frame < 3; ++frame) {
            sampler.step(snapshot);
            sets.push_back(sampler.vpls());
        }
        return sets;
    };
    const std::vector<VPLSet> two = run(2, 7u), again = run(2, 7u), one = run(1, 7u), other = run(2, 8u);
    bool sameAgain = true, sameOne = true, sameOther = true;
    for (std::size_t i = 0; i < two.size(); ++i) {
        sameAgain = sameAgain && identicalSets(two[i], again[i]) && two[i].changed == again[i].changed;
        sameOne = sameOne && identicalSets(two[i], one[i]) && two[i].changed == one[i].changed;
        sameOther = sameOther && identicalSets(two[i], other[i]);
    }
    CHECK(sameAgain);
    CHECK(sameOne);
    CHECK_FALSE(sameOther);
}

TEST_CASE("ir behind the VPL pipeline: the published set is the sampler's, with its statistics", "[ir][numbers]")
{
    // The GPU technique builds IRSampler(scene, rays, params) like SMCIRSampler and runs it through
    // VPLPipeline; a synchronous advance publishes the step's set and stats.
    const Scene scene = makeBuiltinScene("cornell");
    const RayScene rays(scene);
    const FrameSnapshot snapshot = FrameSnapshot::of(scene, scene.cameras[0], 16.0f / 9.0f);
    VPLPipeline pipeline(std::make_unique<IRSampler>(scene, rays, irParams(2048, 3)));
    pipeline.advance(snapshot, true);
    const VPLSet& set = pipeline.advance(snapshot, true);
    IRSampler reference(scene, rays, irParams(2048, 3));
    reference.initialize(snapshot);
    reference.step(snapshot);
    CHECK(identicalSets(set, reference.vpls()));
    double paths = 0.0, escaped = -1.0, ms = -1.0;
    for (const auto& [name, value] : pipeline.stats()) {
        if (name == "ir: paths") paths = value;
        if (name == "ir: escaped fraction") escaped = value;
        if (name == "sampler: total ms") ms = value;
    }
    MEASURED("ir cornell (I = 2048, 3 bounces): " << paths << " paths, escaped fraction " << escaped << ", " << ms
             << " ms per frame (2 threads, shared machine)");
    CHECK(paths == static_cast<double>(reference.lastStats().paths));
    CHECK(escaped == reference.lastStats().escapedFraction());
    CHECK(ms >= 0.0);
}
