// Binding slots and GPU structs, named once for C++ and GLSL.
#ifndef VPLGI_SHARED_BINDINGS_H
#define VPLGI_SHARED_BINDINGS_H
#include "compat.h"
#include "lights.h"

VPLGI_SHARED_BEGIN

// Uniform and storage buffer bindings.
VPLGI_CONST int kBindingFrame = 0;               // UBO FrameUniforms
VPLGI_CONST int kBindingPointEmitters = 1;       // SSBO PointEmitter[]
VPLGI_CONST int kBindingDirectionalEmitters = 2; // SSBO DirectionalEmitter[]
VPLGI_CONST int kBindingShadowMatrices = 3;      // SSBO mat4[] (clipFromWorld per shadow layer)

// Storage buffers of the compute passes (gl/passes/prefix_sum_pass, importance_sampler).
VPLGI_CONST int kBindingScanValues = 4;          // SSBO float[]: scanned in place
VPLGI_CONST int kBindingScanBlockSums = 5;       // SSBO float[]: one total per work-group block
VPLGI_CONST int kBindingImportanceColumns = 6;   // SSBO float[W*H]: column prefix sums C(u,v), row-major
VPLGI_CONST int kBindingImportanceMarginal = 7;  // SSBO float[W]: prefix sums of column totals R(u)
VPLGI_CONST int kBindingImportanceSamples = 8;   // SSBO ImportanceSample[]

// Storage buffers of the shadow atlas (gl/passes/shadow_atlas).
VPLGI_CONST int kBindingShadowAtlasMatrices = 9; // SSBO mat4[] (clipFromWorld per shadow-atlas tile index)
VPLGI_CONST int kBindingShadowAtlasDraw = 10;    // SSBO int[] (tile index per instance of a ShadowAtlas draw)

// Storage buffers of the VPL techniques (gl/passes/vpl_shadow_maps, gl/techniques/vpl_technique).
VPLGI_CONST int kBindingVPLs = 11;               // SSBO GpuVPL[] (glsl/shared/vpl.h), one per slot
VPLGI_CONST int kBindingVPLBatch = 12;           // SSBO VPLBatchItem[]: the VPLs whose maps are being resampled

// Storage buffers of VSGL (gl/techniques/vsgl_technique).
VPLGI_CONST int kBindingVSGLights = 13;          // SSBO VSGLight[] (glsl/shared/sg.h): the lights, or the view lights
VPLGI_CONST int kBindingRSMLayers = 14;          // SSBO RSMLayerLight[] (glsl/shared/rsm.h): each RSM layer's light

// Storage buffers of the imperfect shadow maps (gl/passes/imperfect_shadow_maps).
VPLGI_CONST int kBindingISMPoints = 15;          // SSBO uvec4[]: the scene's surface points (position, normal; reach)
VPLGI_CONST int kBindingISMLights = 16;          // SSBO vec4[]: the lights' records (position+valid, normal, ...)
VPLGI_CONST int kBindingISMNearIndices = 30;     // SSBO uint[]: the points' indices, hash slot by hash slot (near field)
VPLGI_CONST int kBindingISMNearSlots = 31;       // SSBO uint[T + 1]: each hash slot's first index (near field)

// Storage buffers of LightSkin (gl/techniques/lightskin_technique, glsl/shared/lightskin_gpu.h).
VPLGI_CONST int kBindingLightCaches = 17;        // SSBO GpuLightCache[] (world space)
VPLGI_CONST int kBindingLightCacheCells = 18;    // SSBO uvec4[]: the cells' hash slots (glsl/shared/light_cache_lookup.h)
VPLGI_CONST int kBindingLightCacheIndices = 19;  // SSBO uint[]: cache indices, cell by cell
VPLGI_CONST int kBindingProxyLights = 20;        // SSBO ProxyLight[]: per cache, diffuse and glossy
VPLGI_CONST int kBindingViewSamples = 21;        // SSBO ViewSample[]: G-buffer samples at Halton points
VPLGI_CONST int kBindingRSMLayerViews = 22;      // SSBO RSMLayerView[]: each RSM layer's depth row and texel size
VPLGI_CONST int kBindingProxySums = 23;          // SSBO vec4[]: the proxy pass's sums per (cache, chunk of VALs)
VPLGI_CONST int kBindingOcclusionTargets = 24;   // SSBO OcclusionTarget[]: kOcclusionCells per cache
VPLGI_CONST int kBindingLightCacheReach = 25;    // SSBO uvec4[]: each cache's reach (glsl/shared/light_cache_lookup.h)
VPLGI_CONST int kBindingCacheRadiance = 26;      // SSBO float[]: each cache's own reflected radiance (luminance)
VPLGI_CONST int kBindingLightCacheVisibility = 29; // SSBO uvec2[]: each cache's visibility map (glsl/shared/lightskin_visibility.h)
// Metropolis-Hastings chains over an importance map (gl/passes/metropolis_chains.h; technique tcas).
VPLGI_CONST int kBindingChainStates = 27;        // SSBO uint[]: each chain's texel, y * W + x (kNoChainState: none)
VPLGI_CONST int kBindingChainCounters = 28;      // SSBO uint[1]: chains that moved in the last step
VPLGI_CONST uint kNoChainState = 0xffffffffu;

// Image units (glBindImageTexture), a namespace separate from texture units.
VPLGI_CONST int kImageImportance = 0; // r32f importance map read by the importance sampler
VPLGI_CONST int kImageRSMTarget = 0;  // 6 units: RSM level l+1 per attachment (passes/rsm_downsample.comp)
VPLGI_CONST int kImageVPLShadowMaps = 6; // r32f 2D array: the VPL paraboloid maps being written
VPLGI_CONST int kImageISMMaps = 6;    // ISM maps (r32f seen as r32ui): the level being splatted, pulled from or pushed
VPLGI_CONST int kImageISMCoarser = 7; // ISM maps (r32f seen as r32ui): the next coarser level
VPLGI_CONST int kImageISMNormals = 7; // ISM planes' packed normals (r32ui), in the splat and gap filling (pull-push uses unit 7 after them)
VPLGI_CONST int kImageISMGapDistances = 2; // ISM gap filling's output distances (r32f seen as r32ui)
VPLGI_CONST int kImageISMGapNormals = 3;   // ISM gap filling's output packed normals (r32ui)
VPLGI_CONST int kImageSelectedVALs = 1; // r32f map of the RSM texels LightSkin selected (its debug view)
VPLGI_CONST int kImageImportanceCoarser = 1; // r32f importance map, level l+1 (passes/importance_mips.comp)

// Texture units.
VPLGI_CONST int kUnitBaseColor = 0;
VPLGI_CONST int kUnitMetallicRoughness = 1;
VPLGI_CONST int kUnitEmission = 2;
VPLGI_CONST int kUnitNormalMap = 3;
VPLGI_CONST int kUnitGBufferPosition = 4;
VPLGI_CONST int kUnitGBufferNormal = 5;
VPLGI_CONST int kUnitGBufferBaseColor = 6;
VPLGI_CONST int kUnitGBufferEmission = 7;
VPLGI_CONST int kUnitPointShadows = 8;
VPLGI_CONST int kUnitDirectionalShadows = 9;
VPLGI_CONST int kUnitDirect = 10;
VPLGI_CONST int kUnitIndirect = 11;
VPLGI_CONST int kUnitRSMSource = 12; // 6 units: RSM level l per attachment (passes/rsm_downsample.comp)
VPLGI_CONST int kUnitShadowAtlas = 18; // ShadowAtlas depth (sampler2DArray), after the RSM units 12..17
VPLGI_CONST int kUnitVPLShadowMaps = 19; // VPL paraboloid maps: distance [m] (sampler2DArray, r32f)
VPLGI_CONST int kUnitDisplayView = 20; // renderer.display's texture view (sampler2DArray; passes/tonemap.frag)
VPLGI_CONST int kUnitBilateralInput = 21; // unfiltered radiance read by passes/bilateral_filter.frag
VPLGI_CONST int kUnitISM = 22; // imperfect shadow maps: distance [m] (sampler2DArray, r32f; gl/passes/imperfect_shadow_maps)
VPLGI_CONST int kUnitImportanceMips = 23; // the PDF of BRSMs with box mips (passes/vsgl_generate.comp: vsgl.footprint = cell)
VPLGI_CONST int kUnitGBufferSurfaceNormals = 24; // G-buffer: octahedral geometric (xy) and interpolated (zw) normals
VPLGI_CONST int kUnitBilateralGuide = 25; // per pixel: the filter's normal (xyz) and in-plane scale (w) (passes/bilateral_guide.frag)
VPLGI_CONST int kUnitAntialiasInput = 26; // the tone-mapped display that passes/fxaa.frag antialiases
VPLGI_CONST int kUnitISMNormals = 27; // imperfect shadow maps with planes: packed normals (usampler2DArray, r32ui)

// Explicit uniform locations (program-wide: the vertex and fragment stages share them).
VPLGI_CONST int kLocationFullscreenLayer = 0; // lib/fullscreen.vert: layer of a layered target
VPLGI_CONST int kLocationDisplayView = 1;     // passes/tonemap.frag: renderer.display (kDisplay*)
VPLGI_CONST int kLocationDisplayViewInfo = 2; // passes/tonemap.frag: ivec4 (kDebugView* kind, layers shown, 0, 0)
VPLGI_CONST int kLocationDisplayViewRect = 3; // passes/tonemap.frag: ivec4 texel rectangle x, y, width, height
VPLGI_CONST int kLocationDisplayViewRange = 4; // passes/tonemap.frag: vec2 value range (scalar and count views)

// renderer.display: what the tone-map pass shows.
VPLGI_CONST int kDisplayFinal = 0;    // direct + indirect, tone mapped
VPLGI_CONST int kDisplayDirect = 1;   // direct light only (+ emission), tone mapped
VPLGI_CONST int kDisplayIndirect = 2; // the technique's indirect light, tone mapped
VPLGI_CONST int kDisplayAlbedo = 3;   // G-buffer base colour (linear, sRGB-encoded)
VPLGI_CONST int kDisplayNormal = 4;   // G-buffer shading normal, n * 0.5 + 0.5
VPLGI_CONST int kDisplayDepth = 5;    // distance to the eye d [m] as d / (1 + d)
VPLGI_CONST int kDisplayTextureView = 6; // a texture view by name (Technique::debugViews, gl/techniques/technique.h)

// How a texture view (DebugView::kind) is turned into display values.
VPLGI_CONST int kDebugViewColor = 0;  // rgb HDR colour: exposure, Reinhard, sRGB, as the final image
VPLGI_CONST int kDebugViewScalar = 1; // r (depth, distance, ...) mapped linearly from range to grey [0, 1]
VPLGI_CONST int kDebugViewNormal = 2; // xyz unit vector as xyz * 0.5 + 0.5
VPLGI_CONST int kDebugViewCount = 3;  // r >= 0 as log2(1 + r) / log2(1 + range max) grey (counts span decades)

// Per-frame constants (std140; vec4/mat4 members only).
struct FrameUniforms {
    mat4 clipFromWorld;
    mat4 viewFromWorld;
    mat4 worldFromClip;
    vec4 cameraPosition; // xyz eye [m]
    vec4 viewport;       // width, height, 1/width, 1/height
    ivec4 counts;        // x point emitters, y directional emitters, z frame index, w unused
    vec4 shadow;         // x cube far distance [m], y normal offset [texels], z depth bias [m], w PCF radius [texels]
    vec4 toneMap;        // x exposure, yzw unused
};

VPLGI_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(vplgi::shared::FrameUniforms) == 3 * 64 + 5 * 16, "FrameUniforms must match std140");
static_assert(sizeof(vplgi::shared::PointEmitter) == 64, "PointEmitter must match std430");
static_assert(sizeof(vplgi::shared::DirectionalEmitter) == 32, "DirectionalEmitter must match std430");
#endif

#endif // VPLGI_SHARED_BINDINGS_H
