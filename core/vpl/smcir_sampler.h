// The CPU half of SMCIR: the sequential Monte Carlo VPL sampler of Algorithm 1, on Embree.
//
// Intro
// -----
// Sequential Monte Carlo Instant Radiosity (Hedman, Karras, Lehtinen 2017; papers/000) keeps one
// set of I virtual point lights alive across frames instead of drawing a fresh set every frame.
// Each frame at most M_max of them move, which is what keeps the indirect light from flickering.
// The set aims at two things (3.1): VPLs only on surfaces *indirectly visible* to the camera (seen
// from some surface the camera sees), and a density proportional to the radiosity, p(y) ~ L(y), so
// that every VPL has about the same intensity I(y) = L(y)/p(y) (eq. 6). The density of a set that
// evolved over many frames has no closed form; it is estimated with kNN (eq. 7, core/util/knn.h).
// This class is the sampler only: the renderer (gl/techniques) shades with the published set
// through eq. (5), L_ind(x) = (1/I) sum_i f(x) G(x, y_i) V(x, y_i) I(y_i) (core/vpl/vpl.h, MATH.md 1.4).
//
// Overview (Algorithm 1; one call of step() is one frame, lines 3-19)
// --------
//  initialize()  line 1: X from the camera, candidates exactly as in a frame, every slot filled
//                from them; then `warmupIterations` frames (the paper runs 100 before frame one).
//  step()
//   line 3     X <- RAYCASTFROMCAMERA          primary rays on a jittered grid (Embree)
//   line 4     INVALID <- Y \ INDIRECTLYVISIBLE  mail-boxing + V validation rays per X point (3.2.2)
//   line 5     candidate rays                  16 I rays from X, uniform hemisphere (3.2.1)
//   line 6     RESAMPLECANDIDATES              16:1 weighted resampling to I candidates, weights 1/p_raw
//   line 7     radiosities of the candidates   path tracer, 16 samples, 3 bounces, per-VPL seed (3.2.3)
//   line 8     densities of the candidates     kNN with k = 1 against the current Y (3.2.4)
//   line 9     M_min = min(M_max, M_strong)     candidates stronger than 95 % of Y (eq. 9, 3.2.5)
//   lines 10-12  INVALID += weakest VPLs until |INVALID| >= M_min
//   lines 13-17  remove CLAMPSIZE(INVALID, M_max), refill those slots with the strongest candidates
//   line 18    radiosities of Y                only where the cache is stale (the lights changed)
//   line 19    densities of Y                  kNN with k of eq. (8), self excluded
//
// Details
// -------
//  Camera points X (line 3): cameraSamplesX x cameraSamplesY primary rays, one per cell of a grid
//  over the image, jittered anew every frame. They are cast with Embree, not read back from the
//  G-buffer: the sampler runs on its own thread, decoupled from the GPU frame, and reading the
//  G-buffer back would make it wait for the GPU (a sync point per frame) and tie it to the GPU's
//  resolution. Rays pass through the back of single-sided surfaces, as the rasterizer culls them
//  (the back-face rule, scene.h Material::doubleSided).
//
//  Indirect visibility (3.2.2, line 4): every VPL remembers an associated camera-visible point x
//  that sees it (mail-boxing); at creation, the point whose ray found it. The scene is static for
//  Embree, so x still sees the VPL; the VPL stays valid while x is still seen by the camera:
//  inside the view frustum, facing the eye, and unoccluded (one shadow ray). The others are
//  INVALID and get `validationIterations` rounds of validation rays. The paper: "casting rays from
//  these points towards V randomly chosen invalid VPLs ... associate it with the point that chose
//  it", so in each round every point of X chooses V distinct VPLs among those still invalid (all of
//  them if fewer) and casts a shadow ray to each that faces it; the first success in X order
//  validates the VPL and becomes its new associated point. A round costs at most |X| V rays, and
//  nothing when no VPL is invalid (a static camera). The test is not exhaustive; the paper relies
//  on the rest of the method being robust to a few wrong classifications, and still-invalid VPLs
//  are the first to be replaced.
//
//  Candidates (3.2.1, lines 5-6): candidateFactor * I rays, round-robin over the points of X,
//  directions uniform over the hemisphere of x's geometric normal. Uniform rather than cosine: 3.1
//  replaces the importance and geometry terms at the primary hits by one, so nothing asks for a
//  cos(theta_x) weight, and uniform directions reach the surfaces seen at grazing angles (walls
//  down a corridor, a room through a door) more often, where the resampling below needs raw
//  points most. Valid hits (front sides, or double-sided) are the raw points. The paper wants the
//  candidates uniform in area, so the resampling weight of a raw point is 1/p_raw, with p_raw the
//  area density of the raw points. It is estimated with kNN among the raw points themselves
//  (k = candidateDensityK, self excluded), not from the ray's pdf: the pdf of the one ray that
//  found a point, cos(theta_y) / (2 pi d^2), is not the point's density. The points are a mixture
//  over all of X, with visibility, and weighting by one component's pdf would favour surfaces that
//  many points of X see; kNN measures the actual mixture, visibility included, and E[1/p] is
//  exact (MATH.md 2). Resampling without replacement as the paper does it: I draws from the
//  weights, duplicates rejected, redrawn for the missing ones at most resampleRetries times, so a
//  frame may end with fewer than I candidates.
//
//  Radiance (3.2.3, lines 7 and 18): L(y) is the diffuse exitant radiance reflected at y
//  (ReflectedRadianceEstimator: path tracer with NEE + MIS, radiositySamples paths, light reflected
//  at most radiosityBounces times counting y, y's own emission excluded because emitters are drawn
//  by the direct pass). Each candidate gets a seed from (seed, frame, index) that it keeps for its
//  whole life as a VPL, so its paths, and hence its radiance, stay the same from frame to frame.
//  The value is cached, keyed by a hash of the lights it was computed for (the frame snapshot's):
//  surviving VPLs are not traced again while the lights stay the same, and line 18 re-traces every
//  VPL whose key differs, with its own seed, in the frame the lights change. Lines 9-12 of that
//  frame compare the candidates (new light) with the VPLs' cached (old) values, as the paper does.
//
//  Untextured scene (section 5): "we use an untextured version of the scene for the VPL generation
//  and use average material colors as albedos. The path traced reference images use the same
//  approximation". By default VPL surfaces and the radiance paths see UntexturedMaterials (core/
//  surface.h: mean albedo per material, no normal maps), and the clamped or indirect reference for
//  SMCIR is rendered with reference.untexturedBounces. smcir.texturedVPLs = true is not in the paper.
//
//  Densities (3.2.4, eq. 7, lines 8 and 19): p(y) = k / (n pi r_k(y)^2), n the number of VPLs in
//  the set (I when full). Candidates: k = 1 against the current Y (candidates are not in Y, so
//  nothing is excluded); a candidate near an existing VPL gets a high density and a low intensity,
//  which spreads VPLs like blue noise. Rendering: k = knnRender, or 0 = eq. (8) read as
//  k = max(1, floor(sqrt(I / 32))) (papers/README.md: 8 at I = 2048). "The k-th nearest neighbour
//  of y among the current VPLs in Y" has two readings: y excluded (r_k to the k-th other VPL;
//  MATH.md 2; unbiased on a Poisson set) or y counted as its own first neighbour (r_k to the
//  (k-1)-th other; smcir.knnCountsSelf, the default, k raised to 2: -1/k on a Poisson set, and
//  about right on the evolved, more regular one; see "Selection" below). Lines 8 and 19 use n, not
//  the budget, so a set that is not full still integrates to 1.
//
//  Undersampled regions (3.2.5, eq. 9, lines 9-17): intensities are compared by luminance (Rec.
//  709). M_strong counts candidates whose intensity exceeds that of strongFraction (95 %) of the
//  current VPLs, i.e. is above the ceil(0.95 n)-th smallest VPL intensity. M_min = min(M_max,
//  M_strong). Slots are freed in this order, at most M_max per frame (CLAMPSIZE): empty slots,
//  invalid VPLs from the weakest up, and, while fewer than M_min, the weakest valid VPLs. Freed
//  slots get the strongest remaining candidates; a slot left without one becomes empty.
//
//  Selection (docs/smcir.md, "Selection bias"; core/vpl/smcir_selection.h measures it). Lines 9-12
//  rank the VPLs by their intensities and render with them: the survivors are the VPLs whose
//  estimates came out high, and the bias grows with the frames (the winner's curse; the paper
//  accepts a biased, consistent method, 3.3). Two parts:
//   - radiance: the paper ranks a VPL by the value it renders with. smcir.rankRadiance = candidate
//     (F1, ours, the default) ranks it by its line-7 candidate estimate and renders with an
//     independent lifetime estimate (independentRadiance); when the lights change both are
//     re-estimated, each with its own seed (line 18). The radiance part is then 0 at every frame.
//   - density: ranking by last frame's r_k keeps the VPLs whose r_k came out large, and k = 1
//     candidate densities make the set blue noise, on which kNN with y excluded over-estimates 1/p
//     (the furnace's area identity: +10% after 100 frames). knnCountsSelf (F2, the default) offsets
//     it, knnRank (F3) ranks with another k than the renderer's. Neither makes the density part
//     stop growing; docs/smcir.md has the table over 8 seeds.
//
//  Stable slots: a VPL keeps its slot for its life. VPLSet::changed lists the slots whose VPL was
//  replaced or removed by the last step (their shadow maps must be redrawn); it is sorted and has
//  at most M_max entries. Line 19 re-estimates every density each step, and line 18 may
//  re-estimate radiances; neither moves a VPL, so neither is "changed". After initialize() every
//  slot is listed.
//
//  Determinism: every random number comes from a PCG32 stream keyed by (seed, frame, stage,
//  item), every parallel loop writes per-item results that are combined in item order, and ties
//  are broken by index. The same seed and camera sequence give bit-identical sets whatever the
//  thread count. No std:: distributions (their output differs between standard libraries).
//
//  Threads: the stages run their loops with tbb::parallel_for. The object itself is not
//  thread-safe: call step() from one thread and read vpls() between steps (copy it to hand it to
//  another thread). A step reads its FrameSnapshot (camera, lights: copies) and the scene's static
//  parts only, never scene.lights, so the render thread may animate the lights meanwhile
//  (core/vpl/vpl_pipeline.h; a ThreadSanitizer test checks it).
//
//  Radiance paths share vertex 0: ReflectedRadianceEstimator evaluates the punctual lights at y
//  once per estimate, not once per path, and skips the final emission-only ray when the scene has
//  no emissive triangles (core/trace/path_tracer.h: both exact, bit for bit; the seeds, and so every
//  VPL's radiance, are unchanged). In the maze (8 point lights) this cut the radiance rays by
//  about 30 % (static frame 724k -> 522k rays).
//
//  Costs per frame (defaults, I = 2048): |X| = 2304 primary rays, up to 2048 mail-box rays, up to
//  2 * 2304 * 16 validation rays (only while VPLs are invalid), 32768 candidate rays, one kNN
//  query per raw point, I radiance estimates of 16 paths (2I when the lights changed), and two
//  kNN passes over I points. lastTimes() reports each stage and the Embree rays cast.
//
// References
// ----------
//  P. Hedman, T. Karras, J. Lehtinen: Sequential Monte Carlo Instant Radiosity, IEEE TVCG 23(5),
//    2017 (papers/000): Algorithm 1, sections 3.1-3.3.
//  A. Keller: Instant Radiosity, SIGGRAPH 1997.
//  B. Segovia, J.-C. Iehl, R. Mitanchey, B. Peroche: Bidirectional Instant Radiosity, EGSR 2006
//    (VPLs on surfaces seen from the camera's points).
//  MATH.md 1.4 (eq. 5, 6 and the 1/I factor), 2 (kNN density, eq. 8 reading).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/frame_snapshot.h"
#include "core/trace/path_tracer.h"
#include "core/trace/ray_scene.h"
#include "core/util/knn.h"
#include "core/vpl/vpl_pipeline.h"
#include "core/scene/scene.h"
#include "core/scene/surface.h"
#include "core/vpl/vpl.h"

namespace vplgi {

class ParamVisitor;
class ReflectedRadianceEstimator;

constexpr int kRankByRenderedRadiance = 0;  // smcir.rankRadiance = rendered (the paper)
constexpr int kRankByCandidateRadiance = 1; // smcir.rankRadiance = candidate (F1, ours)

struct SMCIRParams {
    int vplCount = 2048;            // I: the VPL budget (slots) [1, 2^20]
    int maxMoves = 16;              // M_max: most slots that change per frame [0, 2^20]
    int validationRays = 16;        // V: invalid VPLs each camera point tests per round (3.2.2) [0, 1024]
    int validationIterations = 2;   // rounds of validation rays per frame (3.2.2) [0, 16]
    int candidateFactor = 16;       // candidateFactor * I candidate rays, resampled to I (3.2.1) [1, 256]
    int resampleRetries = 8;        // redraws for duplicates in the resampling (3.2.1) [0, 64]
    int candidateDensityK = 1;      // k of the kNN density of the raw candidate points [1, 64] (3.2.4: 1)
    bool candidateDensityGrid = false; // approximate that density by point counts in a uniform grid of
                                       // about k points per cell (O(N), no kNN). Not in the paper.
    int radiositySamples = 16;      // path-tracer samples per VPL radiance (3.2.3) [1, 65536]
    int radiosityBounces = 3;       // most reflections of those paths, counting the one at the VPL [1, 1024]
    int candidateRadianceSamples = 0; // samples for the candidates' radiance (line 7) [0, 65536]; 0 = the
                                      // paper (radiositySamples). Fewer screens the candidates cheaply; a
                                      // candidate that becomes a VPL is then re-estimated with
                                      // radiositySamples and its own seed (line 18). Not in the paper.
    int knnRender = 0;              // k of the rendering densities (line 19); 0 = eq. (8) [0, 1024]
    float strongFraction = 0.95f;   // eq. (9): a candidate is strong above this fraction of the VPLs [0, 1]
    int cameraSamplesX = 64;        // RAYCASTFROMCAMERA grid columns (jittered per frame) [1, 4096]
    int cameraSamplesY = 36;        // RAYCASTFROMCAMERA grid rows [1, 4096]
    int warmupIterations = 100;     // frames run by initialize() before the first one is shown [0, 100000]
    std::uint32_t seed = 1;         // random stream seed: the same seed and cameras give the same VPLs
    bool texturedVPLs = false;      // false: the paper's untextured scene for the VPLs (mean material
                                    // albedos, no normal maps; section 5). true: textured (not in the paper)
    float clampScale = 2.0f;        // VPL clamping, G_max = 1/d^2, d = clampScale * D / sqrt(I), D the scene
                                    // diagonal [0, 1000]; 0 = none (computeClampGeometry). Not in the paper,
                                    // which clamps "to a value suitable for 2048 VPLs" chosen per scene (5.4).
                                    // 2: against the unclamped indirect reference on Cornell at I = 2048,
                                    // rmse 0.0103 / 0.0092 / 0.0083 / 0.0079 / 0.0079 for 0.25 / 0.5 / 1 /
                                    // 2 / 4; 2 is the mildest clamp on that plateau (README, "clamping")
    bool independentRadiance = true; // line 18 gives a new VPL a radiance estimate independent of the
                                     // candidate estimate that selected it (its own lifetime seed), instead
                                     // of keeping the value it was selected on. Selecting on a noisy value and
                                     // rendering with the same value keeps the VPLs whose estimate came out
                                     // high (test case "smcir: VPLs render with radiance estimates
                                     // independent of the ones they were selected on",
                                     // tests/cpu/test_smcir_sampler.cpp, prints both). The paper's text
                                     // allows both readings ("the intensities are re-estimated for the
                                     // remaining VPLs", a VPL-specific seed for the VPL's lifetime)
    // The selection (lines 9-12) without the winner's curse (docs/smcir.md, "Selection bias"): lines
    // 9-12 rank the VPLs by estimates, and rendering with the very estimates they survived on keeps
    // the VPLs whose estimates came out high, a bias that grows with the frames.
    int rankRadiance = kRankByCandidateRadiance; // the radiance lines 9-12 rank a VPL by: kRankByRenderedRadiance
                                     // (the paper: the value it renders with) or kRankByCandidateRadiance (F1,
                                     // ours: its line-7 candidate estimate, independent of the rendered one
                                     // when independentRadiance; re-estimated with the candidate's seed when
                                     // the lights change). Key "smcir.rankRadiance" ("rendered", "candidate")
    bool knnCountsSelf = true;       // F2, a reading the paper permits (3.2.4: "the k-th nearest neighbour
                                     // of y among the current VPLs in Y", y in Y): y is its own first
                                     // neighbour, p = k / (n pi r^2) with r the distance to the (k-1)-th other
                                     // VPL (k raised to 2 where it is 1). false: MATH.md 2's reading, self
                                     // excluded, unbiased on a Poisson set (this one is -1/k there)
    int knnRank = 0;                 // F3 (ours): k of the densities lines 9-12 rank VPLs by; 0 = the rendering k
    bool reestimateEveryFrame = false; // every frame is a new radiance-cache key: the moving-light cost
                                       // (a measurement aid; key "smcir.invalidateEveryFrame")

    // Keys "smcir.<field>".
    void visitParams(ParamVisitor& visitor);
};

// Eq. (8) as papers/README.md reads it: k = max(1, floor(sqrt(I / 32))). 4 at 512, 8 at 2048.
int computeRenderingK(int vplCount);

// What a path-traced reference must simulate to be compared with SMCIR (smcir, smcir-rt): section 5
// "The path traced reference images use the same approximation" (untextured bounces), 5.4 the same
// clamp, and the same bounce cap (the reflection at the primary hit plus the radiosity paths'
// bounces, which count the reflection at the VPL). Keys in `explicitKeys` (reference.*) are left.
void configureSMCIRReference(const SMCIRParams& params, float sceneDiagonal, PathTracerParams& reference,
                             const std::set<std::string>& explicitKeys);

// G_max [1/m^2] of VPL clamping for a scene of diagonal D [m] (0 = no clamping): d = clampScale D /
// sqrt(I), G_max = 1/d^2. d follows the expected spacing of I VPLs on the scene's surfaces, so the
// clamp relaxes as I grows (3.3: "increasing the number of VPLs (while decreasing their clamping)
// tends to the correct solution"). The clamped reference uses the same value.
float computeClampGeometry(const SMCIRParams& params, float sceneDiagonal);

// What one step() did. Times are wall-clock [ms] (std::chrono::steady_clock) of the stage.
struct SMCIRStageTimes {
    double cameraRays = 0;          // line 3: primary rays and surface points of X
    double indirectVisibility = 0;  // line 4: mail-box checks and validation rays
    double candidateSampling = 0;   // line 5: candidate rays from X
    double candidateResampling = 0; // line 6: kNN density of the raw points and the weighted draws
    double radiosity = 0;           // lines 7 and 18: radiance estimates
    double knn = 0;                 // lines 8 and 19: tree builds and density queries
    double selection = 0;           // lines 9-17
    double total = 0;               // the whole step
    std::uint64_t rays = 0;         // Embree rays cast (intersect + occluded), path tracer included
    int moved = 0;                  // slots listed in VPLSet::changed
    int mailboxMisses = 0;          // VPLs whose associated point the camera no longer sees (3.2.2)
    int invalidated = 0;            // VPLs still invalid after the validation rounds (before line 10)
    int cameraPoints = 0;           // |X|
    int rawCandidates = 0;          // candidate rays that hit a valid surface
    int candidates = 0;             // |Y^| after resampling
    int strongCandidates = 0;       // M_strong of eq. (9)
    int radianceEstimates = 0;      // radiance estimates made (candidates + stale VPLs)
};

class SMCIRSampler final : public VPLSampler {
public:
    // Keeps references to scene and rays (rays built from scene); both must outlive the sampler.
    // Throws Error for parameters out of range.
    SMCIRSampler(const Scene& scene, const RayScene& rays, const SMCIRParams& params);
    ~SMCIRSampler();
    SMCIRSampler(const SMCIRSampler&) = delete;
    SMCIRSampler& operator=(const SMCIRSampler&) = delete;

    // Alg. 1 line 1 and the warm-up frames, for the snapshot's camera, aspect (the view's width /
    // height, for the camera rays and the frustum test) and lights. progress(done, total) is called
    // after each warm-up frame. Afterwards vpls().changed lists every slot, and lastTimes() describes
    // the last warm-up frame (the initialization itself when there is none) with `moved` = all slots.
    // May be called again to start over (same seed and snapshot: the same set).
    void initialize(const FrameSnapshot& snapshot, const Progress& progress = {}) override;
    // One frame, Alg. 1 lines 3-19: at most maxMoves slots change. Requires initialize(). Reads only
    // the snapshot and the scene's static parts. A VPL's cached radiance (3.2.3) is re-estimated,
    // with its own seed, exactly when the snapshot's lights differ from those it was computed for.
    void step(const FrameSnapshot& snapshot) override;
    // Conveniences for single-threaded callers: a snapshot of the scene's lights, taken now.
    void initialize(const Camera& camera, float aspect = 16.0f / 9.0f,
                    const std::function<void(int done, int total)>& progress = {});
    void step(const Camera& camera, float aspect = 16.0f / 9.0f);

    const VPLSet& vpls() const override { return mSet; }
    // lastTimes() in SMCIR Table 2's columns, for `vplgi bench`.
    StatList stats() const override;
    const SMCIRStageTimes& lastTimes() const { return mTimes; }
    // Diagnostics (core/vpl/smcir_selection.h): each slot's radiance estimated anew with `samples`
    // paths and seeds derived from `seed`, by the last frame's estimator (its lights and materials);
    // black for empty slots. Requires initialize().
    std::vector<glm::vec3> estimateRadianceAgain(int samples, std::uint32_t seed) const;
    const SMCIRParams& params() const { return mParams; }
    // Frames run so far (initialization is frame 0; each step adds one).
    std::uint64_t frame() const { return mFrame; }

private:
    struct CameraPoint;
    struct SlotState;
    struct Candidate;

    void beginFrame(const FrameSnapshot& snapshot);
    const UntexturedMaterials* vplMaterials() const; // the materials VPLs see (null: textured)
    void castCameraRays(const Camera& camera, float aspect, std::vector<CameraPoint>& points);
    std::vector<CameraPoint> timedCameraPoints(const Camera& camera, float aspect); // line 3, timed
    std::vector<Candidate> candidatesWithRadiance(const std::vector<CameraPoint>& points,
                                                  const std::vector<Light>& lights); // lines 5-7, timed
    std::vector<char> resolveIndirectVisibility(const Camera& camera, float aspect,
                                                const std::vector<CameraPoint>& points);
    std::vector<Candidate> sampleCandidates(const std::vector<CameraPoint>& points, double& samplingMs,
                                            double& resamplingMs);
    void estimateCandidateRadiance(std::vector<Candidate>& candidates);
    void estimateCandidateDensities(std::vector<Candidate>& candidates);
    void estimateStaleRadiance();
    void estimateRenderingDensities();
    void guardPublishedVPLs();
    struct KNNChoice {
        std::size_t k = 0;         // numerator of eq. (7); 0: no density (fewer than 2 VPLs)
        std::size_t neighbour = 0; // r is the distance to this neighbour in the index (y itself is the 1st)
    };
    KNNChoice knnChoice(int wanted, std::size_t n) const; // smcir.knnCountsSelf's two readings
    bool ranksByCandidateRadiance() const;
    void assignSlot(std::uint32_t slot, const Candidate& candidate, const std::vector<CameraPoint>& points);
    void clearSlot(std::uint32_t slot);

    const Scene& mScene;
    const RayScene& mRays;
    SMCIRParams mParams;
    int mRenderK = 1;
    // Line 19 is incremental and exact: per slot, the position and r_k^2 of the last estimate. A
    // VPL's k-th neighbour distance can only change when a point was added or removed within it.
    std::vector<glm::vec3> mDensityPositions;
    std::vector<float> mDensityR2;
    NeighbourSearch mCandidateSearch; // line 6's kNN; its buffers kept between frames
    std::vector<char> mDensityValid;
    std::size_t mDensityK = ~std::size_t{0}; // neighbour of that estimate (a different one recomputes all)
    std::vector<float> mRankDensity;              // per slot, the density lines 9-12 rank by (smcir.knnRank)
    float mOffset = 1e-4f;                        // ray offset along geometric normals [m]
    std::unique_ptr<ReflectedRadianceEstimator> mEstimator; // rebuilt each frame from the snapshot's lights
    UntexturedMaterials mUntextured;              // section 5: mean albedos (unless texturedVPLs)
    VPLSet mSet;
    std::vector<SlotState> mSlots;                // per slot, beside mSet.slots
    std::uint64_t mFrame = 0;
    std::uint64_t mRadianceKey = 0;               // this frame's radiance-cache key (hash of the lights)
    int candidateSamples() const;                 // samples of line 7
    bool mInitialized = false;
    SMCIRStageTimes mTimes;
    std::uint64_t mRayCount = 0;                  // rays of the frame being built
    int mEstimates = 0;
};

} // namespace vplgi
