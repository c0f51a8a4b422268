#version 450 core
// Imperfect shadow maps, push (gl/passes/imperfect_shadow_maps.h, glsl/shared/ism.h): fills the
// empty texels of level uLevel from level uLevel + 1 (already pushed). Invocation (t, light): texel t
// (row-major) of the light's finer tile. Each invocation reads and writes only its own finer texel.
#include "../shared/bindings.h"
#include "../shared/ism.h"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(binding = kImageISMMaps, r32ui) uniform uimage2DArray uFiner;
layout(binding = kImageISMCoarser, r32ui) readonly uniform uimage2DArray uCoarser;

uniform int uCount;
uniform int uCoarseSize; // (map size >> (uLevel + 1)) texels
uniform int uTilesPerRow;
uniform float uDepthRange;

void main()
{
    int fineSize = 2 * uCoarseSize;
    int t = int(gl_GlobalInvocationID.x);
    int light = int(gl_GlobalInvocationID.y);
    if (t >= fineSize * fineSize || light >= uCount) return;
    ivec3 tile = shadowAtlasTileFromIndex(light, uTilesPerRow);
    ivec2 finer = ivec2(t % fineSize, t / fineSize);
    ivec3 address = ivec3(tile.xy * fineSize + finer, tile.z);
    float own = uintBitsToFloat(imageLoad(uFiner, address).x);
    if (ismValid(own)) return;
    vec4 coarser = vec4(kVPLNoOccluder);
    vec4 weights = vec4(0.0);
    for (int which = 0; which < 4; ++which) {
        weights[which] = ismPushWeight(finer, which, uCoarseSize);
        if (weights[which] > 0.0) {
            ivec2 c = tile.xy * uCoarseSize + ismPushNeighbour(finer, which);
            coarser[which] = uintBitsToFloat(imageLoad(uCoarser, ivec3(c, tile.z)).x);
        }
    }
    imageStore(uFiner, address, uvec4(floatBitsToUint(ismPush(own, coarser, weights, uDepthRange))));
}
