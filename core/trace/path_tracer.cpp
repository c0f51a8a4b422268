#include "core/trace/path_tracer.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include "core/util/basis.h"
#include "core/scene/direct_lights.h"
#include "core/util/error.h"
#include "core/util/params.h"
#include "core/util/random.h"
#include "core/scene/surface.h"
#include "glsl/shared/tonemap.h"

namespace vplgi {

CameraRays::CameraRays(const Camera& camera, int width, int height)
    : mWidth(width), mHeight(height), mEye(camera.position),
      mWorldFromClip(glm::inverse(
          glm::dmat4(camera.clipFromView(static_cast<float>(width) / static_cast<float>(height)) * camera.viewFromWorld())))
{
}

Ray CameraRays::at(double x, double y) const
{
    const double ndcX = x / mWidth * 2.0 - 1.0;
    const double ndcY = 1.0 - y / mHeight * 2.0;
    const glm::dvec3 nearPoint = unproject(ndcX, ndcY, -1.0);
    const glm::dvec3 farPoint = unproject(ndcX, ndcY, 1.0);
    const glm::dvec3 direction = glm::normalize(farPoint - mEye);
    Ray ray;
    ray.origin = glm::vec3(mEye);
    ray.direction = glm::vec3(direction);
    ray.tMin = static_cast<float>(std::max(0.0, glm::dot(nearPoint - mEye, direction)));
    ray.tMax = static_cast<float>(glm::dot(farPoint - mEye, direction));
    return ray;
}

glm::dvec3 CameraRays::unproject(double x, double y, double z) const
{
    const glm::dvec4 p = mWorldFromClip * glm::dvec4(x, y, z, 1.0);
    return glm::dvec3(p) / p.w;
}

void PathTracerParams::visitParams(ParamVisitor& v)
{
    v.field("reference.spp", spp, 1, 1 << 24, "samples per pixel");
    v.field("reference.maxDepth", maxDepth, 0, 1024,
            "most reflections along a light path (0 = emission only, 1 = direct light)");
    v.field("reference.rrStartDepth", rrStartDepth, 1, 1025,
            "first path vertex reached only through Russian roulette (> maxDepth = never)");
    int modeIndex = static_cast<int>(mode);
    v.field("reference.mode", modeIndex, 0, 4,
            "0 full, 1 direct (emission + one reflection at the primary hit), 2 indirect (full - direct), "
            "3 indirect with G clamped on the segment leaving the primary hit, "
            "4 onebounce (indirect reflected exactly once after the primary hit)");
    mode = static_cast<Mode>(modeIndex);
    v.field("reference.clampGeometry", clampGeometry, 0.0f, 1e9f, "G_max of the clamped mode [1/m^2]");
    v.field("reference.seed", seed, "random stream seed (same seed, same image)");
    // The visitor knows floats; write back only a changed value so a double budget keeps its bits.
    float budget = static_cast<float>(timeBudgetSeconds);
    v.field("reference.timeBudgetSeconds", budget, 0.0f, 1e7f,
            "wall-clock budget, checked between passes [s]; 0 = none");
    if (budget != static_cast<float>(timeBudgetSeconds)) timeBudgetSeconds = budget;
    v.field("reference.progress", progress, "print one line per pass to stderr");
    v.field("reference.jitterPixels", jitterPixels, "spread samples over the pixel (false: pixel centres only)");
    v.field("reference.untexturedBounces", untexturedBounces,
            "beyond the primary hit, mean material albedos and no normal maps (SMCIR 5: the reference for VPLs "
            "made on an untextured scene)");
    v.field("reference.diffuseVertices", diffuseVertices, 0, 2,
            "vertices after the primary hit reflecting with their diffuse lobe only, as VPLs: 0 none, 1 the "
            "first (SMCIR), 2 every one (IR)");
}

namespace {

// Collects "key=value" lines of the visited fields that change the image, values exact.
class ImageKeyVisitor final : public ParamVisitor {
public:
    void field(const std::string& key, float& value, float, float, const char*) override
    {
        std::ostringstream s;
        s << std::hexfloat << value;
        add(key, s.str());
    }
    void field(const std::string& key, int& value, int, int, const char*) override { add(key, std::to_string(value)); }
    void field(const std::string& key, bool& value, const char*) override { add(key, value ? "true" : "false"); }
    void field(const std::string& key, std::uint32_t& value, const char*) override { add(key, std::to_string(value)); }
    std::string text;

private:
    void add(const std::string& key, const std::string& value)
    {
        if (key == "reference.progress" || key == "reference.timeBudgetSeconds") return;
        text += key + "=" + value + "\n";
    }
};

} // namespace

std::string pathTracerImageKey(const PathTracerParams& params)
{
    PathTracerParams copy = params; // visitParams takes a non-const visitor over mutable fields
    ImageKeyVisitor visitor;
    visitor.text = "pathTracerVersion=" + std::to_string(kPathTracerVersion) + "\n";
    copy.visitParams(visitor);
    return visitor.text;
}

namespace {

using Mode = PathTracerParams::Mode;

// --- Random numbers (core/util/random.h) ---------------------------------------------------------------

// The stream of sample `sample` of pixel `pixel`: a function of these and the seed only, which makes
// the image independent of threads and scheduling.
Pcg32 sampleStream(std::uint32_t seed, std::uint32_t pixel, std::uint32_t sample)
{
    const std::uint64_t key = mix64((static_cast<std::uint64_t>(seed) << 32u) ^ pixel);
    return Pcg32(mix64(key ^ (static_cast<std::uint64_t>(sample) * 0xD1B54A32D192ED03ull)), key);
}

// --- Small helpers -----------------------------------------------------------------------------

float maxComponent(const glm::vec3& c)
{
    return std::max(c.r, std::max(c.g, c.b));
}

bool isBlack(const glm::vec3& c)
{
    return c.r <= 0.0f && c.g <= 0.0f && c.b <= 0.0f;
}

// Veach's power heuristic with beta = 2, for one sample from each of two strategies.
float powerHeuristic(float pdfThis, float pdfOther)
{
    const float a = pdfThis * pdfThis, b = pdfOther * pdfOther;
    return a > 0.0f ? a / (a + b) : 0.0f;
}

// --- The shared material's sampling density ----------------------------------------------------

float alphaOf(const shared::SurfaceMaterial& m)
{
    return std::max(m.roughness * m.roughness, shared::kMinAlpha); // as evaluateBRDF
}

glm::vec3 specularF0(const shared::SurfaceMaterial& m)
{
    return glm::mix(glm::vec3(0.04f * m.specular), m.baseColor, m.metallic); // as evaluateBRDF
}

// Probability of drawing from the GGX lobe: the Fresnel reflectance at the view angle against the
// diffuse albedo, kept in [0.1, 0.9] when both lobes exist so neither is starved.
float specularProbability(const shared::SurfaceMaterial& m, float NoV)
{
    const glm::vec3 f0 = specularF0(m);
    if (f0.x + f0.y + f0.z <= 0.0f) return 0.0f; // evaluateBRDF is then exactly Lambert
    const float diffuse = shared::luminanceRec709((1.0f - m.metallic) * m.baseColor);
    if (diffuse <= 0.0f) return 1.0f;
    const float specular = shared::luminanceRec709(shared::fresnelSchlick(f0, NoV));
    return std::clamp(specular / (specular + diffuse), 0.1f, 0.9f);
}

// Smith's masking G1 for GGX (separable form, the one the visible-normal distribution uses).
float smithG1(float NoV, float alpha)
{
    const float a2 = alpha * alpha;
    return 2.0f * NoV / (NoV + std::sqrt(a2 + (1.0f - a2) * NoV * NoV));
}

// Density of wi when reflecting wo about a visible normal: D_wo(h) / (4 wo.h) = G1(wo) D(h) / (4 NoV).
float pdfSpecular(const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi, float alpha)
{
    const float NoV = glm::dot(n, wo);
    const glm::vec3 h = glm::normalize(wo + wi);
    const float NoH = std::clamp(glm::dot(n, h), 0.0f, 1.0f);
    return shared::distributionGGX(NoH, alpha) * smithG1(NoV, alpha) / (4.0f * NoV);
}

// A GGX visible normal in the local frame (z = normal) for the local view direction v (Heitz 2018).
glm::vec3 sampleVisibleNormal(const glm::vec3& v, float alpha, float u1, float u2)
{
    const glm::vec3 vh = glm::normalize(glm::vec3(alpha * v.x, alpha * v.y, v.z)); // to the hemisphere config
    const float lengthSquared = vh.x * vh.x + vh.y * vh.y;
    const glm::vec3 t1 =
        lengthSquared > 0.0f ? glm::vec3(-vh.y, vh.x, 0.0f) / std::sqrt(lengthSquared) : glm::vec3(1.0f, 0.0f, 0.0f);
    const glm::vec3 t2 = glm::cross(vh, t1);
    const float r = std::sqrt(u1);
    const float phi = 2.0f * shared::kPi * u2;
    const float p1 = r * std::cos(phi);
    const float s = 0.5f * (1.0f + vh.z);
    const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
    const glm::vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return glm::normalize(glm::vec3(alpha * nh.x, alpha * nh.y, std::max(0.0f, nh.z))); // back to the ellipsoid
}

} // namespace

float pdfBRDF(const shared::SurfaceMaterial& material, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi)
{
    const float NoV = glm::dot(n, wo);
    const float NoL = glm::dot(n, wi);
    if (!(NoV > 0.0f) || !(NoL > 0.0f)) return 0.0f;
    const float p = specularProbability(material, NoV);
    float pdf = (1.0f - p) * NoL * shared::kInvPi;
    if (p > 0.0f) pdf += p * pdfSpecular(n, wo, wi, alphaOf(material));
    return pdf;
}

std::optional<BRDFSample> sampleBRDF(const shared::SurfaceMaterial& material, const glm::vec3& n, const glm::vec3& wo,
                                     const glm::vec3& u)
{
    const float NoV = glm::dot(n, wo);
    if (!(NoV > 0.0f)) return std::nullopt;
    glm::vec3 t, b;
    makeBasis(n, t, b);
    BRDFSample sample;
    if (u.x < specularProbability(material, NoV)) {
        const glm::vec3 local(glm::dot(wo, t), glm::dot(wo, b), NoV);
        const glm::vec3 m = sampleVisibleNormal(local, alphaOf(material), u.y, u.z);
        const glm::vec3 h = m.x * t + m.y * b + m.z * n;
        sample.wi = glm::normalize(2.0f * glm::dot(wo, h) * h - wo);
    } else {
        // Cosine-weighted hemisphere (Malley): a uniform disc point lifted to the hemisphere.
        const float r = std::sqrt(u.y);
        const float phi = 2.0f * shared::kPi * u.z;
        const float z = std::sqrt(std::max(0.0f, 1.0f - u.y));
        sample.wi = glm::normalize(r * std::cos(phi) * t + r * std::sin(phi) * b + z * n);
    }
    const float NoL = glm::dot(n, sample.wi);
    if (!(NoL > 0.0f)) return std::nullopt;
    sample.pdf = pdfBRDF(material, n, wo, sample.wi);
    const glm::vec3 f = shared::evaluateBRDF(material, n, wo, sample.wi);
    if (!(sample.pdf > 0.0f) || isBlack(f)) return std::nullopt;
    sample.weight = f * (NoL / sample.pdf);
    return sample;
}

namespace {

// --- Scene lights -------------------------------------------------------------------------------

// One triangle of an emissive instance, world space. Every triangle of such an instance is listed
// (zero-power ones with probability 0) so that (instance, triangle) maps to an index directly.
struct EmissiveTriangle {
    glm::vec3 p0{0.0f}, p1{0.0f}, p2{0.0f};
    glm::vec3 normal{0.0f};   // unit, counter-clockwise side (the front); zero for degenerate ones
    glm::vec3 radiance{0.0f}; // material emission factor [W/(m^2 sr)]
    float area = 0.0f;        // [m^2]
    float power = 0.0f;       // shared::luminanceRec709(radiance) * area: the selection weight
    int instance = -1;
    int triangle = -1;
    bool doubleSided = false; // emits on both sides
    bool textured = false;    // the emission texture modulates `radiance`
};

// Random numbers per path vertex, drawn whether used or not so that all modes follow the same
// paths: [0] emitter choice, [1, 2] point on it, [3, 4, 5] BRDF sample, [6] Russian roulette.
constexpr int kNumbersPerVertex = 7;

class Integrator {
public:
    // `lights` in place of scene.lights (a snapshot: the scene's light list is never read). With
    // params.untexturedBounces, `untextured` is the table to use (the caller's, computed once), or
    // null to compute it here.
    Integrator(const Scene& scene, const RayScene& rays, const std::vector<Light>& lights, const PathTracerParams& params,
               const UntexturedMaterials* untextured = nullptr)
        : mScene(scene), mRays(rays), mParams(params), mOffset(1e-4f * rays.sceneScale())
    {
        if (params.untexturedBounces && !untextured) mOwnUntextured = computeUntexturedMaterials(scene);
        mUntextured = !params.untexturedBounces ? nullptr : untextured ? untextured : &*mOwnUntextured;
        // Punctual and directional lights exactly as the GPU direct pass gets them; the cosine point
        // samples standing in for emissive triangles are dropped (triangles are sampled by area here).
        DirectLightSet all = buildDirectLights(scene, lights, DirectLightParams{});
        mPunctual.directionals = all.directionals;
        for (const shared::PointEmitter& e : all.points)
            if (static_cast<int>(e.positionProfile.w + 0.5f) != shared::kProfileCosine) mPunctual.points.push_back(e);
        collectEmitters();
    }

    // The punctual-light term at a given vertex 0 (evaluateDirectLight): it draws no random numbers,
    // so it is the same for every path from that vertex and is computed once, on first use.
    struct StartDirect {
        bool computed = false;
        glm::vec3 value{0.0f};
    };

    glm::vec3 radiance(Ray ray, Pcg32& rng) const { return trace(ray, nullptr, rng, nullptr); }
    // The path of radiance(), or with `start` the path whose vertex 0 is *start (wo = its shading
    // normal, no intersection, no emission at vertex 0). Adds the Embree rays cast to *rays if given.
    // With `startDirect` (only together with `start`), vertex 0's punctual-light term is taken from
    // it, computed and counted (rays) by the first path that needs it.
    glm::vec3 trace(Ray ray, const SurfacePoint* start, Pcg32& rng, std::uint64_t* rays,
                    StartDirect* startDirect = nullptr) const;

private:
    void collectEmitters();
    glm::vec3 emitted(const Hit& hit, const SurfacePoint& s, const glm::vec3& wo) const;
    float lightPdf(const Hit& hit, const glm::vec3& wo) const;
    glm::vec3 sampleEmitters(const SurfacePoint& s, const glm::vec3& wo, float u0, float u1, float u2,
                             std::uint64_t* rays) const;

    bool countsEmission(int depth) const
    {
        switch (mParams.mode) {
        case Mode::Full:
            return true;
        case Mode::Direct:
            return depth <= 1;
        case Mode::Indirect:
        case Mode::Clamped:
        case Mode::OneBounce: // trace() caps its depth at 2: emission at vertex 2 only
            return depth >= 2;
        }
        return false;
    }
    bool countsLightSamples(int depth) const
    {
        switch (mParams.mode) {
        case Mode::Full:
            return true;
        case Mode::Direct:
            return depth == 0;
        case Mode::Indirect:
        case Mode::Clamped:
        case Mode::OneBounce: // trace() caps its depth at 2: light samples at vertex 1 only
            return depth >= 1;
        }
        return false;
    }

    const Scene& mScene;
    const RayScene& mRays;
    const PathTracerParams& mParams;
    const float mOffset; // ray offset along geometric normals [m]
    DirectLightSet mPunctual;
    std::optional<UntexturedMaterials> mOwnUntextured;   // computed here when the caller gave none
    const UntexturedMaterials* mUntextured = nullptr;      // untexturedBounces: the materials of vertices >= 1
    std::vector<EmissiveTriangle> mEmitters;
    std::vector<int> mFirstEmitter; // per instance: index of its triangle 0 in mEmitters, -1 = none
    std::vector<double> mPowerCdf;  // running sum of mEmitters' power
    double mTotalPower = 0.0;
};

void Integrator::collectEmitters()
{
    mFirstEmitter.assign(mScene.instances.size(), -1);
    for (std::size_t i = 0; i < mScene.instances.size(); ++i) {
        const Instance& instance = mScene.instances[i];
        const Mesh& mesh = mScene.meshes[instance.mesh];
        const Material& material = mScene.materials[mesh.material];
        if (!material.isEmissive()) continue;
        mFirstEmitter[i] = static_cast<int>(mEmitters.size());
        auto world = [&](std::uint32_t v) {
            return glm::vec3(instance.worldFromObject * glm::vec4(mesh.vertices[v].position, 1.0f));
        };
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
            EmissiveTriangle e;
            e.p0 = world(mesh.indices[3 * t]);
            e.p1 = world(mesh.indices[3 * t + 1]);
            e.p2 = world(mesh.indices[3 * t + 2]);
            const glm::vec3 cross = glm::cross(e.p1 - e.p0, e.p2 - e.p0);
            const float twiceArea = glm::length(cross);
            if (twiceArea > 0.0f) {
                e.normal = instance.winding() * cross / twiceArea; // the emitting front (Instance::winding)
                e.area = 0.5f * twiceArea;
            }
            e.radiance = material.emission;
            e.power = shared::luminanceRec709(material.emission) * e.area;
            e.instance = static_cast<int>(i);
            e.triangle = static_cast<int>(t);
            e.doubleSided = material.doubleSided;
            e.textured = material.emissionTexture.valid();
            mEmitters.push_back(e);
        }
    }
    mPowerCdf.resize(mEmitters.size());
    for (std::size_t i = 0; i < mEmitters.size(); ++i) {
        mTotalPower += mEmitters[i].power;
        mPowerCdf[i] = mTotalPower;
    }
}

// Emitted radiance towards wo at a hit: the front side of single-sided emitters, both of
// double-sided ones (as the rasterizer's culling shows them).
glm::vec3 Integrator::emitted(const Hit& hit, const SurfacePoint& s, const glm::vec3& wo) const
{
    const int first = mFirstEmitter[hit.instance];
    if (first < 0) return glm::vec3(0.0f);
    const EmissiveTriangle& e = mEmitters[first + hit.triangle];
    const float cosine = glm::dot(e.normal, wo);
    if (!(e.doubleSided ? cosine != 0.0f : cosine > 0.0f)) return glm::vec3(0.0f);
    return s.emission;
}

// Solid-angle density with which sampleEmitters would have chosen the hit point, seen from the
// previous vertex along -wo at distance hit.t.
float Integrator::lightPdf(const Hit& hit, const glm::vec3& wo) const
{
    const EmissiveTriangle& e = mEmitters[mFirstEmitter[hit.instance] + hit.triangle];
    const float cosine = std::abs(glm::dot(e.normal, wo));
    if (!(e.power > 0.0f) || !(cosine > 0.0f)) return 0.0f;
    const auto probability = static_cast<float>(e.power / mTotalPower);
    return probability / e.area * hit.t * hit.t / cosine;
}

// One area-light sample for the point s (next-event estimation), weighted against BRDF sampling.
glm::vec3 Integrator::sampleEmitters(const SurfacePoint& s, const glm::vec3& wo, float u0, float u1, float u2,
                                     std::uint64_t* rays) const
{
    if (!(mTotalPower > 0.0)) return glm::vec3(0.0f);
    // upper_bound never returns a zero-power triangle: its running sum equals its predecessor's.
    const double target = std::min(static_cast<double>(u0) * mTotalPower, std::nextafter(mTotalPower, 0.0));
    const auto index = std::min(
        static_cast<std::size_t>(std::upper_bound(mPowerCdf.begin(), mPowerCdf.end(), target) - mPowerCdf.begin()),
        mEmitters.size() - 1);
    const EmissiveTriangle& e = mEmitters[index];
    if (!(e.power > 0.0f)) return glm::vec3(0.0f);

    // Uniform point on the triangle; (b1, b2) are Embree's barycentrics of p1 and p2.
    const float root = std::sqrt(u1);
    const float b1 = root * (1.0f - u2), b2 = root * u2;
    const glm::vec3 y = (1.0f - b1 - b2) * e.p0 + b1 * e.p1 + b2 * e.p2;
    const glm::vec3 toLight = y - s.position;
    const float distance2 = glm::dot(toLight, toLight);
    if (!(distance2 > 0.0f)) return glm::vec3(0.0f);
    const glm::vec3 wi = toLight / std::sqrt(distance2);
    if (glm::dot(s.geometricNormal, wi) <= 0.0f) return glm::vec3(0.0f); // as BRDF sampling: below the horizon
    const float cosSurface = glm::dot(s.normal, wi);
    if (cosSurface <= 0.0f) return glm::vec3(0.0f);
    const float signedCosLight = glm::dot(e.normal, -wi);
    const float cosLight = e.doubleSided ? std::abs(signedCosLight) : signedCosLight;
    if (!(cosLight > 0.0f)) return glm::vec3(0.0f);
    const glm::vec3 f = shared::evaluateBRDF(s.material, s.normal, wo, wi);
    if (isBlack(f)) return glm::vec3(0.0f);

    glm::vec3 radiance = e.radiance;
    if (e.textured) {
        Hit hit;
        hit.instance = e.instance;
        hit.triangle = e.triangle;
        hit.barycentric = glm::vec2(b1, b2);
        hit.geometricNormal = e.normal;
        hit.t = std::sqrt(distance2);
        radiance = surfaceAt(mScene, hit, -wi).emission;
    }
    if (isBlack(radiance)) return glm::vec3(0.0f);

    // Both ends lifted off their surfaces, the light point towards the receiver.
    const glm::vec3 origin = s.position + s.geometricNormal * mOffset;
    const glm::vec3 end = y + (signedCosLight > 0.0f ? e.normal : -e.normal) * mOffset;
    if (rays) ++*rays;
    if (!mRays.visible(origin, end, Looker::End)) return glm::vec3(0.0f); // the emitter looks

    const float pdfLight = static_cast<float>(e.power / mTotalPower) / e.area * distance2 / cosLight;
    const float weight = powerHeuristic(pdfLight, pdfBRDF(s.material, s.normal, wo, wi));
    return f * radiance * (cosSurface * weight / pdfLight);
}

glm::vec3 Integrator::trace(Ray ray, const SurfacePoint* start, Pcg32& rng, std::uint64_t* rays,
                            StartDirect* startDirect) const
{
    // Direct and OneBounce are Full and Indirect with the paths cut short (see the header).
    const int maxDepth = mParams.mode == Mode::Direct      ? std::min(mParams.maxDepth, 1)
                         : mParams.mode == Mode::OneBounce ? std::min(mParams.maxDepth, 2)
                                                           : mParams.maxDepth;
    glm::vec3 radiance(0.0f);
    glm::vec3 throughput(1.0f);
    float previousPdf = 0.0f;    // BRDF density of the direction that led to this vertex [1/sr]
    float previousCosine = 0.0f; // cosine at the previous vertex of that direction
    for (int depth = 0;; ++depth) {
        float u[kNumbersPerVertex];
        for (float& number : u)
            number = rng.uniform();

        SurfacePoint s;
        glm::vec3 wo;
        if (depth == 0 && start) {
            s = *start; // a given vertex 0: its emission is not part of the estimate
            wo = s.normal;
        } else {
            // Past maxDepth a vertex only adds emission: without emitters its intersection is moot.
            if (depth >= maxDepth && mEmitters.empty()) break;
            // The back-face rule (ray_scene.h Looker): the camera does not see backs; a bounce stops
            // on either side (a back is black: the next vertex, whose light the bounce gathers, looks).
            const Hit hit = mRays.intersect(ray, depth == 0 ? Looker::Origin : Looker::None);
            if (rays) ++*rays;
            if (!hit.valid()) break; // no environment light
            wo = -ray.direction;
            s = surfaceAt(mScene, hit, wo, depth >= 1 ? mUntextured : nullptr);
            if (depth >= 1 && (mParams.diffuseVertices >= 2 || (mParams.diffuseVertices == 1 && depth == 1))) {
                // A VPL's Lambert assumption (SMCIR 3.1): its diffuse lobe, as the samplers reflect.
                s.material.baseColor *= 1.0f - s.material.metallic;
                s.material.metallic = 0.0f;
                s.material.specular = 0.0f;
            }

            if (mParams.mode == Mode::Clamped && depth == 1) {
                // SMCIR Sec. 5.4: clamp G of the segment x0 -> x1 as VPL methods clamp it (MATH.md 1.2 a).
                const float cosine = std::max(0.0f, glm::dot(s.normal, wo));
                const float geometry = previousCosine * cosine / (hit.t * hit.t);
                if (geometry > mParams.clampGeometry) throughput *= mParams.clampGeometry / geometry;
            }

            if (countsEmission(depth)) {
                const glm::vec3 emission = emitted(hit, s, wo);
                if (!isBlack(emission)) {
                    // Emission found by BRDF sampling shares the estimate with light sampling (MIS).
                    const float weight = depth == 0 ? 1.0f : powerHeuristic(previousPdf, lightPdf(hit, wo));
                    radiance += throughput * emission * weight;
                }
            }
        }
        if (depth >= maxDepth) break;
        // The back of a single-sided surface (met by a bounce, Looker::None) reflects nothing, nor does
        // a point seen from below its geometric horizon.
        if (glm::dot(s.geometricNormal, wo) <= 0.0f) break;

        if (countsLightSamples(depth)) {
            glm::vec3 direct = sampleEmitters(s, wo, u[0], u[1], u[2], rays);
            if (!mPunctual.points.empty() || !mPunctual.directionals.empty()) {
                if (depth == 0 && start && startDirect) {
                    // The same deterministic value every path from this start would compute.
                    if (!startDirect->computed) {
                        startDirect->value = evaluateDirectLight(mRays, mPunctual, s, wo, rays);
                        startDirect->computed = true;
                    }
                    direct += startDirect->value;
                } else {
                    direct += evaluateDirectLight(mRays, mPunctual, s, wo, rays);
                }
            }
            radiance += throughput * direct;
        }

        const std::optional<BRDFSample> sample = sampleBRDF(s.material, s.normal, wo, glm::vec3(u[3], u[4], u[5]));
        if (!sample || glm::dot(s.geometricNormal, sample->wi) <= 0.0f) break;
        throughput *= sample->weight;
        previousPdf = sample->pdf;
        previousCosine = glm::dot(s.normal, sample->wi);
        if (depth + 1 >= mParams.rrStartDepth) {
            const float survival = std::min(0.95f, maxComponent(throughput));
            if (!(u[6] < survival)) break;
            throughput /= survival;
        }
        if (isBlack(throughput)) break;

        ray.origin = s.position + s.geometricNormal * mOffset;
        ray.direction = sample->wi;
        ray.tMin = 0.0f;
        ray.tMax = std::numeric_limits<float>::infinity();
    }
    return radiance;
}


void checkParams(int width, int height, const PathTracerParams& p)
{
    require(width >= 1 && height >= 1, "reference: image size must be at least 1x1");
    require(p.spp >= 1, "reference.spp must be >= 1");
    require(p.maxDepth >= 0, "reference.maxDepth must be >= 0");
    require(p.rrStartDepth >= 1, "reference.rrStartDepth must be >= 1");
    require(static_cast<int>(p.mode) >= 0 && static_cast<int>(p.mode) <= 4, "reference.mode must be 0..4");
    require(std::isfinite(p.clampGeometry) && p.clampGeometry >= 0.0f, "reference.clampGeometry must be >= 0");
    require(std::isfinite(p.timeBudgetSeconds) && p.timeBudgetSeconds >= 0.0,
            "reference.timeBudgetSeconds must be >= 0");
}

} // namespace

ReferenceResult renderReference(const Scene& scene, const RayScene& rays, const Camera& camera, int width, int height,
                                const PathTracerParams& params, ProgressCallback progress)
{
    assert(&rays.scene() == &scene && "the RayScene must be built from this scene");
    checkParams(width, height, params);
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    auto elapsed = [&start] { return std::chrono::duration<double>(Clock::now() - start).count(); };

    const Integrator integrator(scene, rays, scene.lights, params);
    const CameraRays cameraRays(camera, width, height);
    const std::size_t pixelCount = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    std::vector<double> sums(3 * pixelCount, 0.0);

    // Samples first .. first+count-1 of pixel (x, y), added to its sum in sample order.
    auto addSamples = [&](int x, int y, int first, int count) {
        const std::size_t pixel = static_cast<std::size_t>(y) * width + x;
        glm::dvec3 sum(sums[3 * pixel], sums[3 * pixel + 1], sums[3 * pixel + 2]);
        for (int s = first; s < first + count; ++s) {
            Pcg32 rng = sampleStream(params.seed, static_cast<std::uint32_t>(pixel), static_cast<std::uint32_t>(s));
            // Both numbers are drawn either way so the paths are the same with and without jitter.
            const float u = rng.uniform();
            const float v = rng.uniform();
            const float jitterX = params.jitterPixels ? u : 0.5f;
            const float jitterY = params.jitterPixels ? v : 0.5f;
            const glm::vec3 L = integrator.radiance(cameraRays.at(x + jitterX, y + jitterY), rng);
            // A non-finite sample (a numerical accident) counts as black, deterministically.
            if (std::isfinite(L.r) && std::isfinite(L.g) && std::isfinite(L.b)) sum += glm::dvec3(L);
        }
        sums[3 * pixel] = sum.x;
        sums[3 * pixel + 1] = sum.y;
        sums[3 * pixel + 2] = sum.z;
    };

    // Passes of 1, 2, 4, ... samples; with a budget, a pass is shortened to what the measured time
    // per sample says still fits, and no pass starts once the budget is spent.
    int done = 0;
    int passSize = 1;
    while (done < params.spp) {
        int count = std::min(passSize, params.spp - done);
        if (params.timeBudgetSeconds > 0.0 && done > 0) {
            const double remaining = params.timeBudgetSeconds - elapsed();
            if (remaining <= 0.0) break;
            const double secondsPerSample = elapsed() / done;
            const double fits = secondsPerSample > 0.0 ? std::floor(remaining / secondsPerSample) : count;
            count = std::max(1, static_cast<int>(std::min<double>(count, fits)));
        }
        const int first = done;
        tbb::parallel_for(tbb::blocked_range2d<int>(0, height, 4, 0, width, 4),
                          [&](const tbb::blocked_range2d<int>& tile) {
                              for (int y = tile.rows().begin(); y < tile.rows().end(); ++y)
                                  for (int x = tile.cols().begin(); x < tile.cols().end(); ++x)
                                      addSamples(x, y, first, count);
                          });
        done += count;
        passSize = std::min(2 * passSize, 1 << 24);
        if (params.progress) std::fprintf(stderr, "reference: %d/%d spp, %.2f s\n", done, params.spp, elapsed());
        if (progress) progress(static_cast<double>(done) / params.spp);
    }

    ReferenceResult result;
    result.spp = done;
    result.image.width = width;
    result.image.height = height;
    result.image.pixels.resize(4 * pixelCount);
    for (std::size_t i = 0; i < pixelCount; ++i) {
        for (int c = 0; c < 3; ++c)
            result.image.pixels[4 * i + c] = static_cast<float>(sums[3 * i + c] / done);
        result.image.pixels[4 * i + 3] = 1.0f;
    }
    result.seconds = elapsed();
    return result;
}

PixelReferenceResult renderReferencePixels(const Scene& scene, const RayScene& rays, const Camera& camera, int width,
                                           int height, const std::vector<glm::ivec2>& pixels,
                                           const PathTracerParams& params, ProgressCallback progress)
{
    assert(&rays.scene() == &scene && "the RayScene must be built from this scene");
    checkParams(width, height, params);
    for (const glm::ivec2& p : pixels)
        require(p.x >= 0 && p.y >= 0 && p.x < width && p.y < height,
                "reference: pixel (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ") is outside the " +
                    std::to_string(width) + "x" + std::to_string(height) + " image");
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();

    const Integrator integrator(scene, rays, scene.lights, params);
    const CameraRays cameraRays(camera, width, height);
    std::vector<glm::dvec3> sums(pixels.size(), glm::dvec3(0.0));
    // A handful of pixels cannot keep the threads busy: batches of samples of every pixel run in
    // parallel into a buffer, then each pixel adds its batch in sample order, exactly as
    // renderReference's per-pixel loop adds them (the same sums, so the same bits).
    const int batch = std::min(params.spp, 16384);
    std::vector<glm::vec3> values(pixels.size() * static_cast<std::size_t>(batch));
    for (int first = 0; first < params.spp; first += batch) {
        const int count = std::min(batch, params.spp - first);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pixels.size() * static_cast<std::size_t>(count), 256),
                          [&](const tbb::blocked_range<std::size_t>& range) {
                              for (std::size_t i = range.begin(); i < range.end(); ++i) {
                                  const std::size_t k = i / static_cast<std::size_t>(count);
                                  const int s = first + static_cast<int>(i % static_cast<std::size_t>(count));
                                  const glm::ivec2 p = pixels[k];
                                  const std::size_t pixel = static_cast<std::size_t>(p.y) * width + p.x;
                                  Pcg32 rng = sampleStream(params.seed, static_cast<std::uint32_t>(pixel),
                                                           static_cast<std::uint32_t>(s));
                                  const float u = rng.uniform(); // as renderReference: both drawn either way
                                  const float v = rng.uniform();
                                  const float jitterX = params.jitterPixels ? u : 0.5f;
                                  const float jitterY = params.jitterPixels ? v : 0.5f;
                                  values[k * static_cast<std::size_t>(batch) + (s - first)] =
                                      integrator.radiance(cameraRays.at(p.x + jitterX, p.y + jitterY), rng);
                              }
                          });
        for (std::size_t k = 0; k < pixels.size(); ++k)
            for (int s = 0; s < count; ++s) {
                const glm::vec3& L = values[k * static_cast<std::size_t>(batch) + s];
                if (std::isfinite(L.r) && std::isfinite(L.g) && std::isfinite(L.b)) sums[k] += glm::dvec3(L);
            }
        if (progress) progress(static_cast<double>(first + count) / params.spp);
    }

    PixelReferenceResult result;
    result.spp = params.spp;
    // As renderReference: the double sum divided by the count, then rounded to float.
    for (const glm::dvec3& sum : sums)
        result.radiance.emplace_back(static_cast<float>(sum.x / params.spp), static_cast<float>(sum.y / params.spp),
                                     static_cast<float>(sum.z / params.spp));
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return result;
}

// --- Reflected radiance at a surface point ------------------------------------------------------

struct ReflectedRadianceEstimator::Impl {
    PathTracerParams params; // declared before the integrator, which keeps a reference to it
    Integrator integrator;

    Impl(const Scene& scene, const RayScene& rays, const std::vector<Light>& lights, const PathTracerParams& p,
         const UntexturedMaterials* untextured)
        : params(p), integrator(scene, rays, lights, params, untextured)
    {
    }
};

namespace {

PathTracerParams reflectedRadianceParams(int maxBounces, const UntexturedMaterials* untextured)
{
    require(maxBounces >= 1 && maxBounces <= 1024, "reflected radiance: maxBounces must be in [1, 1024]");
    PathTracerParams params;
    params.mode = Mode::Full; // vertex 0's emission is skipped by trace() itself
    params.maxDepth = maxBounces;
    params.rrStartDepth = 3; // as the reference's default: Russian roulette from vertex 3 on
    params.untexturedBounces = untextured != nullptr;
    return params;
}

// Distinguishes these streams from the image's (whose pixel index stays below 2^32 - 1 in practice).
constexpr std::uint32_t kReflectedRadianceStream = 0xFFFFFFFFu;

} // namespace

ReflectedRadianceEstimator::ReflectedRadianceEstimator(const Scene& scene, const RayScene& rays, int maxBounces)
    : ReflectedRadianceEstimator(scene, rays, scene.lights, maxBounces, nullptr)
{
}

ReflectedRadianceEstimator::ReflectedRadianceEstimator(const Scene& scene, const RayScene& rays,
                                                       const std::vector<Light>& lights, int maxBounces,
                                                       const UntexturedMaterials* untextured)
    : mImpl(std::make_unique<Impl>(scene, rays, lights, reflectedRadianceParams(maxBounces, untextured), untextured))
{
    assert(&rays.scene() == &scene && "the RayScene must be built from this scene");
}

ReflectedRadianceEstimator::~ReflectedRadianceEstimator() = default;

glm::vec3 ReflectedRadianceEstimator::estimate(const SurfacePoint& y, int samples, std::uint32_t seed,
                                               std::uint64_t* rays) const
{
    require(samples >= 1, "reflected radiance: samples must be >= 1");
    // SMCIR 3.1: indirectly visible surfaces are treated as Lambertian, so the VPL reflects with the
    // diffuse lobe only: rho_d / pi with rho_d = (1 - metallic) * baseColor (F0 = 0 turns off GGX).
    SurfacePoint diffuse = y;
    diffuse.material.baseColor = (1.0f - y.material.metallic) * y.material.baseColor;
    diffuse.material.metallic = 0.0f;
    diffuse.material.specular = 0.0f;
    std::uint64_t count = 0;
    glm::dvec3 sum(0.0);
    // Vertex 0 is the same for every sample: its punctual-light term (no random numbers) is
    // evaluated once and shared, the same value each path would compute (see the header).
    Integrator::StartDirect startDirect;
    for (int s = 0; s < samples; ++s) {
        Pcg32 rng = sampleStream(seed, kReflectedRadianceStream, static_cast<std::uint32_t>(s));
        const glm::vec3 L = mImpl->integrator.trace(Ray{}, &diffuse, rng, rays ? &count : nullptr, &startDirect);
        // A non-finite sample (a numerical accident) counts as black, deterministically.
        if (std::isfinite(L.r) && std::isfinite(L.g) && std::isfinite(L.b)) sum += glm::dvec3(L);
    }
    if (rays) *rays += count;
    return glm::vec3(sum / static_cast<double>(samples));
}

glm::vec3 estimateReflectedRadiance(const Scene& scene, const RayScene& rays, const SurfacePoint& y, int samples,
                                    int maxBounces, std::uint32_t seed, std::uint64_t* rayCount)
{
    const ReflectedRadianceEstimator estimator(scene, rays, maxBounces);
    return estimator.estimate(y, samples, seed, rayCount);
}

} // namespace vplgi
