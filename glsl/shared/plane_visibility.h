// Visibility from a map of planes (not in any of the papers; ours): the rule LightSkin's visibility
// maps (glsl/shared/lightskin_visibility.h) and the imperfect shadow maps with planes
// (glsl/shared/ism.h, `<technique>.ismPlanes`) share. Defined once for the GPU and the CPU.
//
// A map seen from an origin (a light cache, a virtual light) holds, per texel, the distance t along
// the texel's central direction to the first surface, and that surface's normal turned towards the
// origin: the plane of what the texel saw, or a miss. A receiver (a VAL, a shaded point) is judged
// by the four texels around its direction (the bilinear neighbours), each against the plane it saw
// (planeMapTexelVerdict): the receiver lies behind that plane (2: hidden), on it near the texel's
// hit (1: the texel may see the receiver's own surface), or anywhere else (0: nothing the texel saw
// stands in the way). Planes, not depths: a wall seen at a slant is exact (its depth changes fast
// from texel to texel, its plane does not), a surface the receiver lies on or in front of never
// shadows it (a concave corner, the inside of a sphere), and no margin in proportion to the distance
// is needed, so a 10 cm wall 5 m away still stops the light (a relative depth bias of 10% did not).
// A texel's 0 or 1 is cut (planeMapCut) when another texel puts the receiver behind its plane and
// the first texel's hit lies in front of that plane: its view stays on the origin's side of the
// wall (the floor beyond a wall's foot, coplanar with the floor behind the wall; the corner where
// wall, floor and the next wall meet). A cut texel counts as seeing the receiver only if an uncut one
// sees its surface. The four shares are weighted bilinearly. The maps err within about a texel of a
// silhouette, in both directions (tests/cpu/test_traced_visibility.cpp and
// tests/gl/test_imperfect_shadow_maps.cpp measure how often, per scene, against Embree rays).
#ifndef VPLGI_SHARED_PLANE_VISIBILITY_H
#define VPLGI_SHARED_PLANE_VISIBILITY_H
#include "compat.h"

VPLGI_SHARED_BEGIN

VPLGI_CONST float kPlaneMapMiss = 1e30f;      // a texel's distance when it saw nothing
VPLGI_CONST float kPlaneMapRelative = 0.002f; // the plane margin, relative to the texel's distance

// What one texel says of a receiver at `receiver` with geometric normal `receiverNormal` (seen from
// `origin`; `lift` an absolute margin [m]; texelAngle the texel's angular width [rad]; the texel's
// world direction, its distance t, its hit's normal facing the origin): 2 the receiver lies behind
// the hit's plane (and not on the same convex surface), 1 on it within about the texel's footprint
// of the hit (texelAngle across at distance t, stretched by the slant; not a coplanar surface
// further on, such as the floor of the next room), 0 otherwise or for a miss.
VPLGI_FUNC int planeMapTexelVerdict(vec3 origin, vec3 receiver, vec3 receiverNormal, float lift, float texelAngle,
                                    float edge, vec3 direction, float t, vec3 normal)
{
    if (!(t < kPlaneMapMiss)) return 0;
    float margin = kPlaneMapRelative * t + lift;
    vec3 hit = origin + t * direction;
    float height = dot(normal, receiver - hit); // above the hit's plane, towards the origin
    // A convex surface (a sphere, a column) puts a receiver on it below the tangent plane of a hit on
    // it nearby, and the hit as far below the receiver's own plane (R(1 - cos phi) both ways); a
    // receiver behind a wall lies below the wall's plane while the wall stands above the receiver's.
    float below = -dot(receiverNormal, hit - receiver);
    bool convex = below > 0.5f * -height && below < 2.0f * -height && -height < 0.5f * length(receiver - hit);
    if (height < -(margin + edge) && !convex) return 2;
    float footprint = 2.0f * t * texelAngle / max(abs(dot(normal, direction)), 0.05f);
    return height <= margin && length(receiver - hit) <= footprint ? 1 : 0;
}

// Whether texel j's hit lies in front of (or on) texel i's plane, on the origin's side, or less than
// `overhang` behind it (a map of splats: a disk that overhangs its surface's edge, such as a wall's
// disk past the corner where the next wall begins, puts its hit up to its radius beyond that wall's
// plane); for a miss, whether j's ray never crosses that plane.
VPLGI_FUNC bool planeMapHitInFront(vec3 origin, float lift, float overhang, vec3 dI, float tI, vec3 nI, vec3 dJ,
                                   float tJ, vec3 nJ)
{
    if (!(tJ < kPlaneMapMiss)) return dot(nI, dJ) >= 0.0f;
    float margin = kPlaneMapRelative * tI + lift;
    float ahead = dot(nI, (origin + tJ * dJ) - (origin + tI * dI));
    if (ahead > -margin) return true;
    // A concave corner (i's hit in front of j's plane too): j's disk may overhang past it.
    return ahead > -(margin + overhang) && dot(nJ, tI * dI - tJ * dJ) > -margin;
}

// Whether what texel j says of the receiver (its ray runs clear up to its hit, or it sees the
// receiver's plane) is cut off: a texel i puts the receiver behind its own plane (verdict 2) while
// j's hit lies in front of that plane, so j's clear path stays on the origin's side of a surface
// that lies between the origin and the receiver.
VPLGI_FUNC bool planeMapCut(vec3 origin, float lift, float overhang, vec3 dJ, float tJ, vec3 nJ, int r0, vec3 d0, float t0,
                            vec3 n0, int r1, vec3 d1, float t1, vec3 n1, int r2, vec3 d2, float t2, vec3 n2, int r3,
                            vec3 d3, float t3, vec3 n3)
{
    return (r0 == 2 && planeMapHitInFront(origin, lift, overhang, d0, t0, n0, dJ, tJ, nJ)) ||
           (r1 == 2 && planeMapHitInFront(origin, lift, overhang, d1, t1, n1, dJ, tJ, nJ)) ||
           (r2 == 2 && planeMapHitInFront(origin, lift, overhang, d2, t2, n2, dJ, tJ, nJ)) ||
           (r3 == 2 && planeMapHitInFront(origin, lift, overhang, d3, t3, n3, dJ, tJ, nJ));
}

// The extra margin texel i's "behind" test takes (edgeMargin x its distance; 0 for edgeMargin 0)
// when it sees a step at the edge of its surface: another texel's hit lies behind its plane, by at
// most that margin, and does not itself put the receiver behind its own plane (rK, that texel's
// verdict without the extra margin, is not 2), on a parallel face (normals within 25 degrees). The plane does not go on across the four texels
// there, and a receiver on the step behind it lies beside the surface rather than behind it, at a
// distance a texel cannot resolve (a canyon's terraces 21 m away under 2.6 m texels). A hit far
// behind (a gap in a wall, the room beyond) or a parallel face that hides the receiver too (the far
// side of a thin wall) is no step. Where the other hits lie on or in front of the plane (a flat
// wall, a concave corner) the plane is trusted to the small margin. For the imperfect shadow maps
// (ours): a texel spans 2-4 / N radians, details under it are not in the map.
VPLGI_FUNC bool planeMapStep(float lift, float edgeMargin, vec3 dI, float tI, vec3 nI, vec3 dK, float tK, vec3 nK,
                             int rK)
{
    if (!(tK < kPlaneMapMiss) || rK == 2 || !(dot(nI, nK) > 0.9f)) return false;
    float behind = -dot(nI, tK * dK - tI * dI);
    return behind > kPlaneMapRelative * tI + lift && behind <= edgeMargin * tI;
}

VPLGI_FUNC float planeMapEdgeMargin(float lift, float edgeMargin, vec3 dI, float tI, vec3 nI, vec3 dA, float tA, vec3 nA,
                                    int rA, vec3 dB, float tB, vec3 nB, int rB, vec3 dC, float tC, vec3 nC, int rC)
{
    if (!(edgeMargin > 0.0f) || !(tI < kPlaneMapMiss)) return 0.0f;
    bool step = planeMapStep(lift, edgeMargin, dI, tI, nI, dA, tA, nA, rA) ||
                planeMapStep(lift, edgeMargin, dI, tI, nI, dB, tB, nB, rB) ||
                planeMapStep(lift, edgeMargin, dI, tI, nI, dC, tC, nC, rC);
    return step ? edgeMargin * tI : 0.0f;
}

// One texel's share: its verdict, whether it is cut off (planeMapCut), and whether any texel that is
// not cut sees the receiver's surface (verdict 1). Behind its plane: 0; otherwise 1, unless it is
// cut and no uncut texel sees the receiver's surface.
VPLGI_FUNC float planeMapTexelVisible(int verdict, bool cut, bool seenAny)
{
    if (verdict == 2) return 0.0f;
    if (!cut) return 1.0f;
    return seenAny ? 1.0f : 0.0f;
}

// The visibility of a receiver from the four texels around its direction: their shares weighted
// bilinearly (f the position between the texel centres, 0-1 along x and y; texels 0, 1 along x,
// 2, 3 the next row).
VPLGI_FUNC float planeMapVisibility(vec3 origin, vec3 receiver, vec3 receiverNormal, float lift, float texelAngle,
                                    float overhang, float edgeMargin, vec2 f, vec3 d0, float t0, vec3 n0, vec3 d1,
                                    float t1, vec3 n1, vec3 d2, float t2, vec3 n2, vec3 d3, float t3, vec3 n3)
{
    int r0 = planeMapTexelVerdict(origin, receiver, receiverNormal, lift, texelAngle, 0.0f, d0, t0, n0);
    int r1 = planeMapTexelVerdict(origin, receiver, receiverNormal, lift, texelAngle, 0.0f, d1, t1, n1);
    int r2 = planeMapTexelVerdict(origin, receiver, receiverNormal, lift, texelAngle, 0.0f, d2, t2, n2);
    int r3 = planeMapTexelVerdict(origin, receiver, receiverNormal, lift, texelAngle, 0.0f, d3, t3, n3);
    if (edgeMargin > 0.0f) {
        float e0 = planeMapEdgeMargin(lift, edgeMargin, d0, t0, n0, d1, t1, n1, r1, d2, t2, n2, r2, d3, t3, n3, r3);
        float e1 = planeMapEdgeMargin(lift, edgeMargin, d1, t1, n1, d0, t0, n0, r0, d2, t2, n2, r2, d3, t3, n3, r3);
        float e2 = planeMapEdgeMargin(lift, edgeMargin, d2, t2, n2, d0, t0, n0, r0, d1, t1, n1, r1, d3, t3, n3, r3);
        float e3 = planeMapEdgeMargin(lift, edgeMargin, d3, t3, n3, d0, t0, n0, r0, d1, t1, n1, r1, d2, t2, n2, r2);
        r0 = e0 > 0.0f ? planeMapTexelVerdict(origin, receiver, receiverNormal, lift, texelAngle, e0, d0, t0, n0) : r0;
        r1 = e1 > 0.0f ? planeMapTexelVerdict(origin, receiver, receiverNormal, lift, texelAngle, e1, d1, t1, n1) : r1;
        r2 = e2 > 0.0f ? planeMapTexelVerdict(origin, receiver, receiverNormal, lift, texelAngle, e2, d2, t2, n2) : r2;
        r3 = e3 > 0.0f ? planeMapTexelVerdict(origin, receiver, receiverNormal, lift, texelAngle, e3, d3, t3, n3) : r3;
    }
    bool c0 = planeMapCut(origin, lift, overhang, d0, t0, n0, r0, d0, t0, n0, r1, d1, t1, n1, r2, d2, t2, n2, r3, d3, t3, n3);
    bool c1 = planeMapCut(origin, lift, overhang, d1, t1, n1, r0, d0, t0, n0, r1, d1, t1, n1, r2, d2, t2, n2, r3, d3, t3, n3);
    bool c2 = planeMapCut(origin, lift, overhang, d2, t2, n2, r0, d0, t0, n0, r1, d1, t1, n1, r2, d2, t2, n2, r3, d3, t3, n3);
    bool c3 = planeMapCut(origin, lift, overhang, d3, t3, n3, r0, d0, t0, n0, r1, d1, t1, n1, r2, d2, t2, n2, r3, d3, t3, n3);
    bool seen = (r0 == 1 && !c0) || (r1 == 1 && !c1) || (r2 == 1 && !c2) || (r3 == 1 && !c3);
    float v0 = planeMapTexelVisible(r0, c0, seen), v1 = planeMapTexelVisible(r1, c1, seen);
    float v2 = planeMapTexelVisible(r2, c2, seen), v3 = planeMapTexelVisible(r3, c3, seen);
    return mix(mix(v0, v1, f.x), mix(v2, v3, f.x), f.y);
}

VPLGI_SHARED_END

#endif
