#version 450 core
// LightSkin's proxy lights, second step (lightskin_proxy.comp makes the sums): per cache, the
// chunks' sums added in chunk order, then
//   position  x_p = sum (w/P) x_l / sum (w/P)                       eq. (5)/(13)
//   extent    the bounding-sphere radius from the weighted positions' per-axis deviation
//   flux      Phi_p = 4 pi L_o(c) |x_p - c|^2 / (f_r(c, w, w_i) cos+)  eq. (7)
// with the colours that cancelled left out (lightskin_proxy.comp says which). Visibility starts at
// 1; lightskin_occlusion.comp lowers it, testing occluders against the targets written here: one per
// occlusion cell (uOcclusionCells, not in the paper; lightskin.h says why) or the two proxies'
// spheres (the paper).
#include "../shared/bindings.h"
#include "../shared/lightskin.h"
#include "../shared/lightskin_gpu.h"
#include "../shared/normals.h"
#include "../shared/rsm.h"
#include "../shared/tonemap.h"
#include "../lib/frame.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = kBindingLightCaches) readonly buffer Caches { GpuLightCache caches[]; };
layout(std430, binding = kBindingProxySums) readonly buffer Sums { vec4 partialSums[]; };
layout(std430, binding = kBindingProxyLights) writeonly buffer Proxies { ProxyLight proxies[]; };
layout(std430, binding = kBindingOcclusionTargets) writeonly buffer Targets { OcclusionTarget targets[]; };
layout(std430, binding = kBindingCacheRadiance) writeonly buffer Radiance { float cacheRadiance[]; };
layout(binding = kUnitRSMSource) uniform sampler2DArray uSource[kRSMAttachmentCount];
layout(std430, binding = kBindingRSMLayerViews) readonly buffer Views { RSMLayerView views[]; };
layout(std430, binding = kBindingRSMLayers) readonly buffer Layers { RSMLayerLight layerLights[]; };
#include "../lib/lightskin_val.glsl"

uniform int uCacheCount;
uniform int uChunks;
uniform int uOcclusionCells; // 1: a target per occlusion cell; 0: the paper's, the proxies' spheres
uniform int uOwnRadiance;    // 1: the occlusion pass reads each cache's own radiance (lightskin.occluderLight)
uniform int uLayers;         // RSM layers
uniform int uViewCulling;    // 1: a cache no pixel can use gets no light (its sums were not made)
uniform float uCullRadius;   // the lookup's search radius d_eps [m]

// The light the cache's own surface reflects, as luminance of its radiance [W/(m^2 sr)] (not in the
// paper; lightskin_occlusion.comp's occluder light): the cache projected into each RSM layer; where
// the texel there shows the cache's own surface (facing its way, the cache within a texel's size of
// its plane and two footprints of it: not a surface that shadows the cache, nor the other face of a
// thin wall), that texel's VAL exitance over pi. 0 where no layer sees the cache lit.
float ownRadiance(vec3 cp, vec3 cn)
{
    for (int layer = 0; layer < uLayers; ++layer) {
        RSMLayerView view = views[layer];
        vec4 clip = mat4(view.clip0, view.clip1, view.clip2, view.clip3) * vec4(cp, 1.0);
        if (!(clip.w > 0.0)) continue;
        vec3 ndc = clip.xyz / clip.w;
        if (any(greaterThan(abs(ndc), vec3(1.0)))) continue;
        int layerSize = int(view.info.z); // the square the layer's view was drawn into (RSMCubeFaces)
        ivec2 xy = clamp(ivec2((ndc.xy * 0.5 + 0.5) * float(layerSize)), ivec2(0), ivec2(layerSize - 1));
        LightSkinVAL val = readLightSkinVAL(ivec3(xy, layer));
        if (!val.valid || dot(val.normal, cn) < 0.5 || abs(dot(val.normal, cp - val.position)) > sqrt(val.area) ||
            distance(val.position, cp) > 2.0 * sqrt(val.areaTilted))
            continue;
        return luminanceRec709(val.flux) / (kPi * val.areaTilted);
    }
    return 0.0;
}

void main()
{
    int cache = int(gl_GlobalInvocationID.x);
    if (cache >= uCacheCount) return;
    // The sums in the order lightskin_proxy.comp wrote them (lightskin_gpu.h).
    float s[kProxySumCount];
    for (int i = 0; i < kProxySumCount; ++i) s[i] = 0.0;
    bool used = uViewCulling == 0 || lightCacheInView(frame.clipFromWorld, caches[cache].positionArea.xyz, uCullRadius);
    for (int chunk = 0; used && chunk < uChunks; ++chunk) {
        int at = (cache * uChunks + chunk) * kProxySumVec4s;
        for (int v = 0; v < kProxySumVec4s; ++v) {
            vec4 four = partialSums[at + v];
            for (int i = 0; i < 4; ++i) s[4 * v + i] += four[i];
        }
    }
    // Numeric guard: the proxy pass drops non-finite VALs, but finite ones can still overflow a sum
    // (an RSM of absurd flux); inf / inf would make the cache's proxies NaN and every pixel that
    // interpolates them. Such a cache passes on no light.
    bool finite = true;
    for (int i = 0; i < kProxySumCount; ++i) finite = finite && !isnan(s[i]) && !isinf(s[i]);
    if (!finite)
        for (int i = 0; i < kProxySumCount; ++i) s[i] = 0.0;
    GpuLightCache c = caches[cache];
    vec3 cp = c.positionArea.xyz;
    vec3 cn = c.normalRoughness.xyz;
    float alpha = max(c.normalRoughness.w * c.normalRoughness.w, 0.002);
    float k = phongExponentFromRoughness(alpha);
    vec3 view = normalize(frame.cameraPosition.xyz - cp);

    ProxyLight proxy;
    for (int p = 0; p < 2; ++p) {
        int o = p * 10;
        float w = s[o];
        vec3 offsetSum = vec3(s[o + 1], s[o + 2], s[o + 3]);
        vec3 squaredOffsetSum = vec3(s[o + 4], s[o + 5], s[o + 6]);
        vec3 mean = w > 0.0 ? offsetSum / w : cn; // no VAL at all (epsilon 0): 1 m above the cache, no flux
        vec3 radiance = vec3(s[o + 7], s[o + 8], s[o + 9]);
        float distance2 = dot(mean, mean);
        vec3 toProxy = distance2 > 0.0 ? mean * inversesqrt(distance2) : cn;
        float cosCache = dot(cn, toProxy);
        // f_r of eq. (7) without the colours that cancelled: 1 for the diffuse proxy, cos^k theta_e
        // towards the proxy for the glossy one.
        float brdf = p == 0 ? 1.0 : phongLobe(dot(view, mirrorDirection(toProxy, cn)), k);
        vec3 flux = proxyFluxFromRadiance(radiance, distance2, vec3(brdf), cosCache);
        if (any(isinf(flux)) || any(isnan(flux))) flux = vec3(0.0); // eq. (7) overflowed: no light
        vec4 positionRadius = vec4(cp + mean, proxySphereRadius(w, offsetSum, squaredOffsetSum));
        if (p == 0) {
            proxy.diffusePositionRadius = positionRadius;
            proxy.diffuseFlux = vec4(flux, 1.0);
        } else {
            proxy.glossyPositionRadius = positionRadius;
            proxy.glossyFlux = vec4(flux, 1.0);
        }
    }
    proxies[cache] = proxy;
    float own = uOwnRadiance != 0 ? ownRadiance(cp, cn) : 0.0;
    cacheRadiance[cache] = isnan(own) || isinf(own) ? 0.0 : own;

    mat3 diskFrame = occlusionFrame(cn);
    for (int g = 0; g < kOcclusionCells; ++g) {
        OcclusionTarget target;
        target.square = vec4(0.0);
        target.centre = vec4(cp + cn, 0.0);
        target.depthShares = vec4(0.0);
        if (uOcclusionCells != 0) {
            int o = kProxyCellFirst + g * kProxyCellSums;
            float w = s[o];
            if (w > 0.0) {
                target.square = vec4(occlusionCellSquare(w, vec2(s[o + 1], s[o + 2]), vec2(s[o + 3], s[o + 4])), 0.0);
                target.centre = vec4(cp + vec3(s[o + 5], s[o + 6], s[o + 7]) / w, 0.0);
                target.depthShares = vec4(occlusionCellDepth(w, s[o + 8], s[o + 9]), s[o + 10], s[o + 11]);
            }
        } else if (g < 2) {
            // The paper: the proxy's bounding sphere; occluders between the cache and its near side,
            // not inside it: the caches on the lit surfaces that the proxy stands for are its light,
            // not its blockers (not in the paper; docs/lightskin.md has the measurement behind it).
            vec4 sphere = g == 0 ? proxy.diffusePositionRadius : proxy.glossyPositionRadius;
            vec3 toSphere = sphere.xyz - cp;
            target.square = vec4(projectSphereToUnitDisk(toSphere, sphere.w, diskFrame), 0.0);
            target.centre = vec4(sphere.xyz, 0.0);
            target.depthShares = vec4(max(length(toSphere) - sphere.w, 0.0), 0.0, g == 0 ? 1.0 : 0.0, g == 0 ? 0.0 : 1.0);
        }
        targets[cache * kOcclusionCells + g] = target;
    }
}
