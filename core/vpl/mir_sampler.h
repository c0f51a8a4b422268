// The CPU half of the `mir` comparison method: Metropolis Instant Radiosity as the SMCIR paper ran
// it, light paths resampled by the power they bring to the image.
//
// Intro
// -----
// MIR (Segovia, Iehl, Peroche 2007) distributes VPLs "according to the radiance they bring the
// camera" (SMCIR, papers/000, lines 886-897); SMCIR calls it "a gold standard for single frame image
// quality" with no temporal coherence (lines 725-733). The original draws the light paths with
// Metropolis light transport; the SMCIR paper instead "generate[s] these paths by resampling paths
// from our path tracer" at a resampling rate of 256:1. We do the same with the light paths of the
// `ir` baseline (core/vpl/ir_sampler.h): 256 I candidate VPLs deposited by light paths, of which I
// are kept with probability proportional to their contribution to the image. A new set every
// frame; every slot changes. The GPU half is `ir`'s and `smcir`'s (gl/techniques/vpl_technique.h):
// only the VPL positions and intensities differ, as in the paper's comparisons.
//
// Overview (one call of step() is one frame)
// --------
//  1. candidates   M = mir.resamplingRate * I VPLs from IRSampler (bounces, untextured scene,
//                  fillBudget: every candidate slot taken), a new sequence every frame. Candidate j
//                  is a diffuse emitter of intensity e_j [W/sr], with L_ind(x) = sum_j f G V e_j
//                  (e_j = IR's published intensity / M: its 1/n convention undone).
//  2. camera       K = cameraSamplesX * cameraSamplesY primary rays through a jittered grid, new
//     points       every frame: the surface points x_k the camera sees and their (textured) BRDFs.
//  3. importance   C_j = (1/K) sum_k lum f(x_k, w_o, w) min(G(x_k, y_j), G_max) without visibility:
//                  what y_j brings to the image, estimated at the K points (G_max the renderer's
//                  clamp). Weight w_j = lum(e_j) (C_j + delta C_bar), C_bar the flux-weighted mean of C.
//  4. resampling   I of the M candidates by systematic resampling with probabilities w_j / W,
//                  W = sum_j w_j; VPL i taken from candidate j gets intensity e_j W / w_j.
//
// Details
// -------
//  Why the estimate stays unbiased (MATH.md style, docs/mir.md). With N_j the times candidate j is
//  taken, E[N_j] = I w_j / W for systematic resampling. The renderer shades with
//  (1/I) sum_i f G V I_i = (1/I) sum_j N_j f G V e_j W / w_j, whose expectation over the resampling is
//  sum_j f G V e_j: the candidates' estimate, itself IR's unbiased estimate with M VPLs. This holds
//  for any weights that are positive wherever e_j is, however roughly C_j estimates the truth; the
//  weights only decide the variance. Hence the defensive term delta C_bar (ours, not in the paper):
//  a candidate that none of the K points sees (unoccluded importance 0) can still be taken, so no
//  light is lost where the K points did not look. It spends delta / (1 + delta) of the weight.
//
//  Why light paths and not camera paths (the issue "MIR and TCAS" asked for camera samples with a
//  BRDF-sampled direction each, target f(x) G L(y) at that one pixel). A VPL lights every pixel, so
//  its intensity must divide by the density of its position over the whole image, the marginal
//  over all camera samples, which a camera path's own weight does not give: dividing by the one
//  pixel's f G L is unbiased only with a uniform-pixel conditional and makes intensities scale with
//  1 / G(x_i, y) of a pixel unrelated to the one being shaded (in the furnace, where IR's
//  intensities are all equal, they would span the whole range of G). Resampling light paths needs
//  no marginal: their flux is known exactly, and the image contribution enters only through the
//  weights. The result is what MIR aims at: VPLs with density proportional to the power they bring
//  to the image, each carrying the same share W / I of it (up to the importance's estimation error).
//
//  Radiance. A candidate's intensity is its light path's flux (IR's bookkeeping), not an estimate
//  of the surface's radiance: nothing is estimated per VPL as SMCIR does (its eq. 6 radiance).
//
//  Visibility is left out of C_j (the paper's MIR has it, through the Metropolis paths' connection
//  to the camera): K visibility rays per candidate would be 256 K rays per VPL. Left out, a wall's
//  far side counts as seen; the resampling stays unbiased (above), only less focused.
//
//  Determinism: IR's per-path streams, camera jitter and the resampling offset keyed by (seed,
//  frame); importance per candidate in a fixed order. The same seed gives a bit-identical set
//  whatever the thread count.
//
// References
// ----------
//  B. Segovia, J.-C. Iehl, B. Peroche: Metropolis Instant Radiosity, Eurographics 2007.
//  P. Hedman, T. Karras, J. Lehtinen: Sequential Monte Carlo Instant Radiosity (papers/000), section
//    5.1 (MIR by resampling, 256:1) and Table 1.
//  A. Doucet, N. de Freitas, N. Gordon: Sequential Monte Carlo Methods in Practice, 2001
//    (systematic resampling, the same as SMCIR's Alg. 1 uses).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/frame_snapshot.h"
#include "core/scene/scene.h"
#include "core/trace/ray_scene.h"
#include "core/vpl/ir_sampler.h"
#include "core/vpl/vpl.h"
#include "core/vpl/vpl_pipeline.h"

namespace vplgi {

class ParamVisitor;

struct MIRParams {
    int vplCount = 2048;        // I: the VPL budget (slots) [1, 65536]; SMCIR's default budget
    int resamplingRate = 256;   // candidates per VPL (SMCIR 896-897: 256:1) [1, 4096]; M = rate * I <= 2^20
    int bounces = 3;            // most surface hits per light path that deposit a candidate (as ir) [1, 64]
    int cameraSamplesX = 12;    // camera points K: grid columns, jittered per frame (ours) [1, 256]
    int cameraSamplesY = 8;     // camera points: grid rows (ours) [1, 256]
    float defensive = 0.1f;     // delta: the weight every candidate keeps, in units of the mean (ours) [0, 10]
    std::uint32_t seed = 1;     // random stream seed: the same seed, camera and lights give the same VPLs
    bool texturedVPLs = false;  // false: untextured scene, mean material albedos (SMCIR section 5)

    // Keys "mir.<field>".
    void visitParams(ParamVisitor& visitor);
};

// What one initialize() or step() did.
struct MIRStats {
    int candidates = 0;     // M: candidate VPLs the light paths deposited
    int cameraPoints = 0;   // K: camera rays that hit a surface
    int distinct = 0;       // candidates taken at least once (<= I)
    int vpls = 0;           // valid slots (I, or 0 when there is no light)
    double unseenFlux = 0.0; // share of the candidates' flux with importance 0 (kept by the defensive term only)
    double candidateMs = 0.0, importanceMs = 0.0, resampleMs = 0.0, ms = 0.0; // wall-clock [ms]
    std::uint64_t rays = 0; // Embree rays: the light paths' and the camera points'
};

class MIRSampler final : public VPLSampler {
public:
    // Keeps references to scene and rays; both must outlive the sampler. `clampGeometry` is the
    // renderer's G_max (0: no clamp), used in the importance. Throws Error for parameters out of range.
    MIRSampler(const Scene& scene, const RayScene& rays, const MIRParams& params, float clampGeometry);
    ~MIRSampler() override;
    MIRSampler(const MIRSampler&) = delete;
    MIRSampler& operator=(const MIRSampler&) = delete;

    // Frame 0 for the snapshot's camera and lights; afterwards vpls().changed lists every slot.
    void initialize(const FrameSnapshot& snapshot, const Progress& progress = {}) override;
    // The next frame: new candidates, camera points and resampling. Requires initialize().
    void step(const FrameSnapshot& snapshot) override;

    const VPLSet& vpls() const override { return mSet; }
    // "mir: candidates", "mir: camera points", "mir: distinct", "mir: unseen flux", "mir: rays",
    // "mir: candidates ms", "mir: importance ms", "mir: resample ms", "sampler: total ms".
    StatList stats() const override;
    const MIRStats& lastStats() const { return mStats; }
    const MIRParams& params() const { return mParams; }
    // The importance C_j of the last frame's candidates (for tests and debugging), candidate order.
    const std::vector<float>& importance() const { return mImportance; }
    const VPLSet& candidates() const { return mCandidates->vpls(); }

private:
    struct CameraPoint;
    void buildFrame(const FrameSnapshot& snapshot);
    std::vector<CameraPoint> cameraPoints(const FrameSnapshot& snapshot);

    const Scene& mScene;
    const RayScene& mRays;
    MIRParams mParams;
    float mClampGeometry = 0.0f;
    std::unique_ptr<IRSampler> mCandidates;
    std::vector<float> mImportance;
    VPLSet mSet;
    MIRStats mStats;
    std::uint64_t mFrame = 0;
    float mOffset = 1e-4f; // ray offset along geometric normals [m]
    bool mInitialized = false;
};

} // namespace vplgi
