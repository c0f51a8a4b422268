#version 450 core
// LightSkin's interpolation and shading (papers/004 section 3 "Interpolation using the Proxy
// Lights"): every pixel finds its <= 16 nearest caches (glsl/shared/light_cache_lookup.h: per
// pixel, not per vertex; gl/techniques/lightskin_technique.h says why), weights them by eq. (8)
//   w'_d = (1 - |x - c| / d_max)^p (n_x . n_c)+,   w'_g = (1 - |x - c| / d_max)^p (r_x . r_c)+
// and interpolates the proxies' positions and (occluded) fluxes by eq. (9). The interpolated
// proxies are point lights moved along with the pixel: L = f_r(x) Phi_v / (4 pi) cos+ / |x_v - x|^2,
// the diffuse proxy with the pixel's Lambert lobe and the glossy one with its GGX lobe (glTF's
// BRDF, glsl/shared/brdf.h). r_x and r_c mirror the direction towards the cache's glossy proxy at
// the pixel's and the cache's normal (the paper's "incident light direction mirrored at the
// surface normal").
#include "../lib/frame.glsl"
#include "../shared/brdf.h"
#include "../shared/lightskin.h"
#include "../shared/lightskin_gpu.h"
#include "../shared/normals.h"

layout(binding = kUnitGBufferPosition) uniform sampler2D uPosition;
layout(binding = kUnitGBufferNormal) uniform sampler2D uNormal;
layout(binding = kUnitGBufferBaseColor) uniform sampler2D uBaseColor;
layout(binding = kUnitGBufferEmission) uniform sampler2D uEmission;
layout(binding = kUnitGBufferSurfaceNormals) uniform sampler2D uSurfaceNormals;

layout(std430, binding = kBindingLightCaches) readonly buffer Caches { GpuLightCache caches[]; };
layout(std430, binding = kBindingLightCacheCells) readonly buffer Cells { uvec4 cellSlots[]; };
layout(std430, binding = kBindingLightCacheIndices) readonly buffer Indices { uint cacheIndices[]; };
layout(std430, binding = kBindingProxyLights) readonly buffer Proxies { ProxyLight proxies[]; };
layout(std430, binding = kBindingLightCacheReach) readonly buffer Reach { uvec4 reach[]; };

uvec4 lightCacheSlot(int slot) { return cellSlots[slot]; }
uint lightCacheIndex(int i) { return cacheIndices[i]; }
vec3 lightCachePosition(int cache) { return caches[cache].positionArea.xyz; }
vec3 lightCacheNormal(int cache) { return caches[cache].normalRoughness.xyz; }
uvec4 lightCacheReach(int cache) { return reach[cache]; }
#include "../shared/light_cache_lookup.h"

uniform vec3 uGridOrigin;
uniform float uGridCellSize;
uniform uint uGridSlotMask; // the cells' hash table: slots - 1
uniform int uGridMaxProbe;
uniform float uExponent; // p of eq. (8)
uniform int uReach;      // 1: each cache's reach limits its points (lightskin.reach; not in the paper)
uniform int uFixedRadius; // 1: d_max of eq. (8) is the search radius (lightskin.fixedRadius; not in the paper)

layout(location = 0) out vec4 outRadiance;

// One interpolated proxy as a point light: f_r Phi / (4 pi) cos+ / d^2 (MATH.md 9.5), with the
// pixel's Lambert lobe (diffuse proxy) or its GGX lobe (glossy proxy).
// n_g, the G-buffer's geometric normal: a light below the triangle's plane (n_g . w <= 0) adds
// nothing, as the path tracer drops a direction below the geometric surface (issue "Every light
// type in the RSM techniques", part 2; the shading normal alone let a normal map tilt light in).
vec3 shadeProxy(vec3 x, vec3 n, vec3 ng, vec3 v, vec3 diffuse, vec3 f0, float roughness, vec3 proxyPosition, vec3 flux, bool glossy)
{
    vec3 toProxy = proxyPosition - x;
    float d2 = dot(toProxy, toProxy);
    if (!(d2 > 0.0) || flux == vec3(0.0) || dot(ng, toProxy) <= 0.0) return vec3(0.0);
    vec3 l = toProxy * inversesqrt(d2);
    vec3 brdf = glossy ? evaluateBRDFCoefficients(vec3(0.0), f0, roughness, n, v, l)
                       : evaluateBRDFCoefficients(diffuse, vec3(0.0), 1.0, n, v, l);
    return pointLightRadiance(flux, d2, brdf, dot(n, l));
}

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 position = texelFetch(uPosition, pixel, 0);
    outRadiance = vec4(0.0);
    if (position.w == 0.0) return;
    vec4 normalRoughness = texelFetch(uNormal, pixel, 0);
    vec4 baseMetallic = texelFetch(uBaseColor, pixel, 0);
    float specularFactor = texelFetch(uEmission, pixel, 0).a;
    vec3 x = position.xyz;
    vec3 n = normalize(normalRoughness.xyz);
    // The geometric normal for the below-the-surface test (shadeProxy), the interpolated one
    // (without the normal map) for the caches' lookup and eq. (8)'s weights, which compare it with
    // the caches' geometric normals: a normal map's bumps no longer decide which caches a pixel takes.
    vec4 surfaceNormals = texelFetch(uSurfaceNormals, pixel, 0);
    vec3 ng = octDecode(surfaceNormals.xy);
    vec3 ni = octDecode(surfaceNormals.zw);
    vec3 v = normalize(frame.cameraPosition.xyz - x);
    vec3 diffuse = (1.0 - baseMetallic.a) * baseMetallic.rgb;
    vec3 f0 = mix(vec3(0.04 * specularFactor), baseMetallic.rgb, baseMetallic.a);

    LightCacheNeighbours near;
    findNearestLightCaches(uGridOrigin, uGridCellSize, uGridSlotMask, uGridMaxProbe, x, ni, kMaxLightCacheNeighbours,
                           uReach != 0, near);
    if (near.count == 0) return;
    // d_max of eq. (8): the paper's farthest cache of the set moves when a cache enters or leaves the
    // set (a seam between pixels with different sets); the fixed search radius does not.
    float maxDistance = uFixedRadius != 0 ? uGridCellSize : sqrt(near.distance2[near.count - 1]);
    vec3 sumPositionD = vec3(0.0), sumFluxD = vec3(0.0), sumPositionG = vec3(0.0), sumFluxG = vec3(0.0);
    float sumD = 0.0, sumG = 0.0;
    for (int i = 0; i < near.count; ++i) {
        int index = near.index[i];
        ProxyLight p = proxies[index];
        // Numeric guard: a non-finite proxy (whatever wrote it) is skipped, not spread over the pixels.
        if (any(isnan(p.diffusePositionRadius)) || any(isinf(p.diffusePositionRadius)) || any(isnan(p.diffuseFlux)) ||
            any(isinf(p.diffuseFlux)) || any(isnan(p.glossyPositionRadius)) || any(isinf(p.glossyPositionRadius)) ||
            any(isnan(p.glossyFlux)) || any(isinf(p.glossyFlux)))
            continue;
        vec3 cp = caches[index].positionArea.xyz;
        vec3 cn = caches[index].normalRoughness.xyz;
        // With the paper's d_max, a single cache, or several at the same distance, would all get weight 0:
        // weigh them equally (distance 0; not in the paper).
        float distance = uFixedRadius == 0 && near.distance2[0] >= near.distance2[near.count - 1] ? 0.0 : sqrt(near.distance2[i]);
        float wd = interpolationWeight(distance, maxDistance, uExponent, dot(ni, cn));
        vec3 gp = p.glossyPositionRadius.xyz;
        vec3 rx = mirrorDirection(normalize(gp - x), ni), rc = mirrorDirection(normalize(gp - cp), cn);
        float wg = interpolationWeight(distance, maxDistance, uExponent, dot(rx, rc));
        sumD += wd;
        sumPositionD += wd * p.diffusePositionRadius.xyz;
        sumFluxD += wd * p.diffuseFlux.rgb * p.diffuseFlux.w;
        sumG += wg;
        sumPositionG += wg * gp;
        sumFluxG += wg * p.glossyFlux.rgb * p.glossyFlux.w;
    }
    vec3 radiance = vec3(0.0);
    if (sumD > 0.0)
        radiance += shadeProxy(x, n, ng, v, diffuse, f0, normalRoughness.w, sumPositionD / sumD, sumFluxD / sumD, false);
    if (sumG > 0.0)
        radiance += shadeProxy(x, n, ng, v, diffuse, f0, normalRoughness.w, sumPositionG / sumG, sumFluxG / sumG, true);
    outRadiance = vec4(radiance, 1.0);
}
