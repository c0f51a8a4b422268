#version 450 core
// Shadow-atlas rendering (gl/passes/shadow_atlas.h): one instanced draw per mesh renders every tile
// being updated. Instance i draws tile index drawTiles[i] (= slot * viewsPerSlot + view) with that
// tile's clipFromWorld: it writes the tile's layer to gl_Layer (vertex-shader layer selection, about
// 2x faster than a geometry shader on llvmpipe: ../shared/ENVIRONMENT.md), squeezes the view's clip
// x, y into the tile's rectangle of the layer and clips to the view's frustum with four clip
// distances, so that nothing lands on a neighbouring tile (glsl/shared/shadow_atlas.h).
#extension GL_ARB_shader_viewport_layer_array : require
#include "../shared/bindings.h"
#include "../shared/shadow_atlas.h"

layout(location = 0) in vec3 aPosition;
layout(location = 2) in vec2 aTexcoord;
layout(location = 4) in vec2 aTexcoord1;
layout(location = 5) in vec4 aColor;

uniform mat4 uWorldFromObject;
uniform int uTilesPerRow;

layout(std430, binding = kBindingShadowAtlasMatrices) readonly buffer ShadowAtlasMatrices {
    mat4 clipFromWorldPerTile[];
};

layout(std430, binding = kBindingShadowAtlasDraw) readonly buffer ShadowAtlasDraw {
    int drawTiles[];
};

layout(location = 2) out vec2 vTexcoord; // for alpha masks (locations as passes/shadow.vert)
layout(location = 3) out vec2 vTexcoord1;
layout(location = 4) out float vAlpha;

out float gl_ClipDistance[4];

void main()
{
    int tileIndex = drawTiles[gl_InstanceID];
    ivec3 tile = shadowAtlasTileFromIndex(tileIndex, uTilesPerRow);
    vec4 world = uWorldFromObject * vec4(aPosition, 1.0);
    vec4 clip = clipFromWorldPerTile[tileIndex] * world;
    vec4 distances = shadowAtlasClipDistances(clip);
    gl_ClipDistance[0] = distances.x;
    gl_ClipDistance[1] = distances.y;
    gl_ClipDistance[2] = distances.z;
    gl_ClipDistance[3] = distances.w;
    gl_Layer = tile.z;
    vTexcoord = aTexcoord;
    vTexcoord1 = aTexcoord1;
    vAlpha = aColor.a;
    gl_Position = shadowAtlasClipFromViewClip(clip, tile, uTilesPerRow);
}
