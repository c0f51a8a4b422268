#include "core/vpl/mir_sampler.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/scene/surface.h"
#include "core/trace/path_tracer.h"
#include "core/util/error.h"
#include "core/util/params.h"
#include "core/util/random.h"
#include "glsl/shared/brdf.h"
#include "glsl/shared/tonemap.h"

namespace vplgi {

void MIRParams::visitParams(ParamVisitor& v)
{
    v.field("mir.vplCount", vplCount, 1, 65536, "I: VPL budget (slots)");
    v.field("mir.resamplingRate", resamplingRate, 1, 4096,
            "candidate VPLs per VPL kept (SMCIR 5.1: 256:1); rate * vplCount <= 1048576");
    v.field("mir.bounces", bounces, 1, 64, "most surface hits per light path that deposit a candidate (paper: 3)");
    v.field("mir.cameraSamplesX", cameraSamplesX, 1, 256,
            "camera points that estimate each candidate's contribution to the image: grid columns (not in the paper)");
    v.field("mir.cameraSamplesY", cameraSamplesY, 1, 256, "camera points: grid rows (not in the paper)");
    v.field("mir.defensive", defensive, 0.0f, 10.0f,
            "weight every candidate keeps, in units of the mean importance, so that light the camera points do not "
            "see is not lost (not in the paper)");
    v.field("mir.seed", seed, "random stream seed (same seed, camera and lights, same VPLs)");
    v.field("mir.texturedVPLs", texturedVPLs,
            "VPLs on the textured scene; false = untextured, mean material albedos (SMCIR section 5)");
}

namespace {

using Clock = std::chrono::steady_clock;

double millisecondsSince(Clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

Pcg32 mirStream(std::uint32_t seed, std::uint64_t frame, std::uint64_t stage, std::uint64_t index)
{
    // Distinct from IR's path streams and SMCIR's stages by the leading constant.
    const std::uint64_t key =
        mix64(mix64(mix64(mix64((static_cast<std::uint64_t>(seed) << 32u) ^ 0x4D1B5EEDull) ^ frame) ^ stage) ^ index);
    return Pcg32(key, mix64(key ^ 0x9E3779B97F4A7C15ull));
}

constexpr std::uint64_t kStageCamera = 1, kStageResample = 2;

IRParams candidateParams(const MIRParams& p)
{
    IRParams ir;
    ir.vplCount = p.vplCount * p.resamplingRate;
    ir.bounces = p.bounces;
    ir.seed = p.seed;
    ir.fillBudget = true;      // every candidate slot taken
    ir.fixedSequence = false;  // a new set every frame (MIR has no temporal coherence)
    ir.texturedVPLs = p.texturedVPLs;
    return ir;
}

const MIRParams& checked(const MIRParams& p)
{
    require(p.vplCount >= 1 && p.vplCount <= 65536, "mir.vplCount must be in [1, 65536]");
    require(p.resamplingRate >= 1 && p.resamplingRate <= 4096, "mir.resamplingRate must be in [1, 4096]");
    require(static_cast<long long>(p.vplCount) * p.resamplingRate <= (1 << 20),
            "mir: vplCount x resamplingRate = " +
                std::to_string(static_cast<long long>(p.vplCount) * p.resamplingRate) +
                " candidates, more than 1048576");
    require(p.cameraSamplesX >= 1 && p.cameraSamplesX <= 256 && p.cameraSamplesY >= 1 && p.cameraSamplesY <= 256,
            "mir.cameraSamplesX and mir.cameraSamplesY must be in [1, 256]");
    require(p.defensive >= 0.0f && p.defensive <= 10.0f, "mir.defensive must be in [0, 10]");
    return p;
}

} // namespace

// A surface point the camera sees, with what the importance needs of it.
struct MIRSampler::CameraPoint {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f};          // shading normal, unit
    glm::vec3 geometricNormal{0.0f}; // unit, the camera's side
    glm::vec3 towardsEye{0.0f};      // w_o, unit
    shared::SurfaceMaterial material{};
};

MIRSampler::MIRSampler(const Scene& scene, const RayScene& rays, const MIRParams& params, float clampGeometry)
    : mScene(scene), mRays(rays), mParams(checked(params)), mClampGeometry(std::max(clampGeometry, 0.0f)),
      mCandidates(std::make_unique<IRSampler>(scene, rays, candidateParams(params)))
{
    mOffset = 1e-4f * rays.sceneScale(); // as the path tracer
    mSet.slots.assign(static_cast<std::size_t>(mParams.vplCount), VPL{});
}

MIRSampler::~MIRSampler() = default;

// Step 2: K primary rays through a jittered grid (the path tracer's camera rays), new every frame.
std::vector<MIRSampler::CameraPoint> MIRSampler::cameraPoints(const FrameSnapshot& snapshot)
{
    const int columns = mParams.cameraSamplesX, rows = mParams.cameraSamplesY;
    // CameraRays takes an image size; one of 4096 rows with the view's aspect gives its rays.
    const int height = 4096, width = std::max(1, static_cast<int>(std::lround(4096.0 * snapshot.aspect)));
    const CameraRays cameraRays(snapshot.camera, width, height);
    const std::size_t cells = static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows);
    std::vector<CameraPoint> found(cells);
    std::vector<char> hit(cells, 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 16), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t cell = r.begin(); cell != r.end(); ++cell) {
            Pcg32 rng = mirStream(mParams.seed, mFrame, kStageCamera, cell);
            const double u = (static_cast<double>(cell % columns) + rng.uniform()) / columns;
            const double v = (static_cast<double>(cell / columns) + rng.uniform()) / rows;
            const Ray ray = cameraRays.at(u * width, v * height);
            const Hit h = mRays.intersect(ray, Looker::Origin); // the camera
            if (!h.valid()) continue;
            const glm::vec3 wo = -ray.direction;
            // The camera sees the textured surface (the renderer shades it so).
            const SurfacePoint s = surfaceAt(mScene, h, wo);
            if (glm::dot(s.geometricNormal, wo) <= 0.0f) continue;
            CameraPoint& p = found[cell];
            p.position = s.position;
            p.normal = s.normal;
            p.geometricNormal = s.geometricNormal;
            p.towardsEye = wo;
            p.material = s.material;
            hit[cell] = 1;
        }
    });
    mStats.rays += cells;
    std::vector<CameraPoint> points;
    for (std::size_t cell = 0; cell < cells; ++cell)
        if (hit[cell]) points.push_back(found[cell]);
    return points;
}

void MIRSampler::buildFrame(const FrameSnapshot& snapshot)
{
    const Clock::time_point start = Clock::now();
    mStats = MIRStats{};
    // Step 1: the candidates, IR's light paths (a new sequence every frame).
    if (mFrame == 0)
        mCandidates->initialize(snapshot);
    else
        mCandidates->step(snapshot);
    const VPLSet& candidates = mCandidates->vpls();
    mStats.rays += mCandidates->lastStats().rays;
    mStats.candidateMs = millisecondsSince(start);

    // Step 2-3: camera points and each candidate's importance C_j.
    Clock::time_point t = Clock::now();
    const std::vector<CameraPoint> points = cameraPoints(snapshot);
    mStats.cameraPoints = static_cast<int>(points.size());
    const std::size_t m = candidates.slots.size();
    mImportance.assign(m, 0.0f);
    const float gMax = mClampGeometry;
    const float invK = points.empty() ? 0.0f : 1.0f / static_cast<float>(points.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m, 256), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t j = r.begin(); j != r.end(); ++j) {
            const VPL& y = candidates.slots[j];
            if (!y.valid) continue;
            float sum = 0.0f;
            for (const CameraPoint& x : points) {
                const glm::vec3 toY = y.position - x.position;
                const float d2 = glm::dot(toY, toY);
                if (!(d2 > 0.0f)) continue;
                const glm::vec3 w = toY / std::sqrt(d2);
                const float cosX = glm::dot(x.normal, w), cosY = -glm::dot(y.normal, w);
                if (cosX <= 0.0f || cosY <= 0.0f || glm::dot(x.geometricNormal, w) <= 0.0f) continue;
                float g = cosX * cosY / d2;
                if (gMax > 0.0f) g = std::min(g, gMax); // the renderer's clamp (vpl_gather.h)
                sum += shared::luminanceRec709(shared::evaluateBRDF(x.material, x.normal, x.towardsEye, w)) * g;
            }
            mImportance[j] = sum * invK;
        }
    });
    mStats.importanceMs = millisecondsSince(t);

    // Step 3: weights w_j = lum(e_j) (C_j + delta C_bar). Luminance of IR's intensity: the factor M
    // between it and e_j cancels in W / w_j.
    t = Clock::now();
    std::vector<double> weight(m, 0.0);
    double power = 0.0, seen = 0.0, unseen = 0.0;
    for (std::size_t j = 0; j < m; ++j) {
        if (!candidates.slots[j].valid) continue;
        const double l = shared::luminanceRec709(candidates.slots[j].intensity());
        power += l;
        seen += l * mImportance[j];
        if (!(mImportance[j] > 0.0f)) unseen += l;
        weight[j] = l;
    }
    // No camera point sees anything that candidates reach (C_bar = 0): the weights are the fluxes,
    // IR's own distribution.
    const double meanImportance = power > 0.0 ? seen / power : 0.0;
    double total = 0.0;
    for (std::size_t j = 0; j < m; ++j) {
        if (meanImportance > 0.0) weight[j] *= mImportance[j] + mParams.defensive * meanImportance;
        total += weight[j];
    }
    mStats.unseenFlux = power > 0.0 ? unseen / power : 0.0;

    // Step 4: systematic resampling, I draws at (i + u) W / I.
    const std::size_t slots = mSet.slots.size();
    const double candidateCount = static_cast<double>(mCandidates->vpls().validCount());
    std::fill(mSet.slots.begin(), mSet.slots.end(), VPL{});
    if (total > 0.0 && candidateCount > 0.0) {
        Pcg32 rng = mirStream(mParams.seed, mFrame, kStageResample, 0);
        const double u = rng.uniform();
        const double step = total / static_cast<double>(slots);
        double cumulative = 0.0;
        std::size_t j = 0, previous = m;
        for (std::size_t i = 0; i < slots; ++i) {
            const double target = (static_cast<double>(i) + u) * step;
            while (j + 1 < m && (weight[j] == 0.0 || cumulative + weight[j] <= target)) cumulative += weight[j++];
            if (weight[j] == 0.0) break; // rounding at the end of the list
            const VPL& c = candidates.slots[j];
            VPL& vpl = mSet.slots[i];
            vpl.position = c.position;
            vpl.normal = c.normal;
            // I_i = e_j W / w_j with e_j = IR's intensity / M (its 1/n convention undone). Published as
            // IR does: density 1 [1/m^2], radiance = the intensity (VPL::intensity() returns it).
            vpl.radiance = c.intensity() * static_cast<float>(total / (weight[j] * candidateCount));
            vpl.density = 1.0f;
            vpl.valid = true;
            ++mStats.vpls;
            if (j != previous) ++mStats.distinct;
            previous = j;
        }
    }
    mStats.candidates = static_cast<int>(candidateCount);
    mStats.resampleMs = millisecondsSince(t);
    mStats.ms = millisecondsSince(start);
}

void MIRSampler::initialize(const FrameSnapshot& snapshot, const Progress& progress)
{
    mFrame = 0;
    buildFrame(snapshot);
    mInitialized = true;
    mSet.changed.resize(mSet.slots.size());
    std::iota(mSet.changed.begin(), mSet.changed.end(), std::uint32_t{0});
    ++mSet.generation;
    if (progress) progress(1, 1);
}

void MIRSampler::step(const FrameSnapshot& snapshot)
{
    require(mInitialized, "mir: step() before initialize()");
    ++mFrame;
    buildFrame(snapshot);
    // A new set every frame: every slot changed (its shadow map is re-rendered).
    mSet.changed.resize(mSet.slots.size());
    std::iota(mSet.changed.begin(), mSet.changed.end(), std::uint32_t{0});
    ++mSet.generation;
}

StatList MIRSampler::stats() const
{
    return {{"mir: candidates", static_cast<double>(mStats.candidates)},
            {"mir: camera points", static_cast<double>(mStats.cameraPoints)},
            {"mir: distinct", static_cast<double>(mStats.distinct)},
            {"mir: VPLs", static_cast<double>(mStats.vpls)},
            {"mir: unseen flux", mStats.unseenFlux},
            {"mir: rays", static_cast<double>(mStats.rays)},
            {"mir: candidates ms", mStats.candidateMs},
            {"mir: importance ms", mStats.importanceMs},
            {"mir: resample ms", mStats.resampleMs},
            {"sampler: total ms", mStats.ms}}; // the name every VPL sampler uses (vplgi bench)
}

} // namespace vplgi
