#version 450 core
// LightSkin's proxy lights (papers/004 section 3 "Proxy Lights Generation", section 4 eq. 13-15):
// one work-group per cache sums the virtual area lights (the N_sVAL selected RSM texels, each
// weighted by 1/P_VAL with P_VAL = N_sVAL p, MATH.md 9.9; or, for lightskin-full, every texel with
// P_VAL = 1) into a diffuse and a glossy proxy point light:
//   position  x_p = sum (w/P) x_l / sum (w/P)                       eq. (5)/(13), weights eq. (6)
//   extent    the per-axis standard deviation of the same weighted positions (section 3 "Occlusion")
//   flux      Phi_p = 4 pi L_o(c) |x_p - c|^2 / (f_r(c, w, w_i) cos+)  eq. (7), L_o from eq. (14)/(15)
// The cache's albedo cancels between eq. (14)/(15) and eq. (7) (MATH.md 9.4), and so does the
// glossy colour and the Phong normalisation (k + 2)/(2 pi): the sums below leave them out.
// For occlusion it also sums the same VALs per cell of the cache's unit disk (lightskin.h,
// occlusionCell; not in the paper), from which the finalize pass makes the occlusion targets.
// This pass makes the sums: one work-group per (cache, chunk of VALs), each invocation takes every
// 64th VAL of the chunk, and the group reduces its sums in shared memory in a fixed tree order
// into ProxySums[cache * chunks + chunk]. lightskin_proxy_finalize.comp adds the chunks of a cache
// in order and turns the sums into the two proxies, so the result is the same on every run and
// thread count. Why chunks: llvmpipe ends a shader invocation's loops after 65535 iterations in
// all (gallivm's LP_MAX_TGSI_LOOP_ITERATIONS, "shared between every loop in a shader"), which one
// loop over a 2048^2 RSM (65536 texels per invocation) exceeds: lightskin-full at 2048^2 silently
// dropped texels before the split. Chunks also give a GPU more work-groups to spread.
#include "../shared/bindings.h"
#define VPLGI_IMPORTANCE_TYPES_ONLY
#include "../shared/importance.h"
#include "../shared/lightskin.h"
#include "../shared/lightskin_gpu.h"
#include "../shared/lightskin_visibility.h"
#include "../shared/normals.h"
#include "../shared/rsm.h"
#include "../shared/tonemap.h"
#include "../lib/frame.glsl"

layout(local_size_x = kLightSkinGroupSize) in;

layout(binding = kUnitRSMSource) uniform sampler2DArray uSource[kRSMAttachmentCount];
layout(std430, binding = kBindingImportanceSamples) readonly buffer Draws { ImportanceSample draws[]; };
layout(std430, binding = kBindingRSMLayerViews) readonly buffer Views { RSMLayerView views[]; };
layout(std430, binding = kBindingRSMLayers) readonly buffer Layers { RSMLayerLight layerLights[]; };
layout(std430, binding = kBindingLightCaches) readonly buffer Caches { GpuLightCache caches[]; };
layout(std430, binding = kBindingProxySums) writeonly buffer Sums { vec4 partialSums[]; }; // kProxySumVec4s per (cache, chunk)
layout(std430, binding = kBindingLightCacheVisibility) readonly buffer VisibilityMaps { uvec2 visibilityMaps[]; };

uniform int uAllTexels;      // 1: every RSM texel (lightskin-full), 0: the selected draws
uniform int uValCount;       // texels (the layers' squares in use) or draws
uniform int uLayers;         // RSM layers
uniform int uSelectionCount; // N_sVAL
uniform int uSize;           // RSM edge [texels]
uniform int uCacheCount;
uniform int uChunkSize;      // VALs per chunk (a multiple of the group size)
uniform int uChunkFirst;     // the chunk of work-group x = 0 (lightskin-full dispatches chunk by chunk)
uniform int uChunks;         // chunks in all
uniform float uEpsilon;      // epsilon_p of eq. (6)
uniform int uFluxWeights;    // weight positions by the VAL's flux luminance too (MATH.md 9.3 option)
uniform int uExactArea;      // MATH.md 9.1's tilted footprint instead of eq. (1)
uniform int uViewCulling;    // 1: no sums for a cache no pixel can use (lightskin.h, lightCacheInView)
uniform float uCullRadius;   // the lookup's search radius d_eps [m]
uniform int uVisibilityMaps;      // 1: weight each VAL by the cache's visibility map (lightskin.visibilityMaps, ours)
uniform int uVisibilityMapSize;   // texels along a map's side
uniform float uVisibilityLift;    // the maps' rays start this far above the cache [m]

#include "../lib/lightskin_val.glsl"

// The visibility of a VAL at xl from cache `cache` (lift the cache's lifted position, frame its
// disk's), as glsl/shared/lightskin_visibility.h and core/lightskin/traced_visibility.cpp take it.
float mapVisibility(int cache, vec3 origin, mat3 frame, vec3 xl, vec3 nl)
{
    // A VAL within the lift of the cache's plane takes the map's rim (visibilityMapFromLocal clamps z).
    vec3 local = transpose(frame) * (xl - origin);
    if (!(dot(local, local) > 0.0)) return 1.0;
    int size = uVisibilityMapSize;
    vec2 uv = visibilityMapFromLocal(local);
    ivec2 first = visibilityMapFirstNeighbour(uv, size);
    vec3 d[4];
    float t[4];
    vec3 n[4];
    for (int k = 0; k < 4; ++k) {
        int x = min(first.x + (k & 1), size - 1), y = min(first.y + (k >> 1), size - 1);
        uvec2 record = visibilityMaps[cache * size * size + y * size + x];
        d[k] = frame * visibilityMapTexelDirection(x, y, size);
        t[k] = uintBitsToFloat(record.x);
        n[k] = octDecode(unpackSnorm2x16(record.y));
    }
    return visibilityMapVisibility(origin, xl, nl, uVisibilityLift, size, visibilityMapBilinear(uv, first, size), d[0], t[0],
                                   n[0], d[1], t[1], n[1], d[2], t[2], n[2], d[3], t[3], n[3]);
}

// The sums per proxy and per occlusion cell (lightskin.h, occlusionCell) in lightskin_gpu.h's order.
shared float sSums[kProxySumCount][kLightSkinGroupSize];

void main()
{
    int cache = int(gl_WorkGroupID.y) + int(gl_WorkGroupID.z) * kLightSkinGroupRows;
    if (cache >= uCacheCount) return; // the whole group: no barrier is skipped by part of it
    if (uViewCulling != 0 && !lightCacheInView(frame.clipFromWorld, caches[cache].positionArea.xyz, uCullRadius))
        return; // the whole group too; the finalize pass does not read its sums
    uint lane = gl_LocalInvocationID.x;
    GpuLightCache c = caches[cache];
    vec3 cp = c.positionArea.xyz;
    vec3 cn = c.normalRoughness.xyz;
    float alpha = max(c.normalRoughness.w * c.normalRoughness.w, 0.002);
    float k = phongExponentFromRoughness(alpha);
    vec3 view = normalize(frame.cameraPosition.xyz - cp);

    mat3 diskFrame = occlusionFrame(cn);
    float sums[kProxySumCount];
    for (int s = 0; s < kProxySumCount; ++s) sums[s] = 0.0;
    int chunk = uChunkFirst + int(gl_WorkGroupID.x);
    int chunkEnd = min((chunk + 1) * uChunkSize, uValCount);
    // lightskin-full: VAL j is texel j of the layers' squares laid end to end, row by row (a layer's
    // square is its RSMLayerView's info.z wide: rsm.size, or less for cube faces within one light's
    // budget, rsm_pass.h RSMCubeFaces); j only grows, so the layer is found by walking forwards.
    int layer = 0, layerStart = 0, side = uAllTexels != 0 ? int(views[0].info.z) : 0;
    for (int j = chunk * uChunkSize + int(lane); j < chunkEnd; j += kLightSkinGroupSize) {
        ivec3 texel;
        float selection; // P_VAL: the expected number of times the VAL is drawn
        if (uAllTexels != 0) {
            while (j >= layerStart + side * side && layer + 1 < uLayers) {
                layerStart += side * side;
                side = int(views[++layer].info.z);
            }
            int i = j - layerStart;
            texel = ivec3(i % side, i / side, layer);
            selection = 1.0;
        } else {
            ImportanceSample d = draws[j];
            if (d.x < 0 || !(d.probability > 0.0)) continue; // also a NaN probability
            texel = ivec3(d.x % uSize, d.y, d.x / uSize);
            selection = float(uSelectionCount) * d.probability;
        }
        LightSkinVAL val = readLightSkinVAL(texel);
        if (!val.valid) continue;
        vec3 xl = val.position, nl = val.normal, flux = val.flux;
        float area = uExactArea != 0 ? val.areaTilted : val.area;
        vec3 v = xl - cp;
        float d2 = dot(v, v);
        if (d2 <= 0.0 || area <= 0.0) continue;
        vec3 toLight = v * inversesqrt(d2);
        float formFactor = diskFormFactor(area, dot(nl, -toLight), dot(cn, toLight), d2);
        // Eq. (14)/(15) without the receiver's colour: Phi cos cos / (A + pi d^2) / P_VAL.
        // lightskin.visibilityMaps (ours): the VAL's light as far as the cache's map lets it through.
        float visible = uVisibilityMaps != 0 ? mapVisibility(cache, cp + uVisibilityLift * cn, diskFrame, xl, nl) : 1.0;
        if (!(visible > 0.0)) continue;
        formFactor *= visible;
        vec3 radiance = flux * (formFactor / area) / selection;
        float cosMirror = dot(view, mirrorDirection(toLight, cn));
        float lobe = phongLobe(cosMirror, k); // cos+^k theta_e
        float base = (uFluxWeights != 0 ? luminanceRec709(flux) : 1.0) / selection;
        float wd = base * proxyWeightDiffuse(formFactor, uEpsilon);
        float wg = base * proxyWeightGlossy(formFactor, cosMirror, k, uEpsilon);
        // Numeric guard: a near-zero P_VAL or area, or an overflowed RSM flux, would make this VAL
        // infinitely strong and the cache's proxy NaN (inf / inf in the finalize pass): dropped.
        if (any(isnan(radiance)) || any(isinf(radiance)) || isnan(wd) || isinf(wd) || isnan(wg) || isinf(wg) ||
            any(isnan(v)) || any(isinf(v)))
            continue;
        sums[0] += wd;
        sums[1] += wd * v.x; sums[2] += wd * v.y; sums[3] += wd * v.z;
        sums[4] += wd * v.x * v.x; sums[5] += wd * v.y * v.y; sums[6] += wd * v.z * v.z;
        sums[7] += radiance.r; sums[8] += radiance.g; sums[9] += radiance.b;
        sums[10] += wg;
        sums[11] += wg * v.x; sums[12] += wg * v.y; sums[13] += wg * v.z;
        sums[14] += wg * v.x * v.x; sums[15] += wg * v.y * v.y; sums[16] += wg * v.z * v.z;
        sums[17] += radiance.r * lobe; sums[18] += radiance.g * lobe; sums[19] += radiance.b * lobe;
        // The occlusion cells' sums feed only the double projection's targets: none with the maps.
        if (uVisibilityMaps == 0) {
            int at = kProxyCellFirst + occlusionCell(toLight, diskFrame) * kProxyCellSums;
            float radianceLuminance = luminanceRec709(radiance);
            vec2 disk = vec2(dot(toLight, diskFrame[0]), dot(toLight, diskFrame[1]));
            float distance = sqrt(d2);
            sums[at] += wd;
            sums[at + 1] += wd * disk.x; sums[at + 2] += wd * disk.y;
            sums[at + 3] += wd * disk.x * disk.x; sums[at + 4] += wd * disk.y * disk.y;
            sums[at + 5] += wd * v.x; sums[at + 6] += wd * v.y; sums[at + 7] += wd * v.z;
            sums[at + 8] += wd * distance;
            sums[at + 9] += wd * d2;
            sums[at + 10] += radianceLuminance;
            sums[at + 11] += radianceLuminance * lobe; // cos^k theta_e: the glossy proxy's share
        }
    }
    for (int s = 0; s < kProxySumCount; ++s) sSums[s][lane] = sums[s];
    barrier();
    for (uint stride = uint(kLightSkinGroupSize) / 2u; stride > 0u; stride /= 2u) {
        if (lane < stride)
            for (int s = 0; s < kProxySumCount; ++s) sSums[s][lane] += sSums[s][lane + stride];
        barrier();
    }
    if (lane != 0u) return;
    int chunks = uChunks;
    int at = (cache * chunks + chunk) * kProxySumVec4s;
    for (int v = 0; v < kProxySumVec4s; ++v)
        partialSums[at + v] = vec4(sSums[4 * v][0], sSums[4 * v + 1][0], sSums[4 * v + 2][0], sSums[4 * v + 3][0]);
}
