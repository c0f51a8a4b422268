// Techniques `smcir` and `ir`: a CPU-maintained VPL set rendered on the GPU with paraboloid shadow
// maps, 4x4 interleaved shading and a cross-bilateral filter (SMCIR section 4). The two differ only
// in where the VPLs come from, as in the paper's comparisons (section 5: "the same shadow maps,
// interleaving, filter and clamping").
//
// Intro
// -----
// `smcir`: Sequential Monte Carlo Instant Radiosity (Hedman et al. 2017, papers/000). The CPU half
// (core/vpl/smcir_sampler.h, Algorithm 1) keeps I VPLs in stable slots and moves at most M_max per
// frame; this file is the GPU half. Only the maps of VPLs that moved are re-rendered (lazy update),
// which is where the method's temporal coherence pays off on the GPU as well.
// `ir`: Keller's Instant Radiosity (1997), the paper's baseline: VPLs deposited along light paths
// (core/vpl/ir_sampler.h), drawn anew every frame, so every map is re-rendered every frame.
//
// Overview (per frame)
// --------
//  update()    VPLPipeline::advance: the sampler's step on its worker thread, one frame of latency
//  render()
//   1. upload   every slot's GpuVPL (glsl/shared/vpl.h) to an SSBO
//   2. shadow   VPLShadowMaps::update for the slots that changed since the set last rendered
//      maps     (VPLSet::changed; every slot after a gap, a rebuild or a parameter change)
//   3. shading  passes/vpl_shading.frag: eq. (5) per pixel over its interleaving subset, BRDF x
//               clamped G x paraboloid visibility x I(y), scaled by tile^2 / n
//   4. filter   cross-bilateral over the interleaved result (the structured noise), into the
//               renderer's indirect target
//
// Details
// -------
//  Estimator and clamp: exactly those of the CPU gather (core/vpl/vpl_gather.h): 1/n with n valid
//  VPLs, G clamped to G_max = 1/d^2, d = clampScale D / sqrt(I) (smcir.clampScale; the same for ir).
//  Visibility modes (<prefix>.visibility): shadowmaps (the paper), raytraced (the same interleaved
//  estimator evaluated by the CPU gather with Embree visibility; for sequences where re-rendering
//  every IR map each frame is too slow on a software rasterizer: Table 1 compares VPL
//  distributions, with visibility held equal), none (no occlusion; a diagnostic), probe (the shadow
//  lookup replaced by a fetch of one texel that every pixel reads: what the lookups cost, `vplgi bench`).
//  Shading modes (<prefix>.shading): interleaved (4 x 4 tiles, the paper) and exhaustive (every
//  pixel gathers every VPL: Fig. 8's "All VPLs - shadow maps").
//  Shadow test: the shaded point is lifted along its normal by normalOffset map texels at its
//  distance d from the VPL and is lit while d <= stored + depthBias texels at d, i.e. stored
//  (1 + 4 depthBias / N) for N x N maps; both are ours. The paper adjusts its depth bias with the
//  map resolution (Fig. 9, lines 1237-1238) but gives no value; ours is in texels so it shrinks as
//  the maps grow. Default 0.16 texels (0.5% of d at N = 128): the former 2% of d let light through
//  a 10 cm wall from VPLs 5 m away (the sealed room: `ir` 5.7e-4 of the lit room's mean, 0 now; 8
//  seeds, docs/smcir.md "Depth bias and thin walls").
//
// References
// ----------
//  SMCIR (papers/000) sections 4 and 5; A. Keller: Instant Radiosity, SIGGRAPH 1997; A. Keller,
//  W. Heidrich: Interleaved Sampling, EGWR 2001; MATH.md 1.2-1.4, 6, 7.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "../api/render_target.h"
#include "../passes/bilateral_filter.h"
#include "../passes/fullscreen_pass.h"
#include "../passes/vpl_shadow_maps.h"
#include "core/trace/ray_scene.h"
#include "core/vpl/ir_sampler.h"
#include "core/vpl/mir_sampler.h"
#include "core/vpl/smcir_sampler.h"
#include "core/vpl/vpl_gather.h"
#include "core/vpl/vpl_pipeline.h"
#include "technique.h"

namespace vplgi {

// How a VPL set is rendered: shared by smcir and ir (keys "<technique>.<field>").
struct VPLRenderParams {
    enum Shading { Interleaved, Exhaustive };
    enum Visibility { ShadowMaps, RayTraced, NoVisibility, FetchProbe };
    int shadowMapSize = 128;    // paraboloid map resolution (SMCIR section 4: 128 x 128) [4, 4096]
    int shading = Interleaved;  // interleaved (the paper) | exhaustive (every VPL at every pixel)
    int interleaveTile = 4;     // tile size of the interleaving (section 4: 4 x 4) [1, 16]
    int visibility = ShadowMaps;
    float normalOffset = 1.0f;  // shadow test: lift along the normal [map texels at the distance]; ours
    float depthBias = 0.16f;    // shadow test: lit while |x - y| <= stored + depthBias texels at the distance; ours
    int shadowBatch = 256;      // VPLs whose cube faces are rendered per batch [1, 65536]
    int mapsPerFrame = 0;       // most maps (re)made per frame, the rest wait for later frames (a viewer
                                // spreading the initial build); 0 = all at once. Ours
    bool rebuildEveryFrame = false; // re-render every map every frame (the lazy update's yardstick)
    BilateralFilterParams filter;   // the cross-bilateral filter (section 4): keys "<technique>.filter.*"
    int debugVPL = 0;           // the slot whose paraboloid map the "<technique>.map" view shows

    void visitParams(ParamVisitor& visitor, const std::string& prefix);
};

class VPLTechnique final : public Technique {
public:
    enum class Source { SMCIR, IR, MIR };
    explicit VPLTechnique(Source source);
    ~VPLTechnique() override;
    std::string_view name() const override;
    void setScene(const SceneContext& context) override;
    void update(const FrameContext& frame) override;
    void render(const FrameContext& frame, const GBuffer& gbuffer, const IndirectTarget& target) override;
    void visitParams(ParamVisitor& visitor) override;
    void reloadShaders(const gl::ShaderLoader& shaders) override;
    void applyParamChanges(const std::set<std::string>& changedKeys) override;
    std::vector<std::pair<std::string, double>> frameStats() const override;
    // conform compares it with: SMCIR 5.4: clamped, its bounce cap (configureReference).
    PathTracerParams::Mode matchedReferenceMode() const override { return PathTracerParams::Mode::Clamped; }
    std::vector<DebugView> debugViews() const override;
    void configureReference(PathTracerParams& params, const std::set<std::string>& explicitKeys) const override;

    // For tests: the paraboloid maps (after render()).
    const VPLShadowMaps* shadowMaps() const { return mShadowMaps.get(); }
    const VPLSet* renderedSet() const { return mRendered; }

private:
    std::string prefix() const { return std::string(name()); }
    void startPipeline();
    void createShadowMaps();
    void dropShadowMaps();
    float clampGeometry() const;
    int vplCount() const;
    void shadeRayTraced(const FrameContext& frame, const gl::RenderTarget& into);
    void drawDebugOverlay(const FrameContext& frame, const gl::Texture& indirect, bool overhead, float colorScale);

    Source mSource;
    SMCIRParams mSMCIR;
    IRParams mIR;
    float mIRClampScale = 2.0f; // ir.clampScale: the same clamp as smcir.clampScale, for ir's budget
    MIRParams mMIR;
    float mMIRClampScale = 2.0f; // mir.clampScale: the same clamp, for mir's budget
    VPLRenderParams mRender;
    bool mSynchronous = false;
    const Scene* mScene = nullptr;
    const GpuScene* mGpuScene = nullptr;
    const gl::ShaderLoader* mShaders = nullptr;
    const RayScene* mRays = nullptr;
    ProgressSink mProgress;
    std::unique_ptr<VPLPipeline> mPipeline;
    const VPLSet* mRendered = nullptr;
    std::unique_ptr<VPLShadowMaps> mShadowMaps;
    std::optional<std::uint64_t> mMapsGeneration; // the set generation the maps show
    std::vector<char> mMapPending;                // slots whose map waits (mapsPerFrame > 0)
    std::unique_ptr<FullscreenPass> mShading;
    std::unique_ptr<CrossBilateralFilter> mFilter;
    gl::Buffer mVPLBuffer;
    gl::RenderTarget mInterleaved; // the shading pass's output, before the filter
    SceneProgram mDebugProgram;    // passes/vpl_debug.*: splats and the overhead view, drawn while shown
    gl::VertexArray mEmptyVertexArray;
    gl::RenderTarget mSplats;      // the indirect image with the VPLs drawn over it
    gl::RenderTarget mOverhead;    // the scene from above, the VPLs and the camera frustum (Fig. 3 bottom)
    int mFacesRendered = 0;
    double mEvaluations = 0.0; // light-pixel pairs the shading pass evaluated (estimated: pixels x n / tile^2)
    double mRayTracedMilliseconds = 0.0;
};

} // namespace vplgi
