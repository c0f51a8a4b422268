// Techniques `lightskin` and `lightskin-full`: one-bounce diffuse and glossy indirect light with
// indirect occlusion from a high-resolution reflective shadow map, through light caches (Lensing,
// Broll: LightSkin) and, for `lightskin`, a bidirectional-RSM selection of the virtual area lights
// (Sievers et al.: LightSkin + BRSM for open worlds, papers/004). `lightskin-full` is the original
// LightSkin, every RSM texel a virtual area light, the paper's baseline.
//
// Intro
// -----
// LightSkin does not light every pixel by every virtual light. It lights a sparse set of light
// caches, precomputed on the surfaces (core/lightskin/light_caches.h), and interpolates. Each
// cache sums the RSM texels' virtual area lights (VALs, eq. 3-4) into two proxy point lights, one
// for diffuse and one for glossy reflection (eq. 5-7), dims them by a cheap occlusion estimate
// (double projection), and every pixel interpolates the proxy lights of its nearest caches (eq.
// 8-9) and shades with them. Its cost is caches x VALs: at the RSM sizes an open world needs
// (1024^2-2048^2) that is millions of VALs per cache. The paper's addition selects N_sVAL VALs
// (2048-8192) by their importance to the camera's view (eq. 10-11, Ritschel et al.'s BRSM) and
// weights them by 1/P_VAL (eq. 13-15), an unbiased estimate of the full sums.
//
// Overview (per frame; the timer scopes are the rows the paper's pipeline, Fig. 1, names)
// --------
//  RSM             RSMPass: the sun's (and any spot/point light's) RSM at rsm.size (default 1024^2)
//  importance      lightskin_view_samples.comp: the G-buffer at N_VS Halton points (eq. 10's view
//                  samples); lightskin_importance.comp: eq. (10)-(11) for every RSM texel
//  SAT             ImportanceSampler::build: the cumulative sums, vertically then horizontally
//  selection       ImportanceSampler::sample: binary search for N_sVAL texels (eq. 12)
//  proxy lights    lightskin_proxy.comp: per cache and chunk of VALs, the sums of the selected VALs
//                  (or all: lightskin-full); lightskin_proxy_finalize.comp: the diffuse and glossy
//                  proxy lights from them (eq. 13-15, 6, 7)
//  occlusion       lightskin_occlusion.comp: double projection of the light (per occlusion cell of
//                  the cache's unit disk, ours; or the proxies' bounding spheres, the paper's) and
//                  the other caches' disks (section 3, "Occlusion"); lightskin.occlusion=false skips
//                  it, lightskin.tracedOcclusion traces each cache's visibility with Embree instead;
//                  with lightskin.visibilityMaps (ours) the proxy pass weights each VAL by the
//                  cache's visibility map instead, and this pass is skipped
//  interpolation   lightskin_shading.frag: every pixel finds its <= 16 nearest caches, interpolates
//                  the proxies (eq. 8-9) and shades with them
//
// Details
// -------
//  VAL flux: the RSM stores the incident flux of a texel; a VAL emits the diffusely reflected part,
//  flux x (1 - metallic) baseColor. The paper's VALs are diffuse emitters (eq. 3's cos+ theta_l):
//  the specular reflection of the RSM's surfaces is not carried (VSGL carries it).
//  Cache albedo: eq. (7) divides the cache's radiance by its BRDF, which contains the same albedo
//  that eq. (3)/(4) multiplied in (MATH.md 9.4): the proxies carry incident light, and the pixel's
//  own BRDF (glTF's Lambert + GGX) is applied when shading. The glossy terms' Phong exponent k comes
//  from the cache's mean roughness through glsl/shared/lightskin.h phongExponentFromRoughness.
//  Nearest caches per pixel, not per vertex: the paper stores 16 cache references per vertex, which
//  assumes finely tessellated models (a floor of two triangles would interpolate from caches far
//  from every pixel); our per-pixel search in a uniform grid (glsl/shared/light_cache_lookup.h)
//  works on any mesh at the cost of a grid walk per pixel.
//  Reference: the one-bounce path tracer (`vplgi compare --reference-mode onebounce`).
//  Seed: the selection's uniforms are the same every frame unless lightskin.animateSeed.
//
// References
// ----------
//  papers/004 sections 3 and 4; MATH.md 9; Lensing, Broll: LightSkin (ISMAR 2013, 2013b);
//  Ritschel et al. 2011 (BRSM); Ward et al. 1988 (irradiance caching).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "../api/render_target.h"
#include "../passes/compute_pass.h"
#include "../passes/fullscreen_pass.h"
#include "../passes/importance_sampler.h"
#include "../passes/rsm_pass.h"
#include "core/lightskin/light_caches.h"
#include "glsl/shared/lightskin.h"
#include "technique.h"

namespace vplgi {

struct LightSkinParams {
    int valCount = 2048;                               // N_sVAL (section 5: 2048, 4096, 8192)
    int viewSamples = 512;                             // N_VS (section 4: 512; 256 as an option)
    float importanceClamp = 1.0f;                      // eq. (11): D(l) = max(clamp^2, |l|^2) [m] (the paper: 1); 0 = scaled with the scene (resolveImportanceClamp; ours)
    float weightEpsilon = shared::kProxyWeightEpsilon; // epsilon_p of eq. (6)
    bool fluxWeights = false;           // MATH.md 9.3: weight eq. (5)/(13) by the VAL's flux too (not in the paper)
    float interpolationExponent = 1.0f; // p of eq. (8) (the paper gives none; MATH.md 9.5)
    bool fixedRadius = true;      // eq. (8)'s d_max = the search radius d_eps (not in the paper: the farthest cache)
    bool reach = true;            // each cache's traced reach limits the points it lights (not in the paper)
    bool viewCulling = true;      // proxies only for caches whose d_eps ball meets the frustum (not in the paper)
    bool occlusion = true;        // occlusion: by the visibility maps, or with visibilityMaps=false the double projection (section 3)
    bool tracedOcclusion = false; // visibility per cache by Embree rays (the reference; not in the paper)
    bool visibilityMaps = true;   // each cache's hemisphere traced once, each VAL weighted by it (not in the paper)
    int visibilityMapSize = 32;   // ... texels along each side of a cache's map
    bool occlusionCells = true;   // ... against the VALs of 5 cells of the unit disk (not in the paper; lightskin.h)
    bool occluderLight = true;    // ... an occluder's own reflected light is not removed (not in the paper)
    bool exactArea = false;       // MATH.md 9.1: the tilted texel footprint instead of eq. (1)'s disk
    bool cubeFaceBudget = true;   // a point light's cube faces share one rsm.size^2 (RSMCubeFaces; not in the paper)
    std::uint32_t seed = 1;
    bool animateSeed = false;
    LightCacheParams caches; // keys lightskin.cache*
    RSMParams rsm;           // key rsm.size (open worlds: 1024^2-2048^2)

    LightSkinParams() { rsm.size = 1024; }
    void visitParams(ParamVisitor& visitor, bool selection);
};

class LightSkinTechnique final : public Technique {
public:
    explicit LightSkinTechnique(bool full);
    ~LightSkinTechnique() override;
    std::string_view name() const override { return mFull ? "lightskin-full" : "lightskin"; }
    void setScene(const SceneContext& context) override;
    void update(const FrameContext& frame) override;
    void render(const FrameContext& frame, const GBuffer& gbuffer, const IndirectTarget& target) override;
    void visitParams(ParamVisitor& visitor) override;
    void reloadShaders(const gl::ShaderLoader& shaders) override;
    std::vector<std::pair<std::string, double>> frameStats() const override;
    // conform compares it with: one bounce from the RSM (LightSkin section 3).
    PathTracerParams::Mode matchedReferenceMode() const override { return PathTracerParams::Mode::OneBounce; }
    std::vector<DebugView> debugViews() const override;
    void applyParamChanges(const std::set<std::string>& changedKeys) override;

    // For tests.
    const LightCacheSet& caches() const { return mCaches; }
    const std::vector<std::uint8_t>& cachesInView() const { return mInView; } // the last frame's view culling
    const gl::Buffer& proxies() const { return mProxies; }
    const gl::Texture& importance() const { return mImportance; }
    const ImportanceSampler& sampler() const { return *mSampler; }
    const RSMPass& rsm() const { return *mRSM; }

private:
    void createPasses(const gl::ShaderLoader& shaders);
    void uploadCaches();
    void drawCacheView(const FrameContext& frame);
    void traceOcclusion(int size, int layers);

    bool mFull;
    LightSkinParams mParams;
    const Scene* mScene = nullptr;
    const GpuScene* mGpuScene = nullptr;
    const SharedRayScene* mRays = nullptr;
    ProgressSink mProgress;
    bool mCachesStale = true;
    LightCacheSet mCaches;
    std::unique_ptr<RSMPass> mRSM;
    std::unique_ptr<ImportanceSampler> mSampler;
    ComputePass mViewSamplePass;
    ComputePass mImportancePass;
    ComputePass mMarkPass;
    ComputePass mProxyPass;    // the sums per (cache, chunk of VALs)
    ComputePass mFinalizePass; // the proxies from the sums
    ComputePass mOcclusionPass;
    std::unique_ptr<FullscreenPass> mShading;
    gl::Program mCacheViewProgram;
    gl::VertexArray mEmptyVertexArray;
    gl::Buffer mCacheBuffer;      // GpuLightCache[caches]
    gl::Buffer mCellBuffer;       // uint[cells + 1]
    gl::Buffer mIndexBuffer;      // uint[entries]
    gl::Buffer mReachBuffer;      // uvec4[caches]: reach records (glsl/shared/light_cache_lookup.h), or one unused
    gl::Buffer mVisibilityBuffer; // uvec2[caches x size^2]: visibility maps (glsl/shared/lightskin_visibility.h), or one
    gl::Buffer mProxies;          // ProxyLight[caches]
    gl::Buffer mProxySums;        // vec4[caches x chunks x kProxySumVec4s]
    gl::Buffer mOcclusionTargets; // OcclusionTarget[caches x kOcclusionCells]
    gl::Buffer mCacheRadiance;    // float[caches]: each cache's own reflected radiance (luminance), the finalize pass
    gl::Buffer mViewSamples;      // ViewSample[N_VS]
    gl::Buffer mLayerViews;       // RSMLayerView[layers]
    gl::Texture mImportance;      // R32F, (rsm.size x layers) x rsm.size
    gl::Texture mSelected;        // R32F, as mImportance: 1 where a VAL was selected (debug view)
    gl::RenderTarget mCacheView;  // the caches as points (debug view)
    gl::RenderTarget mShaded;
    long long mVALsPerCache = 0;
    long long mCachesInView = 0;       // caches whose proxies the last frame made (lightskin.viewCulling)
    std::vector<std::uint8_t> mInView; // per cache: 1 when the view culling keeps it (the traced occlusion's too)
    std::vector<glm::uvec2> mVisibilityMaps; // lightskin.visibilityMaps, cache after cache (traced_visibility.h)
    static constexpr std::size_t kMaxVisibilityMapBytes = std::size_t(1) << 30; // 1 GiB of GPU memory at most
    float mAutomaticClamp = 1.0f; // eq. (11)'s automatic clamp distance on this scene [m] (resolveImportanceClamp)
    float mImportanceRange = 1.0f; // of the importance view: 20x the mean texel importance
};

} // namespace vplgi
