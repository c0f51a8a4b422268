// The CPU half of the `ir` baseline: Keller's instant radiosity, VPLs deposited along light paths.
//
// Intro
// -----
// Instant radiosity (Keller 1997) traces N random walks from the light sources and leaves a virtual
// point light at every surface the walk visits; the renderer then shades with all of them. SMCIR
// (papers/000) compares itself with this method: the same budget of I VPL slots, the same shadow
// maps, interleaving, filter and clamping, "no special consideration for temporal coherence" (a new
// random sequence every frame), so that only the VPL positions and intensities differ between the
// methods. This class produces that set; the GPU technique shades it like SMCIR's (core/vpl/vpl.h).
//
// Overview (one call of step() is one frame)
// --------
//  1. emitters      the snapshot's lights as one list, each with its flux: point (isotropic), spot
//                   (glTF cone falloff), directional (a disk covering the scene's bounding sphere),
//                   and every emissive triangle of the scene (Lambertian); a light is chosen per path
//                   with probability proportional to its flux (luminance).
//  2. light paths   in batches, in parallel, path k with its own random stream (seed, frame, k):
//                   leave the light, deposit a VPL at every surface hit up to `bounces` hits (not at
//                   the light itself: Keller's j = 0 is direct light, which the renderer draws), go on
//                   with a cosine-sampled direction and Russian roulette on the diffuse albedo.
//  3. slots         deposits fill the slots in path order until all I are taken (the path that takes
//                   the last slot loses its later deposits) or `pathCap * I` paths were emitted;
//                   with ir.fillBudget = false (the paper's IR) until the paths would have filled
//                   them had none escaped.
//  4. intensities   with N the paths emitted and n the VPLs deposited, each VPL gets its intensity.
//
// Details
// -------
//  Flux bookkeeping (MATH.md 1.3, the physically based form; pbrt-v2's IGI). A path starts with
//  alpha_0 = Phi_l / (N P_l), Phi_l the chosen emitter's flux [W] and P_l its selection probability
//  (directions and points are importance sampled exactly, so every path of an emitter starts with
//  the same flux). At hit j it deposits {y_j, n_j, alpha_j}, alpha_j the flux *arriving* at y_j; a
//  deposit is an estimate of the flux reaching depth j, and nothing is subtracted from the path. To
//  continue, a direction is drawn with density cos / pi about the shading normal, so the throughput
//  is t = rho_d (the diffuse albedo); the path survives with q = min(1, lum(t)) and then carries
//  alpha_{j+1} = alpha_j t / q. On grey surfaces alpha stays Phi / N for the whole path. A direction
//  below the geometric horizon ends the path (the path tracer's rule). The back of a single-sided
//  surface is never hit: rays pass through it (the back-face rule, scene.h Material::doubleSided).
//
//  The VPL convention (core/vpl/vpl.h, MATH.md 1.4). The renderer computes
//      L_ind(x) = (1/n) sum_i f(x) G(x, y_i) V(x, y_i) I(y_i),
//  and MATH.md 1.1 shades a VPL of incident flux alpha_i with alpha_i f(x) f_r(y_i) G V, where the
//  VPL's own BRDF is f_r = rho_d(y_i) / pi: a diffuse VPL re-emits the fraction rho_d of what
//  arrived, as a cosine emitter. Hence
//      I(y_i) = n alpha_i rho_d(y_i) / pi     [W/sr]
//  (the VPL is a cosine emitter of total flux pi I / n = rho_d alpha_i). The factor n cancels the
//  renderer's 1/n: the estimate is Keller's sum, whatever n is, so deposits that reflect nothing
//  (black surfaces) are simply not stored, and a set short of its budget is still right.
//  Keller's VPLs have no density p(y) to speak of (the estimator weights each VPL by the flux of its
//  path, not by L / p). We publish density = 1 [1/m^2] and radiance = I(y) (numerically), so that
//  VPL::intensity() = radiance / 1 is I(y) bit for bit and every renderer that reads intensity()
//  (CPU gather, GPU upload) needs nothing IR-specific. Do not read `radiance` of an IR VPL as a
//  surface radiance.
//
//  Emitters. Point: flux 4 pi I_0, directions uniform on the sphere. Spot (glsl/shared/lights.h:
//  I_0 t^2, t = clamp((cos - cos_outer) / (cos_inner - cos_outer))): flux 2 pi I_0 ((c_i - c_o)/3 +
//  1 - c_i), cos sampled exactly from that profile (a cubic ramp plus a uniform cap). Directional
//  (irradiance E on a surface facing it): rays from a disk of radius r perpendicular to the light,
//  r the radius of the scene's bounding sphere, flux E pi r^2; rays that miss the scene are part of
//  the escaped fraction below. Emissive triangle (Lambertian radiance L_e, area A): flux pi L_e A
//  (twice that for double-sided materials, a side chosen with probability 1/2), a uniform point and a
//  cosine direction; textured emission is read at the point and weighted against the untextured
//  factor that chose the triangle. Lights come from the FrameSnapshot (they may move); emissive
//  triangles are static scene geometry, collected once.
//
//  The budget (issue 9 part 4: "report how much of it photons that leave the scene leave unused").
//  The I slots are filled by deposits; every path emitted counts in N, including those that never
//  deposit anything. Those "escaped" paths (the first ray left the scene, or ended below a
//  surface's geometric horizon or on a black one) carry flux that lights nothing the camera could see: stat "ir: escaped
//  fraction" = escaped paths / N is the part of the emitted power, and of the work, that the
//  budget spent on nothing. A closed scene (the furnace) reports 0. N is a stopping time (paths are
//  emitted until the slots are full), which biases the estimate by O(1/N), and the last path's
//  lost deposits by at most one path in N: both far below the Monte Carlo noise of I VPLs.
//
//  Untextured scene (SMCIR section 5, for all methods): by default surfaces are seen through
//  UntexturedMaterials (mean material albedos, no normal maps), as the SMCIR sampler's VPLs are;
//  ir.texturedVPLs = true reads the textured surface instead (not in the paper).
//
//  Frames and stable slots. The paper's IR draws a new sequence every frame: the stream of path k
//  is keyed by (seed, frame, k). ir.fixedSequence keys it by (seed, k) only, the same sequence every
//  frame (Wald et al.'s fixed random walks, SMCIR section 2.3; not in the paper's Table 1): with
//  static lights the set does not move at all. VPLSet::changed lists every slot whose VPL was
//  created, removed, or moved (position or normal differ from the previous frame); an intensity
//  change alone is not a change (the shadow map stays valid). After initialize() every slot is
//  listed.
//
//  Determinism: per-path streams (PCG32 keyed by (seed, frame, path)), batches whose size depends
//  only on the slots still free, deposits taken in path order: the same seed gives a bit-identical
//  set whatever the thread count.
//
// References
// ----------
//  A. Keller: Instant Radiosity, SIGGRAPH 1997.
//  P. Hedman, T. Karras, J. Lehtinen: Sequential Monte Carlo Instant Radiosity, IEEE TVCG 23(5),
//    2017 (papers/000): section 2.3 (fixed sequences), section 5 (IR as the baseline, untextured).
//  I. Wald, T. Kollig, C. Benthin, A. Keller, P. Slusallek: Interactive Global Illumination using
//    Fast Ray Tracing, EGRW 2002 (fixed random walks across frames).
//  M. Pharr, G. Humphreys: pbrt-v2, src/integrators/igi.cpp (the flux bookkeeping).
//  MATH.md 1.1 (VPL contribution), 1.3 (flux bookkeeping), 1.4 (the 1/n convention), 3 (furnace).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/frame_snapshot.h"
#include "core/scene/scene.h"
#include "core/scene/surface.h"
#include "core/trace/ray_scene.h"
#include "core/vpl/vpl.h"
#include "core/vpl/vpl_pipeline.h"

namespace vplgi {

class ParamVisitor;

struct IRParams {
    int vplCount = 2048;         // I: the VPL budget (slots) [1, 2^20]; SMCIR's default budget
    int bounces = 3;             // most surface hits per path that deposit a VPL (paper's experiments: 3) [1, 64]
    int pathCap = 64;            // at most pathCap * I paths per frame, full or not (open scenes) [1, 65536]
    bool fillBudget = true;      // true (ours): paths are emitted until all I slots are taken, a stronger
                                 // baseline in open scenes. false: the paper's IR, which "may not use the
                                 // full VPL budget if photons exit" (SMCIR 730-733): N is the path count
                                 // that would fill the budget had no path escaped (each escaped path charged
                                 // the mean deposits of the paths that stayed), so about (1 - escaped
                                 // fraction) I slots are used
    std::uint32_t seed = 1;      // random stream seed: the same seed (and lights) gives the same VPLs
    bool fixedSequence = false;  // false: a new random sequence every frame (the paper's IR); true: the
                                 // same sequence every frame (Wald et al., SMCIR 2.3; not in Table 1)
    bool texturedVPLs = false;   // false: untextured scene, mean material albedos (SMCIR section 5)

    // Keys "ir.<field>".
    void visitParams(ParamVisitor& visitor);
};

// What one initialize() or step() did.
struct IRStats {
    std::uint64_t paths = 0;        // N: light paths emitted (the 1/N of the flux)
    std::uint64_t pathsEscaped = 0; // paths that deposited nothing (left the scene, back face, black)
    std::uint64_t rays = 0;         // Embree rays cast (traced paths, including discarded batch tails)
    int vpls = 0;                   // n: VPLs deposited (valid slots)
    int moved = 0;                  // slots listed in VPLSet::changed
    double ms = 0.0;                // wall-clock time of the call [ms]
    double escapedFraction() const { return paths > 0 ? static_cast<double>(pathsEscaped) / paths : 0.0; }
};

class IRSampler final : public VPLSampler {
public:
    // Keeps references to scene and rays (rays built from scene); both must outlive the sampler.
    // Throws Error for parameters out of range. The scene's emissive triangles are collected here.
    IRSampler(const Scene& scene, const RayScene& rays, const IRParams& params);
    ~IRSampler() override;
    IRSampler(const IRSampler&) = delete;
    IRSampler& operator=(const IRSampler&) = delete;

    // Frame 0 for the snapshot's lights (the camera is not used: IR's VPLs do not depend on it).
    // Afterwards vpls().changed lists every slot. May be called again to start over.
    void initialize(const FrameSnapshot& snapshot, const Progress& progress = {}) override;
    // The next frame: a new sequence (or the same one with fixedSequence) for the snapshot's lights.
    // Requires initialize().
    void step(const FrameSnapshot& snapshot) override;

    const VPLSet& vpls() const override { return mSet; }
    // "ir: paths", "ir: paths escaped", "ir: escaped fraction", "ir: VPLs", "ir: rays", and
    // "sampler: total ms" (the name every VPL sampler uses).
    StatList stats() const override;
    const IRStats& lastStats() const { return mStats; }
    const IRParams& params() const { return mParams; }
    std::uint64_t frame() const { return mFrame; }

private:
    struct Emitter;
    struct Deposit;

    void buildFrame(const FrameSnapshot& snapshot); // steps 1-4 into mSet (changed not set)
    std::vector<Emitter> collectEmitters(const std::vector<Light>& lights) const;
    // Traces path `index`; writes at most mParams.bounces deposits, returns their count.
    int tracePath(const std::vector<Emitter>& emitters, const std::vector<double>& cdf, double totalPower,
                  std::uint64_t index, Deposit* deposits, std::uint64_t& rays) const;
    const UntexturedMaterials* vplMaterials() const { return mParams.texturedVPLs ? nullptr : &mUntextured; }

    const Scene& mScene;
    const RayScene& mRays;
    IRParams mParams;
    UntexturedMaterials mUntextured;
    std::vector<Emitter> mTriangles; // the scene's emissive triangles (static)
    glm::vec3 mBoundsCenter{0.0f};
    float mBoundsRadius = 0.0f;
    float mOffset = 1e-4f;           // ray offset along geometric normals [m]
    VPLSet mSet;
    IRStats mStats;
    std::uint64_t mFrame = 0;
    bool mInitialized = false;
};

} // namespace vplgi
