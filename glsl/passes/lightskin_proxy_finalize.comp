#version 450 core
// LightSkin's proxy lights, second step (lightskin_proxy.comp makes the sums): per cache, the
// chunks' sums added in chunk order, then
//   position  x_p = sum (w/P) x_l / sum (w/P)                       eq. (5)/(13)
//   extent    the bounding-sphere radius from the weighted positions' per-axis deviation
//   flux      Phi_p = 4 pi L_o(c) |x_p - c|^2 / (f_r(c, w, w_i) cos+)  eq. (7)
// with the colours that cancelled left out (lightskin_proxy.comp says which). Visibility starts at
// 1; lightskin_occlusion.comp lowers it.
#include "../shared/bindings.h"
#include "../shared/lightskin.h"
#include "../shared/lightskin_gpu.h"
#include "../lib/frame.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = kBindingLightCaches) readonly buffer Caches { GpuLightCache caches[]; };
layout(std430, binding = kBindingProxySums) readonly buffer Sums { vec4 partialSums[]; };
layout(std430, binding = kBindingProxyLights) writeonly buffer Proxies { ProxyLight proxies[]; };

uniform int uCacheCount;
uniform int uChunks;

void main()
{
    int cache = int(gl_GlobalInvocationID.x);
    if (cache >= uCacheCount) return;
    vec4 sums[kProxySumVec4s];
    for (int v = 0; v < kProxySumVec4s; ++v) sums[v] = vec4(0.0);
    for (int chunk = 0; chunk < uChunks; ++chunk) {
        int at = (cache * uChunks + chunk) * kProxySumVec4s;
        sums[0] += partialSums[at];
        sums[1] += partialSums[at + 1];
        sums[2] += partialSums[at + 2];
        sums[3] += partialSums[at + 3];
        sums[4] += partialSums[at + 4];
    }
    // The 20 sums in the order lightskin_proxy.comp wrote them.
    float s[20] = float[20](sums[0].x, sums[0].y, sums[0].z, sums[0].w, sums[1].x, sums[1].y, sums[1].z, sums[1].w,
                            sums[2].x, sums[2].y, sums[2].z, sums[2].w, sums[3].x, sums[3].y, sums[3].z, sums[3].w,
                            sums[4].x, sums[4].y, sums[4].z, sums[4].w);
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
}
