// Reflective shadow maps (RSMs) with mips, for the RSM-based techniques (VSGL, BRSM, LightSkin).
//
// Intro
// -----
// An RSM is the scene rasterised from a light: every texel is a surface element the light hits
// first, with what a virtual point light (VPL) made from it needs. VSGL (papers/002, Sec. 3.2)
// samples texels by importance and reads the values from a mip level chosen by the sample density
// (MATH.md 5.2), so the mips must be filtered averages of the texels' contents, not of the image.
//
// Overview
// --------
//  render()     layers of a 2D-array target: one per spot light, six per point light (its cube
//               faces, GL order +X, -X, +Y, -Y, +Z, -Z) in DirectLightSet order, then one per
//               directional light; emissive samples get none (see "Point lights" below). Then the
//               mips.
//  Attachments  (glsl/shared/rsm.h; all RGBA32F, size rsm.size^2, full mip chain)
//               position  xyz world position [m], w |x|^2 (VSGL's "squared norm"; MATH.md 5.3)
//               normal    xyz shading normal, w coverage (1 where a surface was rasterised)
//               flux      rgb incident flux of the texel [W]: the light's flux through the texel
//                         (MATH.md 1.5), before reflection; a diffuse VPL's flux is this times
//                         `diffuse`. Incident rather than reflected so that a metal (diffuse 0)
//                         still carries the flux its specular lobe reflects (VSGL's caustics)
//               diffuse   rgb (1 - metallic) baseColor
//               specular  rgb F0 = mix(0.04 specular, baseColor, metallic), w perceptual roughness
//               lobe      xyz the reflection lobe of the light's direction as a Toksvig vector
//                         (eta/(1+eta)) xi (MATH.md 4.6-4.8); its mean over texels keeps the spread;
//                         w the lobe's integral factor s (glsl/shared/sg.h ggxReflectionLobe): the
//                         specular BRDF is ~ F s normalisedSG, VSGL's "coefficient" (section 3.2)
//
// Details
// -------
//  Views. Spot: a square perspective frustum down the axis whose half-angle is the outer cone
//  angle, capped at kRSMMaxSpotHalfAngle (light_view.h lightViewSpot*); near/far from the scene
//  bounds. Directional: lightViewDirectionalFit (the same orthographic view as its shadow map).
//  Point: the six faces of light_view.h's cube (lightViewCubeFace*, as the shadow cubes), near/far
//  as for spots.
//  Flux per texel (MATH.md 1.5). Spot and point: I(w) dw_t with dw_t = 4/(P00 P11 W H) cos^3(alpha),
//  alpha the texel ray's angle to the view axis (the texel's solid angle); directional: E * 4/(P00 P11 W H),
//  the texel's area across the beam. Surfaces take all the flux of their texel: no cosine here.
//  Mips (downsampleRSMLayout: rsm_downsample.comp through ComputePass, one dispatch per level: level l read with
//  texelFetch, level l+1 written as images, six image uniforms within the GL minimum of eight).
//  Coverage and flux are plain 2x2 means, so level l holds per-texel averages (MATH.md 5.2 reads
//  Phi_h as one) and
//  4^l * sum(level l flux) is the total. Everything else is the mean over the level-0 texels below
//  weighted by their flux sum r+g+b (coverage x flux: empty and unlit texels weigh 0); where the
//  block holds no flux at all, weighted by coverage; where it holds no surface, 0. A 2x2 mean with
//  the children's flux means as weights is exactly that (all children cover equally many level-0
//  texels: RSM sizes are powers of two). Normals and lobes are not renormalised: the normal's
//  length is the Toksvig factor |N_a| (MATH.md 4.8), 1 on a flat surface. Each target texel is one
//  invocation summing its children in a fixed order: bit-identical across runs and thread counts.
//  Point lights: six cube faces, not two paraboloids. A paraboloid projection is not linear:
//  a triangle's edges map to curves, so a rasteriser draws large triangles (a floor of two
//  triangles) in the wrong texels unless the scene is tessellated finely, while a cube face is a
//  perspective projection, exact for any triangle. The faces also reuse everything the spot path
//  has (texel solid angle cos^3, the mip reduction per layer, light_view.h's cube faces, the same
//  as the shadow cubes'). The price: six layers per light instead of two, and the mips stop at
//  the face seams (a consumer filtering across a seam must look up the neighbouring face). A
//  consumer that reads texels one by one can keep the six faces within one light's texels
//  (RSMCubeFaces::LightBudget, LightSkin).
//  Emissive triangles (not in any paper: VSGL, LightSkin and the RSM papers light by point, spot
//  and directional lights): their lights.emitterSamples cosine samples are merged into at most
//  rsm.areaSources cosine emitters (groupCosineEmitters, core/scene/direct_lights.h), each rendered
//  like a point light over the cube faces its hemisphere reaches (a face wholly behind the emitter
//  is skipped), with I(w) = I max(n . w, 0): the flux through a texel is I (n . w) x its solid
//  angle (MATH.md 1.5 with the cosine profile), so a group's faces hold its power pi I times the
//  fraction that reaches a surface. rsm.areaSources = 0 leaves them out, with a warning. Default 1
//  (ours): on Cornell (one ceiling panel) one source against four, 4 seeds (`vplgi conform --scenes
//  cornell --techniques 'vpl-brsm,vpl-brsm[rsm.areaSources=4],vsgl,vsgl[rsm.areaSources=4]' --seeds 4
//  --width 32 --height 18`): vpl-brsm -0.9% [-2.0, +0.3] and -1.5% [-2.3, -0.7] against the one-bounce
//  path tracer, vsgl -10.2% [-11.5, -8.9] and -21.0% [-22.0, -20.0] (four times the cube-face seams,
//  which its footprints do not cross), and four sources give lightskin-full four times the VALs.
//  Precision: positions are absolute world coordinates; |x|^2 - |E[x]|^2 loses digits far from the
//  origin (MATH.md 5.3 float32 caution). A consumer that needs the variance far away should store
//  positions relative to the light instead.
//
// References
// ----------
//  C. Dachsbacher, M. Stamminger: Reflective Shadow Maps, I3D 2005.
//  Y. Tokuyoshi: Virtual Spherical Gaussian Lights for Real-Time Glossy Indirect Illumination
//    (papers/002), Sec. 3.2: RSM contents and filtered importance sampling.
//  M. Toksvig: Mipmapping Normal Maps, 2005 (MATH.md 4.8).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "../api/render_target.h"
#include "../api/shader_loader.h"
#include "../debug_view.h"
#include "../gpu_scene.h"
#include "compute_pass.h"
#include "core/scene/direct_lights.h"

namespace vplgi {

class ParamVisitor;

struct RSMParams {
    int size = 256;       // RSM resolution per light [texels], a power of two
    int areaSources = 1;  // emissive triangles as at most this many cosine RSM sources; 0: none
    void visitParams(ParamVisitor& visitor);
};

// The widest spot frustum: cones wider than this lose their rim (the frustum grows as tan).
constexpr float kRSMMaxSpotHalfAngle = 1.4835299f; // 85 degrees

// How the cube faces of a point light or an emissive source are sized (issue "LightSkin's indirect
// shadows", part 4).
//  FaceEach     every face rsm.size^2: a point light takes six times a spot light's texels.
//  LightBudget  (LightSkin's; not in any paper, whose lights are spots and the sun) the faces of one
//               light share one rsm.size^2: each is floor(rsm.size / sqrt(faces)) texels wide, drawn
//               into the corner from texel (0, 0) of its layer (RSMView::size); the rest of the layer
//               stays cleared (coverage 0, no flux), which every per-texel reader skips as it skips a
//               texel that sees no surface. Only RSMMips::None: the mips and VSGL's footprints take
//               whole layers.
enum class RSMCubeFaces { FaceEach, LightBudget };

// What layer i of the RSM was rendered for.
struct RSMView {
    int kind = 0;    // shared::kRSMLightSpot / kRSMLightPoint / kRSMLightArea / kRSMLightDirectional
    int emitter = 0; // index in DirectLightSet::points / ::directionals; area: the group's index
    int face = 0;    // point, area: cube face (0..5 = +X, -X, +Y, -Y, +Z, -Z); 0 otherwise
    shared::PointEmitter source{}; // spot, point, area: the emitter the layer sees (area: its group)
    glm::mat4 viewFromWorld{1.0f};
    glm::mat4 clipFromView{1.0f};
    glm::mat4 clipFromWorld{1.0f};
    float texelFactor = 0.0f; // 4/(P00 P11 W H): on-axis texel solid angle [sr] or area [m^2]
    int size = 0;             // the layer's square in use, from texel (0, 0) [texels]: W = H (RSMCubeFaces)
};

// A target with the RSM layout above (2D array, full mip chain, depth when `withDepth`): the RSM
// pass's and VSGL's G-buffer-as-light (gl/techniques/vsgl_technique.h), which share the mips.
gl::RenderTarget makeRSMLayoutTarget(const std::string& name, bool withDepth, bool mips = true);
// Recomputes levels 1.. of every layer of an RSM-layout target from level 0 with `kernel`
// (passes/rsm_downsample.comp), then issues the barriers for sampling, readback and image loads.
void downsampleRSMLayout(const ComputePass& kernel, const gl::RenderTarget& target, gl::PassTimer* timer = nullptr);

class RSMPass;

// The debug view `name` of an RSM pass's incident flux, every layer tiled (renderer.displayLayer
// picks one); black while `rsm` is null or has no layer. Shared by the RSM techniques.
DebugView rsmFluxDebugView(const std::string& name, const RSMPass* rsm);

// Whether a technique reads the RSM's mips (issue "Every light type in the RSM techniques", part 4).
// Only VSGL's footprints read levels > 0; vpl-brsm and LightSkin read level 0 (texelFetch), so
// their RSM has one level and no downsample pass. Per attachment it is all or none: the kernel's
// weights need flux and coverage whatever else is built, and a per-attachment branch in
// rsm_downsample.comp changed VSGL's output by 17% on llvmpipe with the branch never taken.
enum class RSMMips { None, All };

class RSMPass {
public:
    explicit RSMPass(const gl::ShaderLoader& shaders, RSMMips mips = RSMMips::All);
    void reloadShaders(const gl::ShaderLoader& shaders);
    // Renders every spot, point, area (emissive) and directional light's RSM and, with RSMMips::All,
    // its mips. Throws Error when params.size is not a power of two, or for RSMCubeFaces::LightBudget
    // with mips. With no such light, nothing is drawn and layerCount() is 0.
    void render(const GpuScene& scene, const DirectLightSet& lights, const RSMParams& params,
                gl::PassTimer* timer = nullptr, RSMCubeFaces faces = RSMCubeFaces::FaceEach);
    // Recomputes levels 1.. from level 0 (render() calls it with RSMMips::All; public for the tests).
    void downsample(gl::PassTimer* timer = nullptr);

    const gl::RenderTarget& target() const { return mTarget; }
    const ComputePass& downsampleKernel() const { return mDownsample; }
    const std::vector<RSMView>& views() const { return mViews; }
    // shared::RSMLayerLight per layer (glsl/shared/rsm.h), for consumers that need the direction to
    // the light at a texel; bind it at shared::kBindingRSMLayers.
    const gl::Buffer& layerLights() const { return mLayerLights; }
    int layerCount() const { return static_cast<int>(mViews.size()); }
    // Mip levels of the target: log2(size) + 1 with RSMMips::All, else 1.
    int levelCount() const { return mLevels; }
    RSMMips mips() const { return mMips; }
    // The edge of the last render's layers: rsm.size, clamped to the GL limits (gl/api/limits.h).
    int size() const { return mSize; }

    // The views render() would use (CPU only; shared with the tests' CPU rasterisation).
    static std::vector<RSMView> makeViews(const AABB& bounds, const DirectLightSet& lights, int areaSources,
                                          int size, RSMCubeFaces faces = RSMCubeFaces::FaceEach);

private:
    SceneProgram mProgram;
    ComputePass mDownsample;
    RSMMips mMips;
    gl::RenderTarget mTarget;
    std::vector<RSMView> mViews;
    gl::Buffer mLayerLights;
    int mLevels = 0;
    int mSize = 0;
    bool mWarnedArea = false; // the rsm.areaSources = 0 warning, once
};

} // namespace vplgi
