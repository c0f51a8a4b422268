#version 450 core
// Reads the shadow atlas the way a shading pass would (glsl/shared/shadow_atlas.h) for lookups given
// by tests/gl/test_shadow_atlas.cpp, which compares with the texels read back on the CPU.
layout(local_size_x = 64) in;
#include "shared/bindings.h"
#include "shared/shadow_atlas.h"

struct Lookup {
    ivec4 slotView; // x slot, y view, zw unused
    vec4 tileUV;    // xy coordinates in the view's map, zw unused
};
layout(std430, binding = 0) readonly buffer Lookups { Lookup lookups[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
layout(binding = kUnitShadowAtlas) uniform sampler2DArray uAtlas;
uniform int uCount;
uniform int uViewsPerSlot;
uniform int uTilesPerRow;
uniform int uTileSize;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount) return;
    Lookup l = lookups[i];
    ivec3 tile = shadowAtlasTile(l.slotView.x, l.slotView.y, uViewsPerSlot, uTilesPerRow);
    vec3 coordinates = shadowAtlasCoordinates(tile, l.tileUV.xy, uTilesPerRow, uTileSize);
    results[i] = vec4(texture(uAtlas, coordinates).r, vec3(tile));
}
