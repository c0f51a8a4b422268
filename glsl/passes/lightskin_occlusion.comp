#version 450 core
// LightSkin's occlusion by double projection (papers/004 section 3 "Occlusion"; Lensing, Broll
// 2013b): per cache, each proxy light's bounding sphere and the disks of the other caches between
// the cache and the proxy are projected onto the unit hemisphere and down onto the unit disk
// around the cache's normal (a projected solid angle, i.e. pi times the form factor), turned into
// squares of equal area, and the overlap of the cache squares with the proxy's square is the
// occluded fraction (clamped to 1). The result multiplies the proxy's flux (its w).
// With lightskin.occlusionCells (the default; not in the paper) the light is instead the footprint
// of the VALs in each of five cells of the cache's unit disk, an occluder blocks the share of a
// cell's light behind it, and a proxy's visibility is the radiance-weighted mean over the cells
// (glsl/shared/lightskin.h, occlusionCell, says why). lightskin_proxy_finalize.comp writes the
// targets (OcclusionTarget) for either.
// One work-group per cache, every 64th other cache per invocation, a fixed-order reduction.
#include "../shared/bindings.h"
#include "../shared/lightskin.h"
#include "../shared/lightskin_gpu.h"
#include "../lib/frame.glsl"

layout(local_size_x = kLightSkinGroupSize) in;

layout(std430, binding = kBindingLightCaches) readonly buffer Caches { GpuLightCache caches[]; };
layout(std430, binding = kBindingProxyLights) buffer Proxies { ProxyLight proxies[]; };
layout(std430, binding = kBindingOcclusionTargets) readonly buffer Targets { OcclusionTarget targets[]; };
layout(std430, binding = kBindingCacheRadiance) readonly buffer Radiance { float cacheRadiance[]; };

uniform int uCacheCount;
uniform int uOccluderLight; // 1: an occluder's own reflected light is not removed (lightskin.occluderLight)
uniform int uViewCulling;   // 1: no occlusion for a cache no pixel can use (it still occludes the others)
uniform float uCullRadius;  // the lookup's search radius d_eps [m]

shared float sOverlap[kOcclusionCells][kLightSkinGroupSize];

void main()
{
    int cache = int(gl_WorkGroupID.y) + int(gl_WorkGroupID.z) * kLightSkinGroupRows;
    if (cache >= uCacheCount) return; // the whole group
    uint lane = gl_LocalInvocationID.x;
    GpuLightCache c = caches[cache];
    vec3 cp = c.positionArea.xyz;
    vec3 cn = c.normalRoughness.xyz;
    if (uViewCulling != 0 && !lightCacheInView(frame.clipFromWorld, cp, uCullRadius)) return; // the whole group
    mat3 diskFrame = occlusionFrame(cn);
    // What occluders are tested against: one target per occlusion cell, or the two proxies'
    // spheres (the paper's); lightskin_proxy_finalize.comp writes them.
    vec3 centres[kOcclusionCells];
    vec2 shares[kOcclusionCells];
    vec3 squares[kOcclusionCells]; // xy centre on the unit disk, z area
    vec2 depths[kOcclusionCells];  // the light's distance: mean and spread [m] (spread 0: a step)
    float far2[kOcclusionCells];   // occluders count nearer than this [m^2]
    float perLight[kOcclusionCells]; // the cell's square area over its light (irradiance luminance)
    for (int g = 0; g < kOcclusionCells; ++g) {
        OcclusionTarget target = targets[cache * kOcclusionCells + g];
        centres[g] = target.centre.xyz;
        shares[g] = target.depthShares.zw;
        squares[g] = target.square.xyz;
        depths[g] = target.depthShares.xy;
        float far = depths[g].x + 3.0 * depths[g].y;
        far2[g] = shares[g] != vec2(0.0) ? far * far : 0.0; // empty: no occluder
        perLight[g] = shares[g].x > 0.0 ? squares[g].z / shares[g].x : 0.0;
    }

    float overlap[kOcclusionCells];
    for (int g = 0; g < kOcclusionCells; ++g) overlap[g] = 0.0;
    for (int j = int(lane); j < uCacheCount; j += kLightSkinGroupSize) {
        GpuLightCache o = caches[j];
        // The second cache of a double-sided pair sits on its twin with the same disk: one of them
        // occludes (not in the paper; both would count the surface twice).
        if (o.specular.w != 0.0) continue;
        vec3 op = o.positionArea.xyz;
        vec3 on = o.normalRoughness.xyz;
        // A disk can only block the segment from the cache to its light if the segment crosses the
        // disk's plane: the cache and the light's centre on opposite sides (not in the paper;
        // without it the floor between a lit floor patch and a wall occludes the wall's light,
        // docs/lightskin.md), each by more than kOccluderPlaneMargin of the distance to the disk
        // (a light on the floor's own plane is not behind it: float noise decided that side and
        // took 7% of an open wall's light).
        float cacheSide = dot(on, cp - op);
        float distance = length(op - cp);
        float margin = kOccluderPlaneMargin * distance;
        bool anyCandidate = false;
        bool candidates[kOcclusionCells];
        for (int g = 0; g < kOcclusionCells; ++g) {
            float lightSide = dot(on, centres[g] - op);
            candidates[g] = isOccluderCandidate(cache, cp, cn, j, op, far2[g]) && cacheSide * lightSide < 0.0 &&
                            min(abs(cacheSide), abs(lightSide)) > margin;
            anyCandidate = anyCandidate || candidates[g];
        }
        if (!anyCandidate) continue;
        vec3 square = projectDiskToUnitDisk(op - cp, on, o.positionArea.w, diskFrame);
        // With lightskin.occluderLight (not in the paper): an occluder the light reaches reflects
        // light of its own towards the cache (when its front faces it), which is among the cell's
        // VALs and not behind it. Its radiance L over the overlap (the unit disk's area is the
        // projected solid angle) is irradiance L a, the share L a / E of the cell's light E; the
        // occluder removes its share of what lies behind it, less that, never less than nothing
        // (each occluder on its own: one lit occluder gives back only what it took).
        float ownRadiance = uOccluderLight != 0 && cacheSide > 0.0 ? cacheRadiance[j] : 0.0;
        for (int g = 0; g < kOcclusionCells; ++g)
            if (candidates[g])
                overlap[g] += squareOverlap(squares[g], square) *
                              max(occlusionBehind(distance, depths[g]) - ownRadiance * perLight[g], 0.0);
    }
    for (int g = 0; g < kOcclusionCells; ++g) sOverlap[g][lane] = overlap[g];
    barrier();
    for (uint stride = uint(kLightSkinGroupSize) / 2u; stride > 0u; stride /= 2u) {
        if (lane < stride)
            for (int g = 0; g < kOcclusionCells; ++g) sOverlap[g][lane] += sOverlap[g][lane + stride];
        barrier();
    }
    if (lane != 0u) return;
    // Each proxy's visibility: the share-weighted mean of its targets' 1 - occlusion.
    vec2 visible = vec2(0.0), total = vec2(0.0);
    for (int g = 0; g < kOcclusionCells; ++g) {
        float targetVisible = 1.0 - occlusionFromOverlap(sOverlap[g][0], squares[g].z);
        visible += shares[g] * targetVisible;
        total += shares[g];
    }
    proxies[cache].diffuseFlux.w = total.x > 0.0 ? visible.x / total.x : 1.0;
    proxies[cache].glossyFlux.w = total.y > 0.0 ? visible.y / total.y : 1.0;
}
