#version 450 core
// Imperfect shadow maps, pull (gl/passes/imperfect_shadow_maps.h, glsl/shared/ism.h): level
// uLevel + 1 of every map from level uLevel. Invocation (t, light): texel t (row-major) of the
// light's coarser tile. The maps are r32f; the image units see their bits as r32ui (the splat needs
// atomics, and the formats are compatible by size).
#include "../shared/bindings.h"
#include "../shared/ism.h"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(binding = kImageISMMaps, r32ui) readonly uniform uimage2DArray uFiner;
layout(binding = kImageISMCoarser, r32ui) writeonly uniform uimage2DArray uCoarser;

uniform int uCount;
uniform int uCoarseSize; // (map size >> (uLevel + 1)) texels
uniform int uTilesPerRow;
uniform float uDepthRange;

float load(ivec3 texel)
{
    return uintBitsToFloat(imageLoad(uFiner, texel).x);
}

void main()
{
    int t = int(gl_GlobalInvocationID.x);
    int light = int(gl_GlobalInvocationID.y);
    if (t >= uCoarseSize * uCoarseSize || light >= uCount) return;
    ivec3 tile = shadowAtlasTileFromIndex(light, uTilesPerRow);
    ivec2 coarse = ivec2(t % uCoarseSize, t / uCoarseSize);
    ivec2 fine = tile.xy * (2 * uCoarseSize) + 2 * coarse;
    vec4 finer = vec4(load(ivec3(fine, tile.z)), load(ivec3(fine + ivec2(1, 0), tile.z)),
                      load(ivec3(fine + ivec2(0, 1), tile.z)), load(ivec3(fine + ivec2(1, 1), tile.z)));
    float value = ismPull(finer, uDepthRange);
    imageStore(uCoarser, ivec3(tile.xy * uCoarseSize + coarse, tile.z), uvec4(floatBitsToUint(value)));
}
