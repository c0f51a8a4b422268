#include "core/vpl/smcir_sampler.h"
#include "core/vpl/vpl_gather.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/util/basis.h"
#include "core/util/content_hash.h"
#include "core/util/error.h"
#include "core/util/knn.h"
#include "core/util/params.h"
#include "core/trace/path_tracer.h"
#include "core/util/random.h"
#include "glsl/shared/tonemap.h"

namespace vplgi {

void SMCIRParams::visitParams(ParamVisitor& v)
{
    v.field("smcir.vplCount", vplCount, 1, 1 << 20, "I: VPL budget (slots)");
    v.field("smcir.maxMoves", maxMoves, 0, 1 << 20, "M_max: most VPL slots that change per frame");
    v.field("smcir.validationRays", validationRays, 0, 1024,
            "V: invalid VPLs each camera point tests per validation round (3.2.2)");
    v.field("smcir.validationIterations", validationIterations, 0, 16, "validation rounds per frame (3.2.2)");
    v.field("smcir.candidateFactor", candidateFactor, 1, 256,
            "candidate rays per VPL, resampled down to I candidates (3.2.1: 16)");
    v.field("smcir.resampleRetries", resampleRetries, 0, 64, "redraws for duplicate candidates (3.2.1: 8)");
    v.field("smcir.candidateDensityGrid", candidateDensityGrid,
            "raw candidate density from uniform-grid counts (~k per cell) instead of kNN; faster, not in the paper");
    v.field("smcir.candidateDensityK", candidateDensityK, 1, 64,
            "k of the kNN density of the raw candidate points (resampling weights; 3.2.4: 1)");
    v.field("smcir.radiositySamples", radiositySamples, 1, 65536, "path-tracer samples per VPL radiance (3.2.3)");
    v.field("smcir.candidateRadianceSamples", candidateRadianceSamples, 0, 65536,
            "samples for candidate radiance screening (line 7); 0 = radiositySamples as in the paper");
    v.field("smcir.independentRadiance", independentRadiance,
            "a new VPL's radiance (line 18) is estimated anew with its own seed, independent of the candidate "
            "estimate it was selected on (false: keep that value, which biases the set high)");
    v.field("smcir.radiosityBounces", radiosityBounces, 1, 1024,
            "most reflections of the radiance paths, counting the one at the VPL (3.2.3: 3)");
    v.field("smcir.knnRender", knnRender, 0, 1024,
            "k of the rendering densities; 0 = eq. (8), max(1, floor(sqrt(I/32)))");
    v.choice("smcir.rankRadiance", rankRadiance, {"rendered", "candidate"},
             "the radiance lines 9-12 rank VPLs by: rendered (the paper: the value each renders with) or "
             "candidate (F1, ours: its line-7 candidate estimate, independent of the rendered one)");
    v.field("smcir.knnCountsSelf", knnCountsSelf,
            "eq. (7) counts y as its own first neighbour (F2, a reading of 3.2.4: p = k / (n pi r^2), r the "
            "distance to the (k-1)-th other VPL, k >= 2); false: self excluded (MATH.md 2)");
    v.field("smcir.knnRank", knnRank, 0, 1024,
            "k of the densities lines 9-12 rank VPLs by (F3, ours); 0 = the rendering k");
    v.field("smcir.strongFraction", strongFraction, 0.0f, 1.0f,
            "eq. (9): candidates stronger than this fraction of the VPLs are strong");
    v.field("smcir.cameraSamplesX", cameraSamplesX, 1, 4096, "camera-ray grid columns (jittered per frame)");
    v.field("smcir.cameraSamplesY", cameraSamplesY, 1, 4096, "camera-ray grid rows (jittered per frame)");
    v.field("smcir.warmupIterations", warmupIterations, 0, 100000,
            "frames run before the first one is shown (paper: 100)");
    v.field("smcir.seed", seed, "random stream seed (same seed and cameras, same VPLs)");
    v.field("smcir.texturedVPLs", texturedVPLs,
            "VPLs on the textured scene (albedo textures, normal maps); false = the paper's untextured scene "
            "with mean material albedos (section 5). true is not in the paper");
    v.field("smcir.clampScale", clampScale, 0.0f, 1000.0f,
            "VPL clamping: G_max = 1/d^2 with d = clampScale * D / sqrt(I) (D the scene diagonal: d scales with "
            "the expected VPL spacing); 0 = none");
    v.field("smcir.invalidateEveryFrame", reestimateEveryFrame,
            "re-estimate every VPL's radiance each frame, as when a light moves (measures that cost)");
}

float computeClampGeometry(const SMCIRParams& params, float sceneDiagonal)
{
    return clampGeometryFor(params.clampScale, params.vplCount, sceneDiagonal);
}

void configureSMCIRReference(const SMCIRParams& params, float sceneDiagonal, PathTracerParams& reference,
                             const std::set<std::string>& explicitKeys)
{
    // The VPL reflects its diffuse lobe (3.1); its radiance paths (ReflectedRadianceEstimator) keep the BRDF.
    configureVPLReference(params.texturedVPLs, computeClampGeometry(params, sceneDiagonal), params.radiosityBounces,
                          1, reference, explicitKeys);
}

int computeRenderingK(int vplCount)
{
    // Eq. (8), read as k = max(1, floor(sqrt(I / 32))) (papers/README.md, MATH.md 2).
    return std::max(1, static_cast<int>(std::floor(std::sqrt(static_cast<double>(vplCount) / 32.0))));
}

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// --- Random numbers (core/util/random.h; no std:: distributions) ------------------------------------

// Which part of a frame a stream belongs to; with (seed, frame, item) it names the stream.
enum Stage : std::uint64_t {
    kStageCamera = 1,
    kStageCandidateRays = 2,
    kStageResample = 3,         // + retry round
    kStageRadianceSeed = 100,
    kStageValidation = 200,     // + validation round
};

std::uint64_t streamKey(std::uint32_t seed, std::uint64_t frame, std::uint64_t stage, std::uint64_t item)
{
    return mix64(mix64(mix64((static_cast<std::uint64_t>(seed) << 32u) ^ stage) ^ frame) ^ item);
}

Pcg32 stream(std::uint32_t seed, std::uint64_t frame, std::uint64_t stage, std::uint64_t item)
{
    const std::uint64_t key = streamKey(seed, frame, stage, item);
    return Pcg32(key, mix64(key ^ 0xD1B54A32D192ED03ull));
}

// --- Small helpers -----------------------------------------------------------------------------

// Eq. (6) by luminance: I(y) = L(y) / p(y). A point without a density estimate (no neighbours) is
// infinitely strong when it reflects anything.
float intensityOf(const glm::vec3& radiance, float density)
{
    const float L = shared::luminanceRec709(radiance);
    if (density > 0.0f) return L / density;
    return L > 0.0f ? std::numeric_limits<float>::infinity() : 0.0f;
}

template <typename F>
void parallelFor(std::size_t count, std::size_t grain, const F& body)
{
    if (count == 0) return;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, grain), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i)
            body(i);
    });
}

} // namespace

// A point of X: a surface point seen by a primary ray.
struct SMCIRSampler::CameraPoint {
    glm::vec3 position{0.0f}; // on the surface [m]
    glm::vec3 origin{0.0f};   // lifted off the surface along `normal` (ray origin)
    glm::vec3 normal{0.0f};   // geometric normal, on the camera's side (unit)
};

// What the sampler keeps per slot beside the published VPL.
struct SMCIRSampler::SlotState {
    SurfacePoint surface;           // the VPL's surface point (radiance is re-estimated from it)
    glm::vec3 origin{0.0f};         // the VPL lifted off its surface (end of visibility rays)
    CameraPoint associated;         // 3.2.2 mail box: a camera-visible point that sees the VPL
    std::uint32_t radianceSeed = 0; // 3.2.3: kept for the VPL's life
    std::uint64_t radianceKey = 0;  // radiance cache: the lights (radianceKeyOf) the value was computed for
    glm::vec3 rankRadiance{0.0f};   // what lines 9-12 rank it by (smcir.rankRadiance = candidate): its line-7
                                    // estimate, seed rankSeed, re-estimated when the lights change (rankKey)
    std::uint32_t rankSeed = 0;
    std::uint64_t rankKey = 0;
    bool screened = false;          // the value is the candidate's (a screening estimate, or the one it was
                                    // selected on): line 18 re-estimates it
};

// A VPL candidate (an element of Y^).
struct SMCIRSampler::Candidate {
    SurfacePoint surface;
    glm::vec3 origin{0.0f};
    std::uint32_t cameraPoint = 0; // index into X of the point whose ray found it
    std::uint32_t seed = 0;        // radiance seed
    glm::vec3 radiance{0.0f};
    float density = 0.0f;
    float intensity = 0.0f;        // shared::luminanceRec709(radiance) / density
};

SMCIRSampler::SMCIRSampler(const Scene& scene, const RayScene& rays, const SMCIRParams& params)
    : mScene(scene), mRays(rays), mParams(params)
{
    const SMCIRParams& p = params;
    require(p.vplCount >= 1, "smcir.vplCount must be >= 1");
    require(p.maxMoves >= 0, "smcir.maxMoves must be >= 0");
    require(p.validationRays >= 0, "smcir.validationRays must be >= 0");
    require(p.validationIterations >= 0, "smcir.validationIterations must be >= 0");
    require(p.candidateFactor >= 1, "smcir.candidateFactor must be >= 1");
    require(p.resampleRetries >= 0, "smcir.resampleRetries must be >= 0");
    require(p.candidateDensityK >= 1, "smcir.candidateDensityK must be >= 1");
    require(p.radiositySamples >= 1, "smcir.radiositySamples must be >= 1");
    require(p.radiosityBounces >= 1 && p.radiosityBounces <= 1024, "smcir.radiosityBounces must be in [1, 1024]");
    require(p.knnRender >= 0, "smcir.knnRender must be >= 0");
    require(p.strongFraction >= 0.0f && p.strongFraction <= 1.0f, "smcir.strongFraction must be in [0, 1]");
    require(p.cameraSamplesX >= 1 && p.cameraSamplesY >= 1, "smcir.cameraSamplesX/Y must be >= 1");
    require(p.warmupIterations >= 0, "smcir.warmupIterations must be >= 0");
    require(&rays.scene() == &scene, "smcir: the RayScene must be built from the sampler's scene");
    if (!p.texturedVPLs) mUntextured = computeUntexturedMaterials(scene);
    mRenderK = p.knnRender > 0 ? p.knnRender : computeRenderingK(p.vplCount);
    mOffset = 1e-4f * rays.sceneScale(); // as the path tracer
    mSet.slots.assign(static_cast<std::size_t>(p.vplCount), VPL{});
    mSlots.assign(static_cast<std::size_t>(p.vplCount), SlotState{});
}

SMCIRSampler::~SMCIRSampler() = default;

const UntexturedMaterials* SMCIRSampler::vplMaterials() const
{
    return mParams.texturedVPLs ? nullptr : &mUntextured;
}

// --- Alg. 1 line 3: X <- RAYCASTFROMCAMERA() -----------------------------------------------------

void SMCIRSampler::castCameraRays(const Camera& camera, float aspect, std::vector<CameraPoint>& points)
{
    // Rays as the rasterizer projects them (the path tracer's CameraRays): through a point of the
    // image, from the eye, clipped to the near and far planes.
    const glm::dmat4 worldFromClip =
        glm::inverse(glm::dmat4(camera.clipFromView(aspect)) * glm::dmat4(camera.viewFromWorld()));
    const glm::dvec3 eye(camera.position);
    auto unproject = [&](double x, double y, double z) {
        const glm::dvec4 p = worldFromClip * glm::dvec4(x, y, z, 1.0);
        return glm::dvec3(p) / p.w;
    };
    const int columns = mParams.cameraSamplesX, rows = mParams.cameraSamplesY;
    const std::size_t cells = static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
    std::vector<CameraPoint> found(cells);
    std::vector<char> hitSurface(cells, 0);
    parallelFor(cells, 64, [&](std::size_t cell) {
        // A jittered grid: one uniform point per cell, new every frame.
        Pcg32 rng = stream(mParams.seed, mFrame, kStageCamera, cell);
        const float jitterX = rng.uniform(), jitterY = rng.uniform();
        const double x = (static_cast<double>(cell % columns) + jitterX) / columns;
        const double y = (static_cast<double>(cell / columns) + jitterY) / rows;
        const double ndcX = 2.0 * x - 1.0, ndcY = 1.0 - 2.0 * y;
        const glm::dvec3 nearPoint = unproject(ndcX, ndcY, -1.0), farPoint = unproject(ndcX, ndcY, 1.0);
        const glm::dvec3 direction = glm::normalize(farPoint - eye);
        Ray ray;
        ray.origin = camera.position;
        ray.direction = glm::vec3(direction);
        ray.tMin = static_cast<float>(std::max(0.0, glm::dot(nearPoint - eye, direction)));
        ray.tMax = static_cast<float>(glm::dot(farPoint - eye, direction));
        const Hit hit = mRays.intersect(ray, Looker::Origin); // the camera
        if (!hit.valid()) return;
        const glm::vec3 wo = -ray.direction;
        const SurfacePoint s = surfaceAt(mScene, hit, wo, vplMaterials());
        if (glm::dot(s.geometricNormal, wo) <= 0.0f) return; // below the horizon (backs are not hit: ray_scene.cpp)
        CameraPoint& point = found[cell];
        point.position = s.position;
        point.normal = s.geometricNormal;
        point.origin = s.position + s.geometricNormal * mOffset;
        hitSurface[cell] = 1;
    });
    mRayCount += cells;
    points.clear();
    for (std::size_t cell = 0; cell < cells; ++cell)
        if (hitSurface[cell]) points.push_back(found[cell]);
}

// --- Alg. 1 line 4: INVALID <- Y \ INDIRECTLYVISIBLEVPLS(X, Y) (3.2.2) ----------------------------

std::vector<char> SMCIRSampler::resolveIndirectVisibility(const Camera& camera, float aspect,
                                                          const std::vector<CameraPoint>& points)
{
    const std::size_t slotCount = mSet.slots.size();
    std::vector<char> validated(slotCount, 0);
    std::atomic<std::uint64_t> rays{0};

    // Mail-boxing: a VPL is still indirectly visible if its associated point is still seen by the
    // camera (in the frustum, facing the eye, unoccluded). The VPL-to-point segment was unoccluded
    // when they were associated and the geometry does not move.
    const glm::mat4 clipFromWorld = camera.clipFromView(aspect) * camera.viewFromWorld();
    parallelFor(slotCount, 64, [&](std::size_t slot) {
        if (!mSet.slots[slot].valid) return;
        const CameraPoint& x = mSlots[slot].associated;
        if (glm::dot(x.normal, camera.position - x.position) <= 0.0f) return;
        const glm::vec4 clip = clipFromWorld * glm::vec4(x.position, 1.0f);
        if (!(clip.w > 0.0f) || std::abs(clip.x) > clip.w || std::abs(clip.y) > clip.w || std::abs(clip.z) > clip.w)
            return;
        rays.fetch_add(1, std::memory_order_relaxed);
        if (mRays.visible(camera.position, x.origin, Looker::Origin)) validated[slot] = 1; // the camera looks
    });

    for (std::size_t slot = 0; slot < slotCount; ++slot)
        if (mSet.slots[slot].valid && !validated[slot]) ++mTimes.mailboxMisses;

    // Validation rounds: every point of X casts rays towards V randomly chosen still-invalid VPLs;
    // a VPL that one of them reaches is valid again and associated with that point (Fig. 6 c, d).
    for (int round = 0; round < mParams.validationIterations && mParams.validationRays > 0 && !points.empty();
         ++round) {
        std::vector<std::uint32_t> invalid;
        for (std::size_t slot = 0; slot < slotCount; ++slot)
            if (mSet.slots[slot].valid && !validated[slot]) invalid.push_back(static_cast<std::uint32_t>(slot));
        if (invalid.empty()) break;
        const auto invalidCount = static_cast<std::uint32_t>(invalid.size());
        const std::uint32_t chosenPerPoint = std::min(static_cast<std::uint32_t>(mParams.validationRays), invalidCount);
        std::vector<std::int32_t> success(points.size() * chosenPerPoint, -1);
        parallelFor(points.size(), 16, [&](std::size_t i) {
            Pcg32 rng = stream(mParams.seed, mFrame, kStageValidation + static_cast<std::uint64_t>(round), i);
            // Floyd's algorithm: chosenPerPoint distinct indices of [0, invalidCount).
            std::uint32_t chosen[1024];
            std::uint32_t count = 0;
            for (std::uint32_t j = invalidCount - chosenPerPoint; j < invalidCount; ++j) {
                const std::uint32_t t = rng.below(j + 1);
                const bool taken = std::find(chosen, chosen + count, t) != chosen + count;
                chosen[count++] = taken ? j : t;
            }
            const CameraPoint& x = points[i];
            std::uint64_t cast = 0;
            for (std::uint32_t j = 0; j < count; ++j) {
                const std::uint32_t slot = invalid[chosen[j]];
                const glm::vec3 y = mSet.slots[slot].position;
                // Only a VPL that emits towards x and lies above x's surface can light x.
                if (glm::dot(x.normal, y - x.position) <= 0.0f) continue;
                if (glm::dot(mSet.slots[slot].normal, x.position - y) <= 0.0f) continue;
                ++cast;
                if (mRays.visible(x.origin, mSlots[slot].origin, Looker::End)) // the VPL looks
                    success[i * chosenPerPoint + j] = static_cast<std::int32_t>(slot);
            }
            rays.fetch_add(cast, std::memory_order_relaxed);
        });
        // The first success in X order wins: the same association whatever the thread count.
        for (std::size_t i = 0; i < points.size(); ++i) {
            for (std::uint32_t j = 0; j < chosenPerPoint; ++j) {
                const std::int32_t slot = success[i * chosenPerPoint + j];
                if (slot < 0 || validated[static_cast<std::size_t>(slot)]) continue;
                validated[static_cast<std::size_t>(slot)] = 1;
                mSlots[static_cast<std::size_t>(slot)].associated = points[i];
            }
        }
    }
    mRayCount += rays.load();
    return validated;
}

// --- Alg. 1 lines 5-6: candidate rays and weighted resampling (3.2.1) ----------------------------

std::vector<SMCIRSampler::Candidate> SMCIRSampler::sampleCandidates(const std::vector<CameraPoint>& points,
                                                                    double& samplingMs, double& resamplingMs)
{
    const Clock::time_point samplingStart = Clock::now();
    const std::size_t budget = mSet.slots.size();
    std::vector<Candidate> candidates;
    if (points.empty()) {
        samplingMs = millisecondsSince(samplingStart);
        resamplingMs = 0.0;
        return candidates;
    }

    // Line 5: candidateFactor * I rays, round-robin over X, uniform over the hemisphere of x.
    const std::size_t rayCount = budget * static_cast<std::size_t>(mParams.candidateFactor);
    std::vector<Candidate> raw(rayCount);
    std::vector<char> hitSurface(rayCount, 0);
    parallelFor(rayCount, 256, [&](std::size_t r) {
        const std::size_t xIndex = r % points.size();
        const CameraPoint& x = points[xIndex];
        Pcg32 rng = stream(mParams.seed, mFrame, kStageCandidateRays, r);
        const float cosTheta = rng.uniform(); // uniform hemisphere: cos(theta) uniform in [0, 1)
        const float phi = 2.0f * shared::kPi * rng.uniform();
        const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
        glm::vec3 t, b;
        makeBasis(x.normal, t, b);
        Ray ray;
        ray.origin = x.origin;
        ray.direction = glm::normalize(sinTheta * std::cos(phi) * t + sinTheta * std::sin(phi) * b + cosTheta * x.normal);
        // A bounce from x (the path tracer's rule): either side stops it, a back reflects nothing.
        const Hit hit = mRays.intersect(ray, Looker::None);
        if (!hit.valid()) return;
        const glm::vec3 wo = -ray.direction;
        const SurfacePoint s = surfaceAt(mScene, hit, wo, vplMaterials());
        if (glm::dot(s.geometricNormal, wo) <= 0.0f) return; // the back of a single-sided surface reflects nothing
        Candidate& c = raw[r];
        c.surface = s;
        c.origin = s.position + s.geometricNormal * mOffset;
        c.cameraPoint = static_cast<std::uint32_t>(xIndex);
        hitSurface[r] = 1;
    });
    mRayCount += rayCount;
    std::vector<std::size_t> hits;
    for (std::size_t r = 0; r < rayCount; ++r)
        if (hitSurface[r]) hits.push_back(r);
    samplingMs = millisecondsSince(samplingStart);

    // Line 6: RESAMPLECANDIDATES. Weights 1/p_raw, with p_raw the kNN area density of the raw
    // points among themselves (self excluded: the (k+1)-th neighbour). The normalisation k/(N pi)
    // cancels, so the weight is r_k^2.
    const Clock::time_point resamplingStart = Clock::now();
    std::vector<std::size_t> selected; // indices into `hits`, ascending
    if (hits.size() <= budget) {
        selected.resize(hits.size());
        std::iota(selected.begin(), selected.end(), std::size_t{0});
    } else {
        std::vector<glm::vec3> positions(hits.size());
        for (std::size_t i = 0; i < hits.size(); ++i)
            positions[i] = raw[hits[i]].surface.position;
        const auto k = static_cast<std::size_t>(mParams.candidateDensityK);
        std::vector<double> weight(hits.size(), 1.0);
        if (mParams.candidateDensityGrid) {
            // Option: the area density of a point ~ count of points in its grid cell / cell area; the
            // cell area is the same everywhere, so the weight is 1/count. Cells are sized for about k
            // points each if the points covered a surface as large as their bounds' diagonal squared.
            AABB box;
            for (const glm::vec3& q : positions) box.extend(q);
            const float cell = std::max(1e-6f, glm::length(box.extent()) /
                                                   std::sqrt(static_cast<float>(positions.size()) / static_cast<float>(k)));
            auto key = [&](const glm::vec3& q) {
                const glm::ivec3 c = glm::ivec3(glm::floor((q - box.lower) / cell));
                return (static_cast<std::uint64_t>(c.x & 0x1FFFFF) << 42u) |
                       (static_cast<std::uint64_t>(c.y & 0x1FFFFF) << 21u) | static_cast<std::uint64_t>(c.z & 0x1FFFFF);
            };
            std::unordered_map<std::uint64_t, std::uint32_t> counts;
            counts.reserve(positions.size());
            for (const glm::vec3& q : positions) ++counts[key(q)];
            for (std::size_t i = 0; i < positions.size(); ++i) weight[i] = 1.0 / counts[key(positions[i])];
        } else if (hits.size() > k) {
            // The grid search returns the kd-tree's r_k^2 bit for bit (test_knn.cpp) in a fraction
            // of its time (#23 part 7; docs/smcir.md, "Sampler cost"); its buffers stay between frames.
            const std::vector<float>& r2 = mCandidateSearch.distancesSquared(positions, k);
            std::copy(r2.begin(), r2.end(), weight.begin());
        }
        std::vector<double> cdf(hits.size());
        double total = 0.0;
        for (std::size_t i = 0; i < hits.size(); ++i) {
            total += weight[i];
            cdf[i] = total;
        }
        // Without replacement as the paper does it on the GPU: draw the missing number of elements,
        // keep the new ones, and redraw at most resampleRetries times (duplicates cost a retry).
        std::vector<char> taken(hits.size(), 0);
        std::size_t takenCount = 0;
        for (int round = 0; round <= mParams.resampleRetries && takenCount < budget && total > 0.0; ++round) {
            const std::size_t draws = budget - takenCount;
            Pcg32 rng = stream(mParams.seed, mFrame, kStageResample + static_cast<std::uint64_t>(round), 0);
            for (std::size_t d = 0; d < draws; ++d) {
                // 53-bit uniform in [0, 1) for the double CDF (two draws, in a fixed order).
                const std::uint64_t high = rng.next();
                const std::uint64_t low = rng.next();
                const double u = static_cast<double>((high << 21u) ^ (low >> 11u)) * 0x1p-53;
                const double target = u * total;
                const auto at = static_cast<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), target) - cdf.begin());
                const std::size_t i = std::min(at, hits.size() - 1);
                if (!taken[i]) {
                    taken[i] = 1;
                    ++takenCount;
                }
            }
        }
        for (std::size_t i = 0; i < hits.size(); ++i)
            if (taken[i]) selected.push_back(i);
    }
    candidates.reserve(selected.size());
    for (std::size_t i = 0; i < selected.size(); ++i) {
        Candidate c = raw[hits[selected[i]]];
        // 3.2.3: a seed of its own, kept while it lives as a VPL.
        c.seed = static_cast<std::uint32_t>(streamKey(mParams.seed, mFrame, kStageRadianceSeed, i));
        candidates.push_back(c);
    }
    mTimes.rawCandidates = static_cast<int>(hits.size());
    resamplingMs = millisecondsSince(resamplingStart);
    return candidates;
}

// --- Alg. 1 lines 7 and 18: radiance (3.2.3) ----------------------------------------------------

void SMCIRSampler::estimateCandidateRadiance(std::vector<Candidate>& candidates)
{
    std::vector<std::uint64_t> rays(candidates.size(), 0);
    parallelFor(candidates.size(), 4, [&](std::size_t i) {
        candidates[i].radiance = mEstimator->estimate(candidates[i].surface, candidateSamples(), candidates[i].seed, &rays[i]);
    });
    mRayCount += std::accumulate(rays.begin(), rays.end(), std::uint64_t{0});
    mEstimates += static_cast<int>(candidates.size());
}

void SMCIRSampler::estimateStaleRadiance()
{
    // Work items: 2 slot for the rendered value, 2 slot + 1 for the ranking value (F1: with the lights
    // changed, a VPL is ranked by a fresh estimate with its candidate seed, still independent of the
    // rendered one).
    const bool separateRank = ranksByCandidateRadiance();
    std::vector<std::uint32_t> stale;
    for (std::size_t slot = 0; slot < mSlots.size(); ++slot) {
        if (!mSet.slots[slot].valid) continue;
        if (mSlots[slot].screened || mSlots[slot].radianceKey != mRadianceKey)
            stale.push_back(static_cast<std::uint32_t>(2 * slot));
        if (separateRank && mSlots[slot].rankKey != mRadianceKey)
            stale.push_back(static_cast<std::uint32_t>(2 * slot + 1));
    }
    std::vector<std::uint64_t> rays(stale.size(), 0);
    parallelFor(stale.size(), 4, [&](std::size_t i) {
        const std::uint32_t slot = stale[i] / 2;
        SlotState& state = mSlots[slot];
        if (stale[i] % 2 == 0) {
            mSet.slots[slot].radiance = mEstimator->estimate(state.surface, mParams.radiositySamples, state.radianceSeed, &rays[i]);
            state.radianceKey = mRadianceKey;
            state.screened = false;
        } else {
            state.rankRadiance = mEstimator->estimate(state.surface, candidateSamples(), state.rankSeed, &rays[i]);
            state.rankKey = mRadianceKey;
        }
    });
    if (!separateRank)
        for (std::size_t slot = 0; slot < mSlots.size(); ++slot)
            mSlots[slot].rankRadiance = mSet.slots[slot].radiance;
    mRayCount += std::accumulate(rays.begin(), rays.end(), std::uint64_t{0});
    mEstimates += static_cast<int>(stale.size());
}

// --- Alg. 1 lines 8 and 19: kNN densities (3.2.4, eq. 7) ------------------------------------------

void SMCIRSampler::estimateCandidateDensities(std::vector<Candidate>& candidates)
{
    // k = 1 against the current VPLs; candidates are not in Y, so nothing is excluded.
    std::vector<glm::vec3> positions;
    for (const VPL& vpl : mSet.slots)
        if (vpl.valid) positions.push_back(vpl.position);
    const KNNIndex index(positions);
    parallelFor(candidates.size(), 64, [&](std::size_t i) {
        Candidate& c = candidates[i];
        c.density = estimateKNNDensity(1, positions.size(), index.kthDistanceSquared(c.surface.position, 1));
        c.intensity = intensityOf(c.radiance, c.density);
    });
}

void SMCIRSampler::estimateRenderingDensities()
{
    std::vector<std::uint32_t> slots;
    std::vector<glm::vec3> positions;
    for (std::size_t slot = 0; slot < mSet.slots.size(); ++slot) {
        if (!mSet.slots[slot].valid) continue;
        slots.push_back(static_cast<std::uint32_t>(slot));
        positions.push_back(mSet.slots[slot].position);
    }
    // k of eq. (8) (or knnRender); r_k to the k-th other VPL, or with knnCountsSelf to the k-th
    // counting y itself (a point is its own nearest neighbour in the index: distance 0).
    const std::size_t n = positions.size();
    const KNNChoice render = knnChoice(mRenderK, n);
    const std::size_t k = render.k;
    const std::size_t slotCount = mSet.slots.size();
    if (mDensityPositions.size() != slotCount) {
        mDensityPositions.assign(slotCount, glm::vec3(0.0f));
        mDensityR2.assign(slotCount, 0.0f);
        mDensityValid.assign(slotCount, 0);
    }
    // The points that appeared or disappeared since the last estimate (at most 2 M_max per frame).
    std::vector<glm::vec3> changedPoints;
    std::vector<char> slotChanged(slotCount, 0);
    for (std::size_t slot = 0; slot < slotCount; ++slot) {
        const VPL& vpl = mSet.slots[slot];
        const bool was = mDensityValid[slot] != 0;
        if (was == vpl.valid && (!vpl.valid || mDensityPositions[slot] == vpl.position)) continue;
        slotChanged[slot] = 1;
        if (was) changedPoints.push_back(mDensityPositions[slot]);
        if (vpl.valid) changedPoints.push_back(vpl.position);
    }
    const KNNIndex index(std::move(positions));
    const bool incremental = mDensityK == render.neighbour;
    parallelFor(slots.size(), 64, [&](std::size_t i) {
        const std::uint32_t slot = slots[i];
        bool requery = !incremental || slotChanged[slot] != 0;
        for (std::size_t c = 0; !requery && c < changedPoints.size(); ++c) {
            const glm::vec3 d = changedPoints[c] - mSet.slots[slot].position;
            requery = glm::dot(d, d) <= mDensityR2[slot]; // inside (or on) the k-th neighbour sphere
        }
        if (requery)
            mDensityR2[slot] = k > 0 ? index.kthDistanceSquared(mSet.slots[slot].position, render.neighbour) : 0.0f;
    });
    for (std::size_t slot = 0; slot < slotCount; ++slot) {
        mDensityValid[slot] = mSet.slots[slot].valid ? 1 : 0;
        mDensityPositions[slot] = mSet.slots[slot].position;
    }
    mDensityK = render.neighbour;
    for (std::uint32_t slot : slots)
        mSet.slots[slot].density = k > 0 ? estimateKNNDensity(k, n, mDensityR2[slot]) : 0.0f;

    // F3 (smcir.knnRank): the densities lines 9-12 of the next frame rank by, with their own k.
    mRankDensity.assign(slotCount, 0.0f);
    const KNNChoice rank = knnChoice(mParams.knnRank > 0 ? mParams.knnRank : mRenderK, n);
    if (rank.neighbour == render.neighbour) {
        for (std::uint32_t slot : slots)
            mRankDensity[slot] = mSet.slots[slot].density;
        return;
    }
    parallelFor(slots.size(), 64, [&](std::size_t i) {
        const std::uint32_t slot = slots[i];
        mRankDensity[slot] =
            rank.k > 0 ? estimateKNNDensity(rank.k, n, index.kthDistanceSquared(mSet.slots[slot].position, rank.neighbour))
                       : 0.0f;
    });
}

SMCIRSampler::KNNChoice SMCIRSampler::knnChoice(int wanted, std::size_t n) const
{
    KNNChoice c;
    if (mParams.knnCountsSelf) {
        if (n < 2) return c; // a lone VPL has no neighbour to measure its density with
        c.k = std::min(static_cast<std::size_t>(std::max(wanted, 2)), n);
        c.neighbour = c.k; // y is the first
    } else {
        if (n < 2) return c;
        c.k = std::min(static_cast<std::size_t>(wanted), n - 1);
        c.neighbour = c.k + 1; // the k-th other
    }
    return c;
}

// Numeric guard before publication: every valid slot has a finite radiance, a finite density >= 0
// and a finite intensity L / p (radiance set to 0 otherwise: a dark VPL keeps its slot and the n
// of the estimator). A NaN from a degenerate surface or an overflowing estimate would otherwise
// reach every pixel the VPL lights, and through the filter their neighbours.
void SMCIRSampler::guardPublishedVPLs()
{
    const auto finite = [](const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    for (VPL& vpl : mSet.slots) {
        if (!vpl.valid) continue;
        if (!std::isfinite(vpl.density) || vpl.density < 0.0f) vpl.density = 0.0f;
        if (!finite(vpl.radiance) || (vpl.density > 0.0f && !finite(vpl.radiance / vpl.density)))
            vpl.radiance = glm::vec3(0.0f);
    }
}

// --- Slots ---------------------------------------------------------------------------------------

void SMCIRSampler::assignSlot(std::uint32_t slot, const Candidate& candidate, const std::vector<CameraPoint>& points)
{
    VPL& vpl = mSet.slots[slot];
    vpl.position = candidate.surface.position;
    vpl.normal = candidate.surface.normal;
    vpl.radiance = candidate.radiance;
    vpl.density = candidate.density; // replaced by line 19 before publication
    vpl.valid = true;
    SlotState& state = mSlots[slot];
    state.surface = candidate.surface;
    state.origin = candidate.origin;
    state.associated = points[candidate.cameraPoint]; // 3.2.2: the point it was generated from
    // Line 18 re-estimates a screened candidate (fewer samples than a VPL gets) in full, and with
    // independentRadiance every new VPL, with a lifetime seed of its own: the value it renders with is
    // then independent of the value it won the selection with (lines 13-17), which would be biased
    // high (selection keeps the estimates that came out high).
    state.radianceSeed = mParams.independentRadiance ? mix64(candidate.seed ^ 0x9E3779B97F4A7C15ull) : candidate.seed;
    state.radianceKey = mRadianceKey;
    state.screened = mParams.independentRadiance || candidateSamples() != mParams.radiositySamples;
    state.rankRadiance = candidate.radiance;
    state.rankSeed = candidate.seed;
    state.rankKey = mRadianceKey;
}

std::vector<glm::vec3> SMCIRSampler::estimateRadianceAgain(int samples, std::uint32_t seed) const
{
    require(mInitialized && mEstimator, "smcir: estimateRadianceAgain() before initialize()");
    require(samples >= 1, "smcir: estimateRadianceAgain() needs samples >= 1");
    std::vector<glm::vec3> radiance(mSet.slots.size(), glm::vec3(0.0f));
    parallelFor(mSet.slots.size(), 4, [&](std::size_t slot) {
        if (!mSet.slots[slot].valid) return;
        const auto pathSeed = static_cast<std::uint32_t>(mix64((std::uint64_t{seed} << 32) ^ slot));
        radiance[slot] = mEstimator->estimate(mSlots[slot].surface, samples, pathSeed);
    });
    return radiance;
}

bool SMCIRSampler::ranksByCandidateRadiance() const
{
    // Without independentRadiance (and with equal samples) the candidate estimate is the rendered one.
    return mParams.rankRadiance == kRankByCandidateRadiance &&
           (mParams.independentRadiance || candidateSamples() != mParams.radiositySamples);
}

int SMCIRSampler::candidateSamples() const
{
    return mParams.candidateRadianceSamples > 0 ? std::min(mParams.candidateRadianceSamples, mParams.radiositySamples)
                                                : mParams.radiositySamples;
}

void SMCIRSampler::clearSlot(std::uint32_t slot)
{
    mSet.slots[slot] = VPL{};
    mSlots[slot] = SlotState{};
}

// --- Alg. 1 line 1 and the frame loop --------------------------------------------------------------

void SMCIRSampler::beginFrame(const FrameSnapshot& snapshot)
{
    require(snapshot.aspect > 0.0f && std::isfinite(snapshot.aspect), "smcir: aspect must be > 0");
    // 3.2.3's cache is keyed by the lights it was computed for: a value computed for other lights is
    // stale, whoever changed them. The measurement aid invalidateEveryFrame makes every frame a new key.
    mRadianceKey = hashLights(snapshot.lights);
    if (mParams.reestimateEveryFrame) mRadianceKey = mix64(mRadianceKey ^ (mFrame + 1));

    mTimes = SMCIRStageTimes{};
    mRayCount = 0;
    mEstimates = 0;
}

std::vector<SMCIRSampler::CameraPoint> SMCIRSampler::timedCameraPoints(const Camera& camera, float aspect)
{
    const Clock::time_point t = Clock::now();
    std::vector<CameraPoint> points;
    castCameraRays(camera, aspect, points);
    mTimes.cameraRays = millisecondsSince(t);
    mTimes.cameraPoints = static_cast<int>(points.size());
    return points;
}

std::vector<SMCIRSampler::Candidate> SMCIRSampler::candidatesWithRadiance(const std::vector<CameraPoint>& points,
                                                                          const std::vector<Light>& lights)
{
    // Lines 5-6: candidate rays from X, resampled to an area-uniform set (3.2.1).
    std::vector<Candidate> candidates = sampleCandidates(points, mTimes.candidateSampling, mTimes.candidateResampling);
    mTimes.candidates = static_cast<int>(candidates.size());
    // Line 7: their radiance, lit by this frame's snapshot of the lights.
    const Clock::time_point t = Clock::now();
    mEstimator = std::make_unique<ReflectedRadianceEstimator>(mScene, mRays, lights, mParams.radiosityBounces,
                                                              vplMaterials());
    estimateCandidateRadiance(candidates);
    mTimes.radiosity = millisecondsSince(t);
    return candidates;
}

void SMCIRSampler::initialize(const Camera& camera, float aspect, const std::function<void(int, int)>& progress)
{
    initialize(FrameSnapshot::of(mScene, camera, aspect), progress);
}

void SMCIRSampler::step(const Camera& camera, float aspect)
{
    step(FrameSnapshot::of(mScene, camera, aspect));
}

StatList SMCIRSampler::stats() const
{
    const SMCIRStageTimes& t = mTimes;
    return {{"sampler: camera rays ms", t.cameraRays},
            {"sampler: candidate sampling ms", t.candidateSampling},
            {"sampler: candidate resampling ms", t.candidateResampling},
            {"sampler: indirect visibility ms", t.indirectVisibility},
            {"sampler: radiosity ms", t.radiosity},
            {"sampler: kNN ms", t.knn},
            {"sampler: selection ms", t.selection},
            {"sampler: total ms", t.total},
            {"sampler: rays", static_cast<double>(t.rays)},
            {"sampler: radiance estimates", static_cast<double>(t.radianceEstimates)}};
}

void SMCIRSampler::initialize(const FrameSnapshot& snapshot, const Progress& progress)
{
    const Camera& camera = snapshot.camera;
    const float aspect = snapshot.aspect;
    const Clock::time_point start = Clock::now();
    mFrame = 0;
    beginFrame(snapshot);
    for (std::uint32_t slot = 0; slot < mSet.slots.size(); ++slot)
        clearSlot(slot);

    // Line 1: INITIALIZEVPLS, sampled "identically to how we generate candidate VPLs" (3.2).
    const std::vector<CameraPoint> points = timedCameraPoints(camera, aspect);
    std::vector<Candidate> candidates = candidatesWithRadiance(points, snapshot.lights);
    Clock::time_point t = Clock::now();
    for (std::size_t i = 0; i < candidates.size() && i < mSet.slots.size(); ++i)
        assignSlot(static_cast<std::uint32_t>(i), candidates[i], points);
    estimateStaleRadiance(); // only new VPLs (independentRadiance, candidateRadianceSamples) are stale here
    mTimes.radiosity += millisecondsSince(t);
    t = Clock::now();
    estimateRenderingDensities();
    guardPublishedVPLs();
    mTimes.knn = millisecondsSince(t);
    mInitialized = true;
    mTimes.rays = mRayCount;
    mTimes.radianceEstimates = mEstimates;
    mTimes.total = millisecondsSince(start);

    // "we run 100 iterations of the algorithm before rendering the first frame" (3.2).
    for (int i = 0; i < mParams.warmupIterations; ++i) {
        step(snapshot);
        if (progress) progress(i + 1, mParams.warmupIterations);
    }
    // The renderer has seen nothing yet: every slot is new to it.
    mSet.changed.resize(mSet.slots.size());
    std::iota(mSet.changed.begin(), mSet.changed.end(), std::uint32_t{0});
    mTimes.moved = static_cast<int>(mSet.changed.size());
    ++mSet.generation;
}

void SMCIRSampler::step(const FrameSnapshot& snapshot)
{
    require(mInitialized, "smcir: step() before initialize()");
    const Camera& camera = snapshot.camera;
    const float aspect = snapshot.aspect;
    const Clock::time_point start = Clock::now();
    ++mFrame;
    beginFrame(snapshot);
    const std::size_t slotCount = mSet.slots.size();

    // Line 3: X <- RAYCASTFROMCAMERA().
    const std::vector<CameraPoint> points = timedCameraPoints(camera, aspect);

    // Line 4: INVALID <- Y \ INDIRECTLYVISIBLEVPLS(X, Y).
    Clock::time_point t = Clock::now();
    const std::vector<char> validated = resolveIndirectVisibility(camera, aspect, points);
    mTimes.indirectVisibility = millisecondsSince(t);

    // Lines 5-7: Y^ <- RESAMPLECANDIDATES(RAYCASTFROMPOINTS(X)); ESTIMATERADIOSITIES(Y^).
    std::vector<Candidate> candidates = candidatesWithRadiance(points, snapshot.lights);

    // Line 8: ESTIMATEPROBABILITYDENSITIES(Y^), k = 1 against the current Y.
    t = Clock::now();
    estimateCandidateDensities(candidates);
    mTimes.knn = millisecondsSince(t);

    t = Clock::now();
    // Intensities of the current VPLs: last frame's radiance and density, not re-estimated yet (3.2).
    std::vector<float> intensity(slotCount, 0.0f);
    std::vector<float> sorted;
    std::size_t invalidCount = 0;
    for (std::size_t slot = 0; slot < slotCount; ++slot) {
        const VPL& vpl = mSet.slots[slot];
        if (!vpl.valid) continue;
        // Lines 9-12 rank by the radiance of smcir.rankRadiance and the density of smcir.knnRank.
        intensity[slot] = intensityOf(mSlots[slot].rankRadiance, mRankDensity[slot]);
        sorted.push_back(intensity[slot]);
        if (!validated[slot]) ++invalidCount;
    }
    mTimes.invalidated = static_cast<int>(invalidCount);
    std::sort(sorted.begin(), sorted.end());

    // Line 9, eq. (9): M_min = min(M_max, M_strong); M_strong counts the candidates stronger than
    // strongFraction of the current VPLs, i.e. above the ceil(fraction n)-th smallest intensity.
    const auto weaker = static_cast<std::size_t>(std::ceil(static_cast<double>(mParams.strongFraction) * sorted.size()));
    const float threshold = weaker == 0 ? -std::numeric_limits<float>::infinity() : sorted[weaker - 1];
    std::size_t strong = 0;
    for (const Candidate& c : candidates)
        if (c.intensity > threshold) ++strong;
    mTimes.strongCandidates = static_cast<int>(strong);
    const std::size_t maxMoves = static_cast<std::size_t>(mParams.maxMoves);
    const std::size_t minMoves = std::min(maxMoves, strong);

    // Slots to free, in order: empty slots (the set is short of I), INVALID from the weakest up,
    // and lines 10-12: the weakest valid VPLs while |INVALID| < M_min.
    auto weakerFirst = [&](std::uint32_t a, std::uint32_t b) {
        return intensity[a] != intensity[b] ? intensity[a] < intensity[b] : a < b;
    };
    std::vector<std::uint32_t> empty, invalid, valid;
    for (std::uint32_t slot = 0; slot < slotCount; ++slot) {
        if (!mSet.slots[slot].valid) empty.push_back(slot);
        else if (!validated[slot]) invalid.push_back(slot);
        else valid.push_back(slot);
    }
    std::sort(invalid.begin(), invalid.end(), weakerFirst);
    std::vector<std::uint32_t> freed = empty;
    freed.insert(freed.end(), invalid.begin(), invalid.end());
    if (invalid.size() < minMoves) {
        const std::size_t weakest = minMoves - invalid.size();
        std::partial_sort(valid.begin(), valid.begin() + static_cast<std::ptrdiff_t>(std::min(weakest, valid.size())),
                          valid.end(), weakerFirst);
        freed.insert(freed.end(), valid.begin(), valid.begin() + static_cast<std::ptrdiff_t>(std::min(weakest, valid.size())));
    }
    // Line 13: Y <- Y \ CLAMPSIZE(INVALID, M_max).
    if (freed.size() > maxMoves) freed.resize(maxMoves);

    // Lines 14-17: fill the freed slots with the strongest candidates.
    std::vector<std::uint32_t> order(candidates.size());
    std::iota(order.begin(), order.end(), std::uint32_t{0});
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        return candidates[a].intensity != candidates[b].intensity ? candidates[a].intensity > candidates[b].intensity
                                                                  : a < b;
    });
    std::vector<std::uint32_t> changed;
    std::size_t next = 0;
    for (std::uint32_t slot : freed) {
        if (next < order.size()) {
            assignSlot(slot, candidates[order[next++]], points);
            changed.push_back(slot);
        } else if (mSet.slots[slot].valid) {
            clearSlot(slot); // no candidate left: the VPL is removed all the same
            changed.push_back(slot);
        }
    }
    std::sort(changed.begin(), changed.end());
    mTimes.selection = millisecondsSince(t);

    // Line 18: ESTIMATERADIOSITIES(Y), only where the cache is stale.
    t = Clock::now();
    estimateStaleRadiance();
    mTimes.radiosity += millisecondsSince(t);

    // Line 19: ESTIMATEPROBABILITYDENSITIES(Y) with k of eq. (8).
    t = Clock::now();
    estimateRenderingDensities();
    guardPublishedVPLs();
    mTimes.knn += millisecondsSince(t);

    mSet.changed = std::move(changed);
    ++mSet.generation;
    mTimes.moved = static_cast<int>(mSet.changed.size());
    mTimes.rays = mRayCount;
    mTimes.radianceEstimates = mEstimates;
    mTimes.total = millisecondsSince(start);
}

} // namespace vplgi
