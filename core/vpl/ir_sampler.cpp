#include "core/vpl/ir_sampler.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/scene/direct_lights.h"
#include "core/util/basis.h"
#include "core/util/error.h"
#include "core/util/params.h"
#include "core/util/random.h"
#include "glsl/shared/tonemap.h"

namespace vplgi {

void IRParams::visitParams(ParamVisitor& v)
{
    v.field("ir.vplCount", vplCount, 1, 1 << 20, "I: VPL budget (slots)");
    v.field("ir.bounces", bounces, 1, 64, "most surface hits per light path that deposit a VPL (paper: 3)");
    v.field("ir.pathCap", pathCap, 1, 65536, "at most pathCap * I light paths per frame (open scenes)");
    v.field("ir.fillBudget", fillBudget,
            "emit paths until every slot is taken (ours); false = the paper's IR: the path count that would fill "
            "the budget in a closed scene, so escaping photons leave slots empty (SMCIR 730-733)");
    v.field("ir.seed", seed, "random stream seed (same seed and lights, same VPLs)");
    v.field("ir.fixedSequence", fixedSequence,
            "the same random sequence every frame (Wald et al., SMCIR 2.3); false = re-seed every frame as the "
            "paper's IR");
    v.field("ir.texturedVPLs", texturedVPLs,
            "VPLs on the textured scene; false = untextured, mean material albedos (SMCIR section 5)");
}

namespace {

using Clock = std::chrono::steady_clock;
constexpr float kPi = 3.14159265358979323846f;

Pcg32 pathStream(std::uint32_t seed, std::uint64_t frameKey, std::uint64_t path)
{
    // Distinct from the SMCIR sampler's stages by the leading constant.
    const std::uint64_t key = mix64(mix64(mix64((static_cast<std::uint64_t>(seed) << 32u) ^ 0x1B5EEDull) ^ frameKey) ^ path);
    return Pcg32(key, mix64(key ^ 0xD1B54A32D192ED03ull));
}

// Cosine-weighted direction about unit n (density cos / pi).
glm::vec3 cosineDirection(const glm::vec3& n, float u1, float u2)
{
    glm::vec3 t, b;
    makeBasis(n, t, b);
    const float r = std::sqrt(u1), phi = 2.0f * kPi * u2;
    return glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0f, 1.0f - u1)) * n);
}

// Unit vector with cosine c about unit axis and azimuth 2 pi u.
glm::vec3 coneDirection(const glm::vec3& axis, float c, float u)
{
    glm::vec3 t, b;
    makeBasis(axis, t, b);
    const float s = std::sqrt(std::max(0.0f, 1.0f - c * c)), phi = 2.0f * kPi * u;
    return glm::normalize(s * std::cos(phi) * t + s * std::sin(phi) * b + c * axis);
}

} // namespace

// One light the paths start from.
struct IRSampler::Emitter {
    enum class Kind { Point, Spot, Directional, Triangle } kind = Kind::Point;
    glm::vec3 position{0.0f};  // point, spot
    glm::vec3 axis{0.0f};      // spot axis, directional travel direction, triangle front normal (unit)
    glm::vec3 flux{0.0f};      // Phi [W], RGB (a triangle's with its untextured emission factor)
    float power = 0.0f;        // shared::luminanceRec709(flux): the selection weight
    // Spot: the profile of glsl/shared/lights.h, t^2 with t = clamp((c - cosOuter) / ramp).
    float cosOuter = -1.0f;
    float ramp = 1.0f;         // max(cos inner - cos outer, 1e-4), as emitterProfile
    float rampShare = 0.0f;    // probability of the ramp part of the profile (c < cosOuter + ramp)
    // Triangle.
    glm::vec3 p0{0.0f}, p1{0.0f}, p2{0.0f};
    float area = 0.0f;
    float sides = 1.0f;        // 2 for double-sided materials
    int instance = -1, triangle = -1;
    bool textured = false;     // the emission texture modulates the factor
};

// A VPL deposited by a path before the slots are assigned.
struct IRSampler::Deposit {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f};
    glm::vec3 reflected{0.0f}; // rho_d(y) * alpha: the flux the VPL re-emits, times N [W]
};

IRSampler::IRSampler(const Scene& scene, const RayScene& rays, const IRParams& params)
    : mScene(scene), mRays(rays), mParams(params)
{
    const IRParams& p = params;
    require(p.vplCount >= 1 && p.vplCount <= (1 << 20), "ir.vplCount must be in [1, 2^20]");
    require(p.bounces >= 1 && p.bounces <= 64, "ir.bounces must be in [1, 64]");
    require(p.pathCap >= 1 && p.pathCap <= 65536, "ir.pathCap must be in [1, 65536]");
    require(&rays.scene() == &scene, "ir: the RayScene must be built from the sampler's scene");
    if (!p.texturedVPLs) mUntextured = computeUntexturedMaterials(scene);
    mOffset = 1e-4f * rays.sceneScale(); // as the path tracer
    const AABB bounds = scene.worldBounds();
    if (!bounds.empty()) {
        mBoundsCenter = bounds.center();
        mBoundsRadius = 0.5f * glm::length(bounds.extent());
    }

    // Emissive triangles (static geometry): Lambertian emitters of flux pi L_e A per side.
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        const Mesh& mesh = scene.meshes[instance.mesh];
        const Material& material = scene.materials[mesh.material];
        if (!material.isEmissive()) continue;
        auto world = [&](std::uint32_t v) {
            return glm::vec3(instance.worldFromObject * glm::vec4(mesh.vertices[v].position, 1.0f));
        };
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            Emitter e;
            e.kind = Emitter::Kind::Triangle;
            e.p0 = world(mesh.indices[3 * t]);
            e.p1 = world(mesh.indices[3 * t + 1]);
            e.p2 = world(mesh.indices[3 * t + 2]);
            const glm::vec3 cross = glm::cross(e.p1 - e.p0, e.p2 - e.p0);
            const float twiceArea = glm::length(cross);
            if (!(twiceArea > 0.0f)) continue;
            e.axis = instance.winding() * cross / twiceArea; // the emitting front (Instance::winding)
            e.area = 0.5f * twiceArea;
            e.sides = material.doubleSided ? 2.0f : 1.0f;
            e.flux = kPi * e.sides * e.area * material.emission;
            e.power = shared::luminanceRec709(e.flux);
            e.instance = static_cast<int>(i);
            e.triangle = static_cast<int>(t);
            e.textured = material.emissionTexture.valid();
            if (e.power > 0.0f) mTriangles.push_back(e);
        }
    }
    mSet.slots.assign(static_cast<std::size_t>(p.vplCount), VPL{});
}

IRSampler::~IRSampler() = default;

std::vector<IRSampler::Emitter> IRSampler::collectEmitters(const std::vector<Light>& lights) const
{
    // Punctual and directional lights exactly as the direct pass and the path tracer get them (the
    // cosine point samples standing in for emissive triangles are dropped: triangles are below).
    DirectLightParams directParams;
    directParams.emitterSamples = 1;
    const DirectLightSet direct = buildDirectLights(mScene, lights, directParams);
    std::vector<Emitter> emitters;
    for (const shared::PointEmitter& p : direct.points) {
        const int profile = static_cast<int>(p.positionProfile.w + 0.5f);
        if (profile == shared::kProfileCosine) continue;
        Emitter e;
        e.position = glm::vec3(p.positionProfile);
        const glm::vec3 intensity(p.intensity);
        if (profile == shared::kProfileSpot) {
            e.kind = Emitter::Kind::Spot;
            e.axis = glm::normalize(glm::vec3(p.axisCosOuter));
            e.cosOuter = p.axisCosOuter.w;
            e.ramp = std::max(p.cosInner.x - e.cosOuter, 1e-4f);
            // Integral of the profile over cos in [cosOuter, 1]: a ramp t^2 and, above it, a cap of 1.
            const float below = 1.0f - e.cosOuter; // length of [cosOuter, 1]
            float rampPart = 0.0f, capPart = 0.0f;
            if (below <= 0.0f) {
                continue; // a closed cone emits nothing
            } else if (e.ramp < below) {
                rampPart = e.ramp / 3.0f;
                capPart = below - e.ramp;
            } else {
                rampPart = below * below * below / (3.0f * e.ramp * e.ramp); // the ramp cut off at cos = 1
            }
            e.rampShare = rampPart / (rampPart + capPart);
            e.flux = 2.0f * kPi * (rampPart + capPart) * intensity;
        } else {
            e.kind = Emitter::Kind::Point;
            e.flux = 4.0f * kPi * intensity;
        }
        e.power = shared::luminanceRec709(e.flux);
        if (e.power > 0.0f) emitters.push_back(e);
    }
    for (const shared::DirectionalEmitter& d : direct.directionals) {
        Emitter e;
        e.kind = Emitter::Kind::Directional;
        e.axis = glm::normalize(glm::vec3(d.direction));
        e.flux = kPi * mBoundsRadius * mBoundsRadius * glm::vec3(d.irradiance); // E through the disk
        e.power = shared::luminanceRec709(e.flux);
        if (e.power > 0.0f) emitters.push_back(e);
    }
    emitters.insert(emitters.end(), mTriangles.begin(), mTriangles.end());
    return emitters;
}

int IRSampler::tracePath(const std::vector<Emitter>& emitters, const std::vector<double>& cdf, double totalPower,
                         std::uint64_t index, Deposit* deposits, std::uint64_t& rays) const
{
    Pcg32 rng = pathStream(mParams.seed, mParams.fixedSequence ? 0u : mFrame, index);

    // Step 1: an emitter with probability power / total. upper_bound never lands on a zero-power
    // emitter (there are none in the list).
    const double target = std::min(static_cast<double>(rng.uniform()) * totalPower, std::nextafter(totalPower, 0.0));
    const auto chosen = std::min(
        static_cast<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), target) - cdf.begin()), emitters.size() - 1);
    const Emitter& e = emitters[chosen];
    const float probability = static_cast<float>(e.power / totalPower);

    // alpha_0 * N = Phi_l / P_l: every sampling below is exact importance sampling of the emission,
    // so the weight does not depend on the point or direction drawn (MATH.md 1.3).
    glm::vec3 alpha = e.flux / probability;
    Ray ray;
    const float u1 = rng.uniform(), u2 = rng.uniform(), u3 = rng.uniform();
    switch (e.kind) {
    case Emitter::Kind::Point: {
        const float z = 1.0f - 2.0f * u1; // uniform on the sphere
        ray.origin = e.position;
        ray.direction = coneDirection(glm::vec3(0.0f, 0.0f, 1.0f), z, u2);
        break;
    }
    case Emitter::Kind::Spot: {
        // cos drawn with density proportional to the profile: the ramp ((c - cosOuter) / ramp)^2 has
        // the CDF ((c - cosOuter) / width)^3 over its part, the cap above it is uniform.
        float c;
        if (u3 < e.rampShare) {
            const float width = std::min(e.ramp, 1.0f - e.cosOuter);
            c = e.cosOuter + width * std::cbrt(u1);
        } else {
            c = e.cosOuter + e.ramp + u1 * (1.0f - e.cosOuter - e.ramp);
        }
        ray.origin = e.position;
        ray.direction = coneDirection(e.axis, std::min(c, 1.0f), u2);
        break;
    }
    case Emitter::Kind::Directional: {
        // A uniform point of the disk of radius r through the scene's bounding sphere, facing the light.
        glm::vec3 t, b;
        makeBasis(e.axis, t, b);
        const float r = mBoundsRadius * std::sqrt(u1), phi = 2.0f * kPi * u2;
        ray.origin = mBoundsCenter - e.axis * (2.0f * mBoundsRadius) + r * std::cos(phi) * t + r * std::sin(phi) * b;
        ray.direction = e.axis;
        break;
    }
    case Emitter::Kind::Triangle: {
        // A uniform point (Embree barycentrics b1, b2) and a cosine direction from a side.
        const float root = std::sqrt(u1);
        const float b1 = root * (1.0f - u2), b2 = root * u2;
        const glm::vec3 point = (1.0f - b1 - b2) * e.p0 + b1 * e.p1 + b2 * e.p2;
        const glm::vec3 normal = e.sides > 1.0f && u3 < 0.5f ? -e.axis : e.axis;
        if (e.textured) {
            // The texture modulates the factor the emitter was chosen by: weight by their ratio.
            Hit hit;
            hit.instance = e.instance;
            hit.triangle = e.triangle;
            hit.barycentric = glm::vec2(b1, b2);
            hit.geometricNormal = normal;
            hit.t = 1.0f;
            const glm::vec3 factor = mScene.materials[mScene.meshes[mScene.instances[e.instance].mesh].material].emission;
            const glm::vec3 textured = surfaceAt(mScene, hit, normal).emission;
            for (int c = 0; c < 3; ++c) alpha[c] = factor[c] > 0.0f ? alpha[c] * textured[c] / factor[c] : 0.0f;
        }
        ray.origin = point + normal * mOffset;
        ray.direction = cosineDirection(normal, rng.uniform(), rng.uniform());
        break;
    }
    }

    // Step 2: the walk. Vertex j = 1 .. bounces deposits; the light itself (j = 0) does not.
    int count = 0;
    for (int depth = 1; depth <= mParams.bounces; ++depth) {
        ++rays;
        const Hit hit = mRays.intersect(ray, Looker::Origin); // the light, then each VPL, looks forward
        if (!hit.valid()) break; // left the scene
        const glm::vec3 wo = -ray.direction;
        const SurfacePoint s = surfaceAt(mScene, hit, wo, vplMaterials());
        if (glm::dot(s.geometricNormal, wo) <= 0.0f) break; // below the horizon (backs are not hit: ray_scene.cpp)
        // SMCIR 3.1's Lambert assumption for VPLs: the diffuse lobe, rho_d = (1 - metallic) baseColor.
        const glm::vec3 albedo = (1.0f - s.material.metallic) * s.material.baseColor;
        const glm::vec3 reflected = alpha * albedo;
        if (reflected.r > 0.0f || reflected.g > 0.0f || reflected.b > 0.0f) {
            deposits[count].position = s.position;
            deposits[count].normal = s.normal;
            deposits[count].reflected = reflected;
            ++count;
        }
        if (depth == mParams.bounces) break;
        // Russian roulette on the throughput of cosine sampling, t = rho_d.
        const float q = std::min(1.0f, shared::luminanceRec709(albedo));
        if (!(q > 0.0f) || rng.uniform() >= q) break;
        alpha *= albedo / q;
        const glm::vec3 direction = cosineDirection(s.normal, rng.uniform(), rng.uniform());
        if (glm::dot(s.geometricNormal, direction) <= 0.0f) break; // below the geometric horizon
        ray = Ray{};
        ray.origin = s.position + s.geometricNormal * mOffset;
        ray.direction = direction;
    }
    return count;
}

void IRSampler::buildFrame(const FrameSnapshot& snapshot)
{
    const Clock::time_point start = Clock::now();
    mStats = IRStats{};
    const std::vector<Emitter> emitters = collectEmitters(snapshot.lights);
    std::vector<double> cdf(emitters.size());
    double totalPower = 0.0;
    for (std::size_t i = 0; i < emitters.size(); ++i) {
        totalPower += emitters[i].power;
        cdf[i] = totalPower;
    }

    // Step 3: batches of paths traced in parallel, deposits taken in path order.
    const std::size_t slotCount = mSet.slots.size();
    const auto bounces = static_cast<std::size_t>(mParams.bounces);
    const std::uint64_t cap = static_cast<std::uint64_t>(mParams.pathCap) * slotCount;
    std::vector<Deposit> taken;
    taken.reserve(slotCount);
    std::uint64_t next = 0;
    bool full = false;
    while (!emitters.empty() && !full && next < cap) {
        // Depends only on the slots still free: the same batches whatever the thread count.
        const std::uint64_t batch = std::min<std::uint64_t>(cap - next, std::max<std::size_t>(256, slotCount - taken.size()));
        std::vector<Deposit> deposits(batch * bounces);
        std::vector<int> counts(batch, 0);
        std::vector<std::uint64_t> rays(batch, 0);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, batch, 32), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t k = r.begin(); k < r.end(); ++k)
                counts[k] = tracePath(emitters, cdf, totalPower, next + k, &deposits[k * bounces], rays[k]);
        });
        mStats.rays += std::accumulate(rays.begin(), rays.end(), std::uint64_t{0});
        for (std::size_t k = 0; k < batch && !full; ++k) {
            ++mStats.paths;
            if (counts[k] == 0) ++mStats.pathsEscaped;
            for (int j = 0; j < counts[k] && taken.size() < slotCount; ++j) taken.push_back(deposits[k * bounces + j]);
            full = taken.size() == slotCount;
            if (!mParams.fillBudget && !full) {
                // The paper's IR: N is the path count that fills the budget in a closed scene. Each
                // escaped path is charged the deposits of an average path that stayed, so N stops
                // where the paths, had none escaped, would have filled every slot.
                const std::uint64_t stayed = mStats.paths - mStats.pathsEscaped;
                const double charged = static_cast<double>(taken.size()) +
                                       (stayed > 0 ? static_cast<double>(mStats.pathsEscaped) * taken.size() / stayed : 0.0);
                full = charged >= static_cast<double>(slotCount);
            }
        }
        next += batch;
    }

    // Step 4: I(y) = n alpha rho_d / pi with alpha = (N alpha) / N (see the header).
    const std::size_t n = taken.size();
    mStats.vpls = static_cast<int>(n);
    const double scale = mStats.paths > 0 ? static_cast<double>(n) / (static_cast<double>(mStats.paths) * kPi) : 0.0;
    for (std::size_t slot = 0; slot < slotCount; ++slot) {
        VPL vpl;
        if (slot < n) {
            const Deposit& d = taken[slot];
            vpl.position = d.position;
            vpl.normal = d.normal;
            vpl.radiance = glm::vec3(glm::dvec3(d.reflected) * scale);
            vpl.density = 1.0f; // no density: radiance / 1 is the intensity, exactly
            vpl.valid = true;
        }
        mSet.slots[slot] = vpl;
    }
    mStats.ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void IRSampler::initialize(const FrameSnapshot& snapshot, const Progress& progress)
{
    mFrame = 0;
    buildFrame(snapshot);
    mSet.changed.resize(mSet.slots.size()); // the renderer has seen nothing yet
    std::iota(mSet.changed.begin(), mSet.changed.end(), std::uint32_t{0});
    mStats.moved = static_cast<int>(mSet.changed.size());
    ++mSet.generation;
    mInitialized = true;
    if (progress) progress(1, 1);
}

void IRSampler::step(const FrameSnapshot& snapshot)
{
    require(mInitialized, "ir: step() before initialize()");
    ++mFrame;
    const std::vector<VPL> previous = mSet.slots;
    buildFrame(snapshot);
    // A slot changed when its VPL appeared, disappeared or moved; a new intensity alone keeps the
    // shadow map valid.
    mSet.changed.clear();
    for (std::size_t slot = 0; slot < previous.size(); ++slot) {
        const VPL& a = previous[slot];
        const VPL& b = mSet.slots[slot];
        if (a.valid != b.valid || (b.valid && (a.position != b.position || a.normal != b.normal)))
            mSet.changed.push_back(static_cast<std::uint32_t>(slot));
    }
    mStats.moved = static_cast<int>(mSet.changed.size());
    ++mSet.generation;
}

StatList IRSampler::stats() const
{
    return {{"ir: paths", static_cast<double>(mStats.paths)},
            {"ir: paths escaped", static_cast<double>(mStats.pathsEscaped)},
            {"ir: escaped fraction", mStats.escapedFraction()},
            {"ir: VPLs", static_cast<double>(mStats.vpls)},
            {"ir: moved", static_cast<double>(mStats.moved)},
            {"ir: rays", static_cast<double>(mStats.rays)},
            {"sampler: total ms", mStats.ms}}; // the name every VPL sampler uses (vplgi bench)
}

} // namespace vplgi
