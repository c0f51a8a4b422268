// LightSkin's visibility maps (issue "LightSkin's indirect shadows"; not in the paper, whose
// occlusion is the double projection of section 3): the caches and the scene's geometry do not move,
// so what each cache sees is traced once with Embree when the caches are made
// (core/lightskin/traced_visibility.h, traceLightCacheVisibilityMaps), and the proxy pass drops every
// VAL the map says is hidden (glsl/passes/lightskin_proxy.comp). Defined once for the GPU and the
// CPU; tests/cpu/test_traced_visibility.cpp checks the verdicts against an Embree ray per
// (cache, VAL) pair.
//
// The map is size x size texels over the cache's hemisphere: a direction w, in the frame of the
// cache's unit disk (occlusionFrame: t, b, n), goes to the hemi-octahedron p = (w.t, w.b) /
// (|w.t| + |w.b| + w.n) turned by 45 degrees onto the square, q = (p.x + p.y, p.x - p.y) in
// [-1, 1]^2 (a bijection: max(|q.x|, |q.y|) = |p.x| + |p.y| <= 1). Each texel holds what the ray
// through its centre hits first, from the cache lifted `lift` off its surface: the distance t and
// the hit's geometric normal turned towards the cache (the plane of what it hit), or a miss.
//
// A VAL at v is judged by the four texels around its direction (the bilinear neighbours), each
// against the plane its ray hit (visibilityMapTexelVerdict): the VAL lies behind that plane (2:
// hidden), on it near the hit (1: the texel may see the VAL's own surface), or anywhere else (0:
// nothing the texel saw stands in the way). Planes, not depths: a wall seen at a slant is exact
// (its depth changes fast from texel to texel, its plane does not), and a surface the VAL lies on
// or in front of never shadows it (a concave corner, the inside of a sphere). A texel's 0 or 1 is
// cut (visibilityMapCut) when another texel puts the VAL behind its plane and the first texel's hit
// lies in front of that plane: its view stays on the cache's side of the wall (the floor beyond a
// wall's foot, coplanar with the floor behind the wall; the corner where wall, floor and the next
// wall meet). A cut texel counts as seeing the VAL only if an uncut one sees its surface. The four
// shares are weighted bilinearly. The maps err within about a texel of a silhouette, in both
// directions (tests/cpu/test_traced_visibility.cpp measures how often, per scene).
#ifndef VPLGI_SHARED_LIGHTSKIN_VISIBILITY_H
#define VPLGI_SHARED_LIGHTSKIN_VISIBILITY_H
#include "compat.h"

VPLGI_SHARED_BEGIN

VPLGI_CONST float kVisibilityMapMiss = 1e30f;      // a texel's distance when its ray hit nothing
VPLGI_CONST float kVisibilityMapRelative = 0.002f; // the plane margin, relative to the texel's distance

// Direction in the map's frame (z along the cache normal; any length) -> [0, 1]^2; a direction below
// the cache's plane goes to the rim above it (z taken as 0), straight down to the centre.
VPLGI_FUNC vec2 visibilityMapFromLocal(vec3 w)
{
    vec2 p = vec2(w.x, w.y) * (1.0f / max(abs(w.x) + abs(w.y) + max(w.z, 0.0f), 1e-30f));
    return (vec2(p.x + p.y, p.x - p.y) + vec2(1.0f)) * 0.5f;
}

// [0, 1]^2 -> unit direction in the map's frame (the inverse of visibilityMapFromLocal).
VPLGI_FUNC vec3 visibilityMapToLocal(vec2 uv)
{
    vec2 q = uv * 2.0f - vec2(1.0f);
    vec2 p = vec2(q.x + q.y, q.x - q.y) * 0.5f;
    return normalize(vec3(p.x, p.y, max(1.0f - abs(p.x) - abs(p.y), 0.0f)));
}

// The direction through the centre of texel (x, y) of a size x size map, in the map's frame.
VPLGI_FUNC vec3 visibilityMapTexelDirection(int x, int y, int size)
{
    return visibilityMapToLocal((vec2(float(x), float(y)) + vec2(0.5f)) / float(size));
}

// The lower-left texel of the four around map position uv (clamped so that all four lie in the map).
VPLGI_FUNC ivec2 visibilityMapFirstNeighbour(vec2 uv, int size)
{
    vec2 texel = floor(uv * float(size) - vec2(0.5f));
    return ivec2(clamp(texel, vec2(0.0f), vec2(float(max(size - 2, 0)))));
}

// Where map position uv lies between the centres of the four texels from `first` (0-1 per axis).
VPLGI_FUNC vec2 visibilityMapBilinear(vec2 uv, ivec2 first, int size)
{
    return clamp(uv * float(size) - vec2(0.5f) - vec2(first), vec2(0.0f), vec2(1.0f));
}

// What one texel says of a VAL at `val` with geometric normal `valNormal` (origin the lifted cache;
// the texel's world direction, its distance t, its hit's normal facing the cache): 2 the VAL lies
// behind the hit's plane (and not on the same convex surface), 1 on it
// within about the texel's footprint of the hit (pi / size across at distance t, stretched by the
// slant; not a coplanar surface further on, such as the floor of the next room), 0 otherwise or
// for a miss.
VPLGI_FUNC int visibilityMapTexelVerdict(vec3 origin, vec3 val, vec3 valNormal, float lift, int size, vec3 direction,
                                         float t, vec3 normal)
{
    if (!(t < kVisibilityMapMiss)) return 0;
    float margin = kVisibilityMapRelative * t + lift;
    vec3 hit = origin + t * direction;
    float height = dot(normal, val - hit); // above the hit's plane, towards the cache
    // A convex surface (a sphere, a column) puts a VAL on it below the tangent plane of a hit on it
    // nearby, and the hit as far below the VAL's own plane (R(1 - cos phi) both ways); a VAL behind
    // a wall lies below the wall's plane while the wall stands above the VAL's own plane.
    float below = -dot(valNormal, hit - val);
    bool convex = below > 0.5f * -height && below < 2.0f * -height && -height < 0.5f * length(val - hit);
    if (height < -margin && !convex) return 2;
    float footprint = 2.0f * t * (3.14159265f / float(size)) / max(abs(dot(normal, direction)), 0.05f);
    return height <= margin && length(val - hit) <= footprint ? 1 : 0;
}

// Whether texel j's hit lies in front of (or on) texel i's plane, on the cache's side; for a miss,
// whether j's ray never crosses that plane.
VPLGI_FUNC bool visibilityMapHitInFront(vec3 origin, float lift, vec3 dI, float tI, vec3 nI, vec3 dJ, float tJ)
{
    if (!(tJ < kVisibilityMapMiss)) return dot(nI, dJ) >= 0.0f;
    return dot(nI, (origin + tJ * dJ) - (origin + tI * dI)) > -(kVisibilityMapRelative * tI + lift);
}

// Whether what texel j says for the VAL (its ray runs clear up to its hit, or it sees the VAL's
// plane) is cut off: a texel i puts the VAL behind its own plane (verdict 2) while j's hit lies in
// front of that plane, so j's clear path stays on the cache's side of a surface that lies between
// the cache and the VAL (the floor beyond a wall's foot, coplanar with the floor behind the wall;
// the corner where the wall meets the floor and the next wall).
VPLGI_FUNC bool visibilityMapCut(vec3 origin, float lift, vec3 dJ, float tJ, int r0, vec3 d0, float t0, vec3 n0, int r1,
                                 vec3 d1, float t1, vec3 n1, int r2, vec3 d2, float t2, vec3 n2, int r3, vec3 d3,
                                 float t3, vec3 n3)
{
    return (r0 == 2 && visibilityMapHitInFront(origin, lift, d0, t0, n0, dJ, tJ)) ||
           (r1 == 2 && visibilityMapHitInFront(origin, lift, d1, t1, n1, dJ, tJ)) ||
           (r2 == 2 && visibilityMapHitInFront(origin, lift, d2, t2, n2, dJ, tJ)) ||
           (r3 == 2 && visibilityMapHitInFront(origin, lift, d3, t3, n3, dJ, tJ));
}

// One texel's share: its verdict, whether it is cut off (visibilityMapCut), and whether any texel
// that is not cut sees the VAL's surface (verdict 1). Behind its plane: 0; otherwise 1, unless it is
// cut and no uncut texel sees the VAL's surface.
VPLGI_FUNC float visibilityMapTexelVisible(int verdict, bool cut, bool seenAny)
{
    if (verdict == 2) return 0.0f;
    if (!cut) return 1.0f;
    return seenAny ? 1.0f : 0.0f;
}

// The visibility of a VAL from the four texels around its direction: their shares weighted
// bilinearly (f the position between the texel centres, 0-1 along x and y).
VPLGI_FUNC float visibilityMapVisibility(vec3 origin, vec3 val, vec3 valNormal, float lift, int size, vec2 f, vec3 d0,
                                         float t0, vec3 n0, vec3 d1, float t1, vec3 n1, vec3 d2, float t2, vec3 n2,
                                         vec3 d3, float t3, vec3 n3)
{
    int r0 = visibilityMapTexelVerdict(origin, val, valNormal, lift, size, d0, t0, n0);
    int r1 = visibilityMapTexelVerdict(origin, val, valNormal, lift, size, d1, t1, n1);
    int r2 = visibilityMapTexelVerdict(origin, val, valNormal, lift, size, d2, t2, n2);
    int r3 = visibilityMapTexelVerdict(origin, val, valNormal, lift, size, d3, t3, n3);
    bool c0 = visibilityMapCut(origin, lift, d0, t0, r0, d0, t0, n0, r1, d1, t1, n1, r2, d2, t2, n2, r3, d3, t3, n3);
    bool c1 = visibilityMapCut(origin, lift, d1, t1, r0, d0, t0, n0, r1, d1, t1, n1, r2, d2, t2, n2, r3, d3, t3, n3);
    bool c2 = visibilityMapCut(origin, lift, d2, t2, r0, d0, t0, n0, r1, d1, t1, n1, r2, d2, t2, n2, r3, d3, t3, n3);
    bool c3 = visibilityMapCut(origin, lift, d3, t3, r0, d0, t0, n0, r1, d1, t1, n1, r2, d2, t2, n2, r3, d3, t3, n3);
    bool seen = (r0 == 1 && !c0) || (r1 == 1 && !c1) || (r2 == 1 && !c2) || (r3 == 1 && !c3);
    float v0 = visibilityMapTexelVisible(r0, c0, seen), v1 = visibilityMapTexelVisible(r1, c1, seen);
    float v2 = visibilityMapTexelVisible(r2, c2, seen), v3 = visibilityMapTexelVisible(r3, c3, seen);
    return mix(mix(v0, v1, f.x), mix(v2, v3, f.x), f.y);
}

VPLGI_SHARED_END

#endif
