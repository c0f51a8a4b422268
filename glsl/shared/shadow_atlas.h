// Shadow-atlas addressing, defined once for GLSL and C++: where the map of view `view` of slot
// `slot` lives in the atlas (gl/passes/shadow_atlas.h), and how a view's clip coordinates are
// squeezed into that place when it is rendered.
//
// Layout
// ------
// The atlas is a GL_TEXTURE_2D_ARRAY whose layers are tilesPerRow x tilesPerRow square tiles of
// tileSize texels each (layer size = tilesPerRow * tileSize). The views of a slot are consecutive
// tiles, and tiles fill a layer row by row (bottom row first, in GL's texel order), then the next
// layer:
//    tile index  t     = slot * viewsPerSlot + view
//    layer             = t / tilesPerRow^2
//    tile x, y         = i % tilesPerRow, i / tilesPerRow     with i = t % tilesPerRow^2
//    texels            [x T, (x + 1) T) x [y T, (y + 1) T) of that layer (T = tileSize)
// A view rendered alone into a T x T map and its tile hold the same texels: texel (a, b) of the
// view is texel (x T + a, y T + b) of the layer.
//
// Rendering into a tile
// ---------------------
// A view's clip coordinates c (NDC in [-1, 1]^2 over its whole map) become
//    c' = (c.xy / n + o c.w, c.z, c.w),   n = tilesPerRow,  o = (2 (x, y) + 1) / n - 1,
// which maps NDC [-1, 1] onto the tile's NDC rectangle [2x/n - 1, 2(x+1)/n - 1] of the layer and
// leaves depth alone (the same z and w as rendering the view alone). Clip space x, y outside the
// view's frustum would now land on the neighbouring tiles, so the four planes w +- x >= 0,
// w +- y >= 0 of the view's own frustum are kept as gl_ClipDistance[0..3].
#ifndef VPLGI_SHARED_SHADOW_ATLAS_H
#define VPLGI_SHARED_SHADOW_ATLAS_H
#include "compat.h"

VPLGI_SHARED_BEGIN

// Tile index of view `view` (0 <= view < viewsPerSlot) of slot `slot`.
VPLGI_FUNC int shadowAtlasTileIndex(int slot, int view, int viewsPerSlot)
{
    return slot * viewsPerSlot + view;
}

// (tile x, tile y, layer) of tile index `tileIndex`.
VPLGI_FUNC ivec3 shadowAtlasTileFromIndex(int tileIndex, int tilesPerRow)
{
    int tilesPerLayer = tilesPerRow * tilesPerRow;
    int layer = tileIndex / tilesPerLayer;
    int inLayer = tileIndex - layer * tilesPerLayer;
    return ivec3(inLayer % tilesPerRow, inLayer / tilesPerRow, layer);
}

// (tile x, tile y, layer) of view `view` of slot `slot`.
VPLGI_FUNC ivec3 shadowAtlasTile(int slot, int view, int viewsPerSlot, int tilesPerRow)
{
    return shadowAtlasTileFromIndex(shadowAtlasTileIndex(slot, view, viewsPerSlot), tilesPerRow);
}

// Texture coordinates (u, v, layer) for sampling the atlas at coordinates tileUV in [0,1]^2 of a
// view's map (tileUV = NDC xy / 2 + 1/2, as for a map of its own). tileUV is clamped to the
// centres of the tile's border texels, so that bilinear or PCF lookups never read a neighbour.
VPLGI_FUNC vec3 shadowAtlasCoordinates(ivec3 tile, vec2 tileUV, int tilesPerRow, int tileSize)
{
    float halfTexel = 0.5f / float(tileSize);
    vec2 inside = clamp(tileUV, vec2(halfTexel), vec2(1.0f - halfTexel));
    vec2 uv = (vec2(float(tile.x), float(tile.y)) + inside) / float(tilesPerRow);
    return vec3(uv.x, uv.y, float(tile.z));
}

// The layer's clip coordinates of a point with the view's clip coordinates `clip`, for rendering
// into tile `tile` (the squeeze above). With tilesPerRow a power of two, 1/n and o are exact.
VPLGI_FUNC vec4 shadowAtlasClipFromViewClip(vec4 clip, ivec3 tile, int tilesPerRow)
{
    float n = float(tilesPerRow);
    vec2 offset = (2.0f * vec2(float(tile.x), float(tile.y)) + vec2(1.0f)) / n - vec2(1.0f);
    vec2 xy = vec2(clip.x, clip.y) / n + offset * clip.w;
    return vec4(xy.x, xy.y, clip.z, clip.w);
}

// gl_ClipDistance[0..3] that keep a primitive inside the view's frustum in x and y (and so inside
// its tile): w + x, w - x, w + y, w - y of the view's own clip coordinates.
VPLGI_FUNC vec4 shadowAtlasClipDistances(vec4 clip)
{
    return vec4(clip.w + clip.x, clip.w - clip.x, clip.w + clip.y, clip.w - clip.y);
}

VPLGI_SHARED_END

#endif // VPLGI_SHARED_SHADOW_ATLAS_H
