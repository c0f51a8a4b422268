#version 450 core
// LightSkin's occlusion by double projection (papers/004 section 3 "Occlusion"; Lensing, Broll
// 2013b): per cache, each proxy light's bounding sphere and the disks of the other caches between
// the cache and the proxy are projected onto the unit hemisphere and down onto the unit disk
// around the cache's normal (a projected solid angle, i.e. pi times the form factor), turned into
// squares of equal area, and the overlap of the cache squares with the proxy's square is the
// occluded fraction (clamped to 1). The result multiplies the proxy's flux (its w).
// One work-group per cache, every 64th other cache per invocation, a fixed-order reduction.
#include "../shared/bindings.h"
#include "../shared/lightskin.h"
#include "../shared/lightskin_gpu.h"

layout(local_size_x = kLightSkinGroupSize) in;

layout(std430, binding = kBindingLightCaches) readonly buffer Caches { GpuLightCache caches[]; };
layout(std430, binding = kBindingProxyLights) buffer Proxies { ProxyLight proxies[]; };

uniform int uCacheCount;

shared float sOverlap[2][kLightSkinGroupSize];

void main()
{
    int cache = int(gl_WorkGroupID.y) + int(gl_WorkGroupID.z) * kLightSkinGroupRows;
    if (cache >= uCacheCount) return; // the whole group
    uint lane = gl_LocalInvocationID.x;
    GpuLightCache c = caches[cache];
    vec3 cp = c.positionArea.xyz;
    vec3 cn = c.normalRoughness.xyz;
    ProxyLight proxy = proxies[cache];
    mat3 diskFrame = occlusionFrame(cn);
    vec4 spheres[2] = vec4[2](proxy.diffusePositionRadius, proxy.glossyPositionRadius);
    vec3 proxySquares[2]; // xy centre on the unit disk, z area
    float proxyDistance2[2];
    for (int p = 0; p < 2; ++p) {
        vec3 toProxy = spheres[p].xyz - cp;
        proxySquares[p] = projectSphereToUnitDisk(toProxy, spheres[p].w, diskFrame);
        // Occluders lie between the cache and the near side of the proxy's sphere, not inside it:
        // the caches on the lit surfaces that the proxy stands for are its light, not its blockers
        // (not in the paper; docs/lightskin.md has the measurement behind it).
        float nearSide = max(length(toProxy) - spheres[p].w, 0.0);
        proxyDistance2[p] = nearSide * nearSide;
    }

    float overlap[2] = float[2](0.0, 0.0);
    for (int j = int(lane); j < uCacheCount; j += kLightSkinGroupSize) {
        GpuLightCache o = caches[j];
        bool candidates[2];
        // A disk can only block the segment from the cache to the proxy if the segment crosses the
        // disk's plane: the cache and the proxy's centre on opposite sides (not in the paper; without
        // it the floor between a lit floor patch and a wall occludes the wall's light,
        // docs/lightskin.md).
        vec3 on = o.normalRoughness.xyz;
        float cacheSide = dot(on, cp - o.positionArea.xyz);
        for (int p = 0; p < 2; ++p)
            candidates[p] = isOccluderCandidate(cache, cp, cn, j, o.positionArea.xyz, proxyDistance2[p]) &&
                            cacheSide * dot(on, spheres[p].xyz - o.positionArea.xyz) < 0.0;
        if (!candidates[0] && !candidates[1]) continue;
        vec3 square = projectDiskToUnitDisk(o.positionArea.xyz - cp, o.normalRoughness.xyz, o.positionArea.w, diskFrame);
        for (int p = 0; p < 2; ++p)
            if (candidates[p]) overlap[p] += squareOverlap(proxySquares[p], square);
    }
    sOverlap[0][lane] = overlap[0];
    sOverlap[1][lane] = overlap[1];
    barrier();
    for (uint stride = uint(kLightSkinGroupSize) / 2u; stride > 0u; stride /= 2u) {
        if (lane < stride) {
            sOverlap[0][lane] += sOverlap[0][lane + stride];
            sOverlap[1][lane] += sOverlap[1][lane + stride];
        }
        barrier();
    }
    if (lane != 0u) return;
    proxies[cache].diffuseFlux.w = 1.0 - occlusionFromOverlap(sOverlap[0][0], proxySquares[0].z);
    proxies[cache].glossyFlux.w = 1.0 - occlusionFromOverlap(sOverlap[1][0], proxySquares[1].z);
}
