// LightSkin's GPU records (gl/techniques/lightskin_technique.h), named once for C++ and GLSL. The
// maths (eq. 1-15 of papers/004) is in glsl/shared/lightskin.h; the nearest-cache search in
// glsl/shared/light_cache_lookup.h.
#ifndef VPLGI_SHARED_LIGHTSKIN_GPU_H
#define VPLGI_SHARED_LIGHTSKIN_GPU_H
#include "compat.h"

VPLGI_SHARED_BEGIN

// One light cache (core/lightskin/light_caches.h LightCache, the same 64 bytes).
struct GpuLightCache {
    vec4 positionArea;    // xyz world position [m], w the surface area it represents [m^2]
    vec4 normalRoughness; // xyz unit normal, w mean perceptual roughness
    vec4 diffuseMetallic; // rgb mean diffuse reflectance, w mean metallic
    vec4 specular;        // rgb mean F0, w 1 for the second cache of a double-sided pair (its twin's copy)
};

// The two proxy lights of a cache (section 3, "Proxy Lights Generation"): isotropic point lights
// that reproduce the cache's diffuse and glossy radiance (eq. 7).
struct ProxyLight {
    vec4 diffusePositionRadius; // xyz position x_p (eq. 5/13) [m], w bounding-sphere radius [m]
    vec4 diffuseFlux;           // rgb flux Phi_p (eq. 7) [W], w visibility 1 - occlusion
    vec4 glossyPositionRadius;
    vec4 glossyFlux;
};

// What the occlusion pass tests occluders against, kOcclusionCells per cache (glsl/shared/
// lightskin.h, occlusionCell): with lightskin.occlusionCells, the VALs of one cell of the cache's
// unit disk; without, the paper's spheres (the diffuse proxy's with shares (1, 0), the glossy one's
// with (0, 1), the rest empty), projected by projectSphereToUnitDisk.
struct OcclusionTarget {
    vec4 square;      // xy centre on the cache's unit disk, z area there, w 0
    vec4 centre;      // xyz a point of the light (for the occluder-plane test) [m], w 0
    vec4 depthShares; // x the light's mean distance [m], y its spread [m] (0: a step at x, the sphere's near
                      // side), z its share of the diffuse radiance, w of the glossy (unnormalised)
};

// A camera G-buffer sample at a Halton point (eq. 10's view samples).
struct ViewSample {
    vec4 positionValid; // xyz world position [m], w 1 where the pixel holds a surface
    vec4 normal;        // xyz shading normal
};

// What eq. (1) needs of an RSM layer.
struct RSMLayerView {
    vec4 depthRow; // dot(depthRow, vec4(x, 1)) = the depth of world point x along the light's view axis [m]
    vec4 info;     // x texel factor 4/(P00 P11 W H) (on-axis solid angle [sr] or, orthographic, area [m^2]),
                   // y 1 for an orthographic (directional) layer, z the layer's square in use from texel
                   // (0, 0) [texels] (rsm_pass.h RSMCubeFaces), w unused
    vec4 clip0;    // the layer's clipFromWorld, column by column (a cache's own texel, the finalize pass)
    vec4 clip1;
    vec4 clip2;
    vec4 clip3;
};

// The proxy pass's sums per (cache, chunk) (lightskin_proxy.comp), in this order: 10 per proxy
// (sum w, sum w v (3), sum w v^2 (3), radiance (3); v = x_l - c), then 12 per occlusion cell (sum w_d,
// sum w_d (u, v) and sum w_d (u^2, v^2) of the VAL's coordinates on the cache's unit disk, sum w_d v
// (3), sum w_d |v| and sum w_d |v|^2, the luminance of the diffuse and of the glossy radiance).
VPLGI_CONST int kOcclusionCells = 5; // cells of a cache's unit disk (glsl/shared/lightskin.h, occlusionCell)
VPLGI_CONST int kProxySums = 10;
VPLGI_CONST int kProxyCellFirst = 2 * kProxySums;
VPLGI_CONST int kProxyCellSums = 12;
VPLGI_CONST int kProxySumCount = kProxyCellFirst + kOcclusionCells * kProxyCellSums; // 80
VPLGI_CONST int kProxySumVec4s = kProxySumCount / 4;
VPLGI_CONST int kLightSkinGroupSize = 64;   // invocations per cache in the proxy and occlusion passes
VPLGI_CONST int kLightSkinGroupRows = 32768; // caches per dispatch row (y); more go to z

VPLGI_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(vplgi::shared::GpuLightCache) == 64, "GpuLightCache must match std430");
static_assert(sizeof(vplgi::shared::ProxyLight) == 64, "ProxyLight must match std430");
static_assert(sizeof(vplgi::shared::OcclusionTarget) == 48, "OcclusionTarget must match std430");
static_assert(vplgi::shared::kProxySumCount % 4 == 0, "the proxy sums are read as whole vec4s");
static_assert(sizeof(vplgi::shared::ViewSample) == 32, "ViewSample must match std430");
static_assert(sizeof(vplgi::shared::RSMLayerView) == 96, "RSMLayerView must match std430");
#endif

#endif // VPLGI_SHARED_LIGHTSKIN_GPU_H
