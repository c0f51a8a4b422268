// Techniques `vsgl` and `vpl-brsm`: one-bounce diffuse and glossy indirect light from reflective
// shadow maps, with bidirectional-RSM importance sampling (Tokuyoshi, Virtual Spherical Gaussian
// Lights for Real-Time Glossy Indirect Illumination, Pacific Graphics 2015; papers/002). The two
// share every pass and draw the same N samples; only the light representation differs, as in the
// paper's comparisons: `vsgl` turns each sample into a virtual spherical Gaussian light read from
// the RSM mips, `vpl-brsm` into a virtual point light (eq. 1) at the sampled texel.
//
// Technique `tcas` (the SMCIR paper's TCAS baseline, Barak et al. 2013, its [26]; docs/tcas.md) is
// `vpl-brsm` with the N independent draws replaced by N Metropolis-Hastings chains over the same
// BRSM importance map, carried from frame to frame (gl/passes/metropolis_chains.h): 16 iterations
// per frame (SMCIR section 5.1; the original's 5 with tcas.iterations=5), one bounce, visibility
// ignored by the importance, imperfect shadow maps (or none) for the VPLs' shadows.
//
// Intro
// -----
// VPLs from an RSM show spikes near surfaces and on glossy receivers (the 1/d^2 and the BRDF peak of
// eq. 1) and flicker where the geometry is discontinuous. A VSGL replaces the point by a spherical
// light of radius r_i, whose radiance integral (eq. 2) is approximated by a triple product of SGs
// (eq. 3): the receiver's GGX lobe as an anisotropic SG, the light's diffuse and specular lobes as
// SGs and the cone it subtends as an SG. The lights come from filtered importance sampling: the
// sampled texel's values are read from the mip level that matches the sample density (section 3.2),
// so a light's radius, normal and lobe are averages over its footprint. Section 3.3 drops the SG
// approximation where the light is small against the BRDF's sharpness, so the estimator converges
// as N grows.
//
// Overview (per frame; the timer scopes are the rows of the paper's Table 1)
// --------
//  RSMs                 RSMPass: every spot, point (cube faces) and directional light, with mips
//  PDF of BRSMs         1. the G-buffer on a grid in the RSM layout + its mips (vsgl_view_rsm.comp,
//                          the shared mip kernel); level L's texels become view lights
//                          (vsgl_generate.comp, grid mode)
//                       2. importance of every RSM texel = its unoccluded VSGL contribution to the
//                          view lights (vsgl_importance.comp; MATH.md 10.1), into an R32F map with
//                          the layers side by side
//                       3. ImportanceSampler: tables and N draws (MATH.md 9.7); tcas: the tables
//                          (for the total) and N Metropolis-Hastings chains stepped against the map
//                          (MetropolisChains, scope "TCAS chains"), started once from N draws
//  VPL/VSGL generation  vsgl_generate.comp: VSGLight per draw (mip level, radius, lobe) or VPL
//  shadow maps          imperfect shadow maps of the N lights (gl/passes/imperfect_shadow_maps.h:
//                       8192 points splatted into a 64^2 paraboloid map per light, pull-push), or none
//  radiance estimation  vsgl_shading.frag: every pixel sums the N lights
//
// Details
// -------
//  Flux: a draw of texel j with probability P_j carries Phi_h / (N P_j), Phi_h the mip value at the
//  sampled level (a per-texel mean; MATH.md 5.2's reading), so the N lights estimate the RSM's total.
//  The view lights: a uniform grid of the G-buffer (vsgl.viewGrid^2 texels, level vsgl.viewLevel:
//  (viewGrid / 2^viewLevel)^2 lights). The paper does not say how many camera samples its BRSM uses.
//  Reference: the one-bounce path tracer (`vplgi compare --reference-mode onebounce`): light ->
//  one reflection -> the primary hit, from the lights the RSMs see (spot, point, directional).
//  Seed: the draws use the same uniforms every frame unless vsgl.animateSeed (the samples then move
//  only as the PDF moves: the temporal coherence the paper's videos show).
//
// References
// ----------
//  papers/002 sections 3.1-3.3 and 4; MATH.md 4, 5, 10; T. Ritschel, E. Eisemann, I. Ha, J. D. K. Kim,
//  H.-P. Seidel: Making Imperfect Shadow Maps View-Adaptive: High-Quality Global Illumination in
//  Large Dynamic Scenes, Computer Graphics Forum 30(8), 2011 (BRSMs and AISMs; the VSGL paper's
//  [Ritschel et al. 2011]; not consulted, MATH.md 10.1; an earlier version of this comment named
//  their 2008 coherent surface shadow maps paper instead); Dachsbacher, Stamminger: RSMs.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "../api/render_target.h"
#include "../passes/compute_pass.h"
#include "../passes/fullscreen_pass.h"
#include "../passes/imperfect_shadow_maps.h"
#include "../passes/importance_sampler.h"
#include "../passes/metropolis_chains.h"
#include "../passes/rsm_pass.h"
#include "technique.h"

namespace vplgi {

struct VSGLParams {
    enum Visibility { ISM, NoVisibility };
    int count = 1024;           // N lights (section 4: 1024) [1, 65536]
    float smoothness = 4.0f;    // k of the mip level (section 3.2; section 4: 4)
    float biasAlpha = 0.001f;   // alpha of section 3.3 (Fig. 6: 0.001); 0 = never cancel (vsgl only)
    // Each light's mip level and flux (vsgl only; passes/vsgl_generate.comp): Texel, the paper's
    // reading; Cell (ours, not in the paper): the coarsest cell with at most k expected draws.
    enum Footprint { Texel, Cell };
    int footprint = Cell;
    // Cell footprints: the coarsest leaf level, 2 = at most 4 x 4 RSM texels (not in the paper; 12:
    // no cap). Without a cap, the leaves of unimportant regions grew to 128^2 texels of a 256^2 RSM
    // and carried a sunlit roof's exact flux into the room below it (sealed room +28%); measured
    // over 8 seeds in docs/vsgl.md, "Leaves capped".
    int maxLeaf = 2;
    // Cell footprints: leaves stop before a geometric edge inside them (ours; passes/vsgl_generate.comp,
    // leafHasEdge; docs/vsgl.md, "Leaves stop at edges").
    bool leafEdges = true;
    // Cell footprints: position, normal, spread and lobes bilinear at the leaf's level (Bilinear),
    // the leaf cell's own as its flux always is (LeafCell), or bilinear over the neighbouring cells on
    // the leaf's surface only (Surface) (ours; passes/vsgl_generate.comp; docs/vsgl.md).
    enum LeafReads { Bilinear, LeafCell, Surface };
    int leafReads = Surface;
    float clampGeometry = 0.0f; // vpl-brsm: cap on cos cos / d^2 [1/m^2]; 0 = none (the paper's VPL figures)
    // The PDF of BRSMs (passes/vsgl_importance.comp): SG, the VSGL paper's (section 3: "in the same
    // fashion as VSGLs"); Point, the original BRSM's point-to-point formula (MATH.md 10.1), Fig. 4a.
    enum PDF { SG, Point };
    int pdf = SG;
    int viewGrid = 64;          // the G-buffer grid of the PDF pass [texels], a power of two
    int viewLevel = 2;          // its mip level whose texels are the view lights ((64/4)^2 = 256)
    std::uint32_t seed = 1;     // the draws' uniforms
    bool animateSeed = false;   // new uniforms every frame
    int visibility = ISM;
    ISMParams ism;              // keys <technique>.ism* (section 4: 8192 points, 64^2 per map)
    RSMParams rsm;              // key rsm.size (section 4: 256^2)

    // tcas only (gl/passes/metropolis_chains.h): the chains' iterations per frame and proposal.
    int iterations = 16;        // SMCIR section 5.1: 16 (Barak et al.: 5)
    MetropolisProposal proposal;

    enum Kind { VSGL, VPLBRSM, TCAS };
    void visitParams(ParamVisitor& visitor, const std::string& prefix, Kind kind);
};

class VSGLTechnique final : public Technique {
public:
    explicit VSGLTechnique(VSGLParams::Kind kind);
    ~VSGLTechnique() override;
    std::string_view name() const override
    {
        return mKind == VSGLParams::TCAS ? "tcas" : mKind == VSGLParams::VPLBRSM ? "vpl-brsm" : "vsgl";
    }
    void setScene(const SceneContext& context) override;
    void update(const FrameContext& frame) override;
    void render(const FrameContext& frame, const GBuffer& gbuffer, const IndirectTarget& target) override;
    void visitParams(ParamVisitor& visitor) override;
    void reloadShaders(const gl::ShaderLoader& shaders) override;
    std::vector<std::pair<std::string, double>> frameStats() const override;
    // conform compares it with: one bounce from the RSM (VSGL eq. (1)).
    PathTracerParams::Mode matchedReferenceMode() const override { return PathTracerParams::Mode::OneBounce; }
    std::vector<DebugView> debugViews() const override;
    void applyParamChanges(const std::set<std::string>& changedKeys) override;

    // For tests.
    const RSMPass& rsm() const { return *mRSM; }
    const gl::Buffer& lights() const { return mLights; }
    const gl::Texture& importance() const { return mImportance; }
    const MetropolisChains* chains() const { return mChains.get(); } // tcas

private:
    void createPasses(const gl::ShaderLoader& shaders);

    bool pointLights() const { return mKind != VSGLParams::VSGL; } // vpl-brsm and tcas

    VSGLParams::Kind mKind;
    VSGLParams mParams;
    const Scene* mScene = nullptr;
    const gl::ShaderLoader* mShaders = nullptr;
    const GpuScene* mGpuScene = nullptr;
    std::unique_ptr<RSMPass> mRSM;
    std::unique_ptr<ImportanceSampler> mSampler;
    std::unique_ptr<MetropolisChains> mChains; // tcas
    bool mChainsStarted = false;               // false: the next frame starts the chains from draws
    ComputePass mViewRSMPass;
    ComputePass mGeneratePass;
    ComputePass mImportancePass;
    std::unique_ptr<FullscreenPass> mShading;
    std::unique_ptr<ImperfectShadowMaps> mISM; // made for the current count and ISM parameters
    gl::Sampler mTrilinear;
    gl::RenderTarget mViewRSM;   // the G-buffer grid in the RSM layout, with mips
    gl::Texture mImportance;     // R32F, (rsm.size x layers) x rsm.size
    gl::Texture mNoImportance;   // bound to the importance unit while the view lights are made (they read none)
    gl::Buffer mViewLights;      // VSGLight[(viewGrid >> viewLevel)^2]
    gl::Buffer mLights;          // VSGLight[N]
    gl::RenderTarget mShaded;    // radiance, cancelled fraction
    int mValidLights = 0;
    int mViewLightCount = 0;
    int mCount = 0; // the N in effect: count clamped to the GL limits (gl/api/limits.h)
};

} // namespace vplgi
