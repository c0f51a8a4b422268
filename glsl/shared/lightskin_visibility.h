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
// A VAL at v is judged by the four texels around its direction, each against the plane its ray hit:
// the rule of glsl/shared/plane_visibility.h, which the imperfect shadow maps with planes share. The
// maps err within about a texel of a silhouette, in both directions
// (tests/cpu/test_traced_visibility.cpp measures how often, per scene).
#ifndef VPLGI_SHARED_LIGHTSKIN_VISIBILITY_H
#define VPLGI_SHARED_LIGHTSKIN_VISIBILITY_H
#include "compat.h"
#include "plane_visibility.h"

VPLGI_SHARED_BEGIN

VPLGI_CONST float kVisibilityMapMiss = kPlaneMapMiss; // a texel's distance when its ray hit nothing

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

// The visibility of a VAL from the four texels around its direction (glsl/shared/plane_visibility.h,
// planeMapVisibility; a texel spans about pi / size radians).
VPLGI_FUNC float visibilityMapVisibility(vec3 origin, vec3 val, vec3 valNormal, float lift, int size, vec2 f, vec3 d0,
                                         float t0, vec3 n0, vec3 d1, float t1, vec3 n1, vec3 d2, float t2, vec3 n2,
                                         vec3 d3, float t3, vec3 n3)
{
    return planeMapVisibility(origin, val, valNormal, lift, 3.14159265f / float(size), 0.0f, 0.0f, f, d0, t0, n0, d1, t1,
                              n1, d2, t2, n2, d3, t3, n3);
}

VPLGI_SHARED_END

#endif
