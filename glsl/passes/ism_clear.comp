#version 450 core
// Imperfect shadow maps (gl/passes/imperfect_shadow_maps.h): empties level 0 of the maps of lights
// 0 .. uCount-1 before the splat. Invocation (t, light): texel t (row-major) of the light's tile.
#include "../shared/bindings.h"
#include "../shared/ism.h"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(binding = kImageISMMaps, r32ui) writeonly uniform uimage2DArray uMaps;

uniform int uCount;
uniform int uMapSize;
uniform int uTilesPerRow;

void main()
{
    int t = int(gl_GlobalInvocationID.x);
    int light = int(gl_GlobalInvocationID.y);
    if (t >= uMapSize * uMapSize || light >= uCount) return;
    ivec3 tile = shadowAtlasTileFromIndex(light, uTilesPerRow);
    ivec2 texel = tile.xy * uMapSize + ivec2(t % uMapSize, t / uMapSize);
    imageStore(uMaps, ivec3(texel, tile.z), uvec4(floatBitsToUint(kVPLNoOccluder)));
}
