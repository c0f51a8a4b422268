// Imperfect shadow maps (gl/passes/imperfect_shadow_maps.h), defined once for GLSL and C++: where a
// scene point is splatted, where a shaded point is looked up, and the pull-push arithmetic.
//
// The maps are SMCIR's paraboloid maps (glsl/shared/vpl.h): the hemisphere about the light's normal
// in the light frame of lightViewBasis, texel vplParaboloidTexel, the distance [m] to the nearest
// surface stored as r32f, kVPLNoOccluder where nothing is known, one tile per light addressed like
// the shadow atlas (glsl/shared/shadow_atlas.h, one view per slot). A splatted point and a looked-up
// point in the same direction land in the same texel because both go through ismMapTexel.
//
// Pull-push (Grossman & Dally 1998, as ISMs use it; MATH.md 10.2). Empty texels hold
// kVPLNoOccluder. Both steps average only texels within (1 + depthRange) times the nearest valid
// distance among their inputs, so a hole next to a depth edge takes the foreground's distance, not a
// blend of foreground and background that would float in empty space.
//  Pull: coarse texel = that average over its 2 x 2 finer texels; empty when all four are.
//  Push: an empty finer texel takes the bilinear interpolation (weights 9, 3, 3, 1 / 16) of the four
//        coarser texels nearest its centre, over those inside the tile and valid (weights
//        renormalised); valid finer texels keep their value.
#ifndef VPLGI_SHARED_ISM_H
#define VPLGI_SHARED_ISM_H
#include "compat.h"
#include "light_view.h"
#include "normals.h"
#include "plane_visibility.h"
#include "shadow_atlas.h"
#include "vpl.h"
#ifdef __cplusplus
#include <glm/gtc/packing.hpp>
#endif

VPLGI_SHARED_BEGIN

// Points this close to the light's tangent plane (cosine to its normal) are not splatted: points of
// the surface the light lies on would otherwise put distances near 0 into the rim texels, and
// pull-push would spread them inwards.
VPLGI_CONST float kISMHorizonCosine = 1.0e-3f;

// True when `distance` is a stored distance, false for kVPLNoOccluder.
VPLGI_FUNC bool ismValid(float distance)
{
    return distance < kVPLNoOccluder;
}

// Texel (x, y in the layer, layer) of light `light`'s map holding unit direction `directionLight`
// (light frame, z >= 0): vplParaboloidTexel inside the light's tile.
VPLGI_FUNC ivec3 ismMapTexel(int light, vec3 directionLight, int mapSize, int tilesPerRow)
{
    ivec3 tile = shadowAtlasTileFromIndex(light, tilesPerRow);
    ivec2 texel = vplParaboloidTexel(directionLight, mapSize);
    return ivec3(tile.x * mapSize + texel.x, tile.y * mapSize + texel.y, tile.z);
}

// The texel a scene point is splatted into, or ivec3(-1) when the point is behind the light's
// tangent plane (or within kISMHorizonCosine of it, or at the light itself). `lightFrame` =
// lightViewBasis(the light's normal).
VPLGI_FUNC ivec3 ismSplatTexel(int light, vec3 lightPosition, mat3 lightFrame, vec3 point, int mapSize, int tilesPerRow)
{
    vec3 toPoint = point - lightPosition;
    float distance = length(toPoint);
    if (!(distance > 0.0f)) return ivec3(-1);
    vec3 directionLight = transpose(lightFrame) * (toPoint / distance);
    if (!(directionLight.z > kISMHorizonCosine)) return ivec3(-1);
    return ismMapTexel(light, directionLight, mapSize, tilesPerRow);
}

// The point a lookup tests for shaded point x (normal nx): x lifted along nx by normalOffset map
// texels at its distance from the light (a paraboloid texel spans 2/N to 4/N radians), as SMCIR's
// lookup (passes/vpl_shading.frag) does.
VPLGI_FUNC vec3 ismLookupPoint(vec3 lightPosition, vec3 x, vec3 nx, float normalOffset, int mapSize)
{
    float d = length(x - lightPosition);
    return x + nx * (normalOffset * 4.0f * d / float(mapSize));
}

// The texel a lookup of point q (from ismLookupPoint) reads: its direction in the light frame,
// pulled up onto the hemisphere when it is below it.
VPLGI_FUNC ivec3 ismLookupTexel(int light, vec3 lightPosition, vec3 lightNormal, vec3 q, int mapSize, int tilesPerRow)
{
    vec3 toPoint = q - lightPosition;
    vec3 d = transpose(lightViewBasis(lightNormal)) * (toPoint / length(toPoint));
    vec3 directionLight = normalize(vec3(d.x, d.y, max(d.z, 0.0f)));
    return ismMapTexel(light, directionLight, mapSize, tilesPerRow);
}

// Footprint splats (ours, not in Ritschel et al. 2008 nor in VSGL, which splat one-texel points).
// A light's run of n points is a uniform sample of the scene's area A, so each point stands for the
// disk of radius r0 = sqrt(A / (pi n)) of its tangent plane; the splat covers the texels whose
// centres lie in the image of the disk of radius r = splatScale r0 (an ellipse: the paraboloid map is
// conformal, and the disk is seen at an angle), each with the distance along the texel's direction to
// the point's tangent plane. One-texel points cover a near surface far more thinly than a far one
// (a texel sees d^2 times more area at distance d), so a far surface showed through the holes of a
// near wall, and pull-push, which fills empty texels only, could not close them: a 10 cm wall of
// the sealed room let about half the light through (docs/vsgl.md, "Imperfect shadow maps"). With
// disks, the share of a surface left uncovered is that of a Poisson disk process,
// exp(-splatScale^2), at any distance.

// Continuous texel coordinates (in the tile) of unit direction `directionLight` (light frame):
// vplParaboloidTexel is their floor.
VPLGI_FUNC vec2 ismMapPosition(vec3 directionLight, int mapSize)
{
    return paraboloidMapFromDirection(directionLight) * float(mapSize);
}

// How far the map position of `toPoint` (light frame, relative to the light) moves, in texels, when
// the point moves by the small world displacement `displacement` (light frame).
VPLGI_FUNC vec2 ismMapDifferential(vec3 toPoint, vec3 displacement, int mapSize)
{
    float d = length(toPoint);
    vec3 u = toPoint / d;
    vec3 du = (displacement - u * dot(u, displacement)) / d;
    float inv = 1.0f / (1.0f + u.z);
    vec2 dst = vec2(du.x, du.y) * inv - vec2(u.x, u.y) * (du.z * inv * inv);
    return dst * (0.5f * float(mapSize));
}

// The linear map from the unit disk to texel offsets of the image of the disk of world radius
// `radius` about `toPoint` in the plane of unit normal `normal` (both in the light frame).
VPLGI_FUNC mat2 ismSplatEllipse(vec3 toPoint, vec3 normal, float radius, int mapSize)
{
    mat3 tangents = lightViewBasis(normal);
    return mat2(ismMapDifferential(toPoint, radius * tangents[0], mapSize),
                ismMapDifferential(toPoint, radius * tangents[1], mapSize));
}

// Half the size of the ellipse's bounding box [texels], each side at most maxExtent.
VPLGI_FUNC vec2 ismSplatExtent(mat2 ellipse, float maxExtent)
{
    vec2 extent = vec2(length(vec2(ellipse[0].x, ellipse[1].x)), length(vec2(ellipse[0].y, ellipse[1].y)));
    return min(extent, vec2(maxExtent));
}

// The first (lo) and last (hi) texel of the tile whose centres may lie in the ellipse about `centre`.
VPLGI_FUNC ivec2 ismSplatFirstTexel(vec2 centre, vec2 extent)
{
    return max(ivec2(ceil(centre - extent - vec2(0.5f))), ivec2(0));
}

VPLGI_FUNC ivec2 ismSplatLastTexel(vec2 centre, vec2 extent, int mapSize)
{
    return min(ivec2(floor(centre + extent - vec2(0.5f))), ivec2(mapSize - 1));
}

// The distance along the direction of texel `texel`'s centre to the plane through `toPoint` with unit
// normal `normal` (light frame), kept within [d - radius, d + radius] (d = |toPoint|; the plane is
// nearly parallel to the direction at a disk's ends); d for radius 0.
VPLGI_FUNC float ismPlaneDistance(vec3 toPoint, float d, vec3 normal, float radius, ivec2 texel, int mapSize)
{
    vec3 w = vplParaboloidTexelDirection(texel, mapSize);
    float nw = dot(normal, w);
    float t = abs(nw) > 1.0e-6f ? dot(normal, toPoint) / nw : d;
    return clamp(t, max(d - radius, 0.0f), d + radius);
}

// The distance the disk's splat writes into texel `texel` of the tile: kVPLNoOccluder when the
// texel's centre is outside the ellipse, else the distance along the texel's direction to the disk's
// plane, kept within [d - radius, d + radius] (d = |toPoint|, computed once per point by the caller;
// the plane is nearly parallel to the direction at the ellipse's ends).
VPLGI_FUNC float ismSplatDistance(vec3 toPoint, float d, vec3 normal, float radius, vec2 centre, mat2 ellipse,
                                  ivec2 texel, int mapSize)
{
    vec2 offset = vec2(float(texel.x), float(texel.y)) + vec2(0.5f) - centre;
    // offset = ellipse (a, b); a^2 + b^2 <= 1 without dividing by the determinant (0 edge-on).
    float det = ellipse[0].x * ellipse[1].y - ellipse[1].x * ellipse[0].y;
    float a = ellipse[1].y * offset.x - ellipse[1].x * offset.y;
    float b = ellipse[0].x * offset.y - ellipse[0].y * offset.x;
    if (!(a * a + b * b <= det * det)) return kVPLNoOccluder;
    return ismPlaneDistance(toPoint, d, normal, radius, texel, mapSize);
}

// A light with extent (a VSGL, radius r_i) is not shadowed by its own footprint: the points within
// ownRadius r_i are left out of its map (ours). With ownSurfaceOnly, only those of its own surface
// are (ours): facing the light's way (normals within 60 degrees) and within half that radius of its
// tangent plane. The walls beside a VSGL on a floor then stay in its map (they stopped the light
// of VSGLs beside a shared wall from reaching the room behind it); a footprint over a convex edge,
// whose mean position lies inside the object, still sees out over the object's other faces.
VPLGI_FUNC bool ismOwnSurface(vec3 lightToPoint, vec3 pointNormal, vec3 lightNormal, float ownRadius)
{
    return dot(pointNormal, lightNormal) > 0.5f && abs(dot(lightNormal, lightToPoint)) < 0.5f * ownRadius;
}

// Planes (ours, not in Ritschel et al. 2008 nor in VSGL; `<technique>.ismPlanes`): each texel also
// keeps the normal of the point whose splat won it (a second splat pass writes it where the point's
// distance equals the texel's; ties go to the smallest packed normal, so the maps do not depend on
// the order the invocations run in), turned towards the light, and the centre texel holds the
// distance along its central direction to the point's plane, as the disk's other texels do. The
// lookup then judges a receiver by the four texels around its direction with the plane rule of
// glsl/shared/plane_visibility.h (the one LightSkin's visibility maps use) instead of one texel's
// depth with a relative bias: a receiver 10 cm behind a wall 5 m away is behind the wall's plane,
// while within 10% of its depth, the relative bias's margin, it was lit (issue "Every light type in
// the RSM techniques": the sealed room's closed side lit along its joints).
VPLGI_CONST uint kISMNoNormal = 0xFFFFFFFFu; // a texel no splat's normal reached (empty, or filled by pull-push)

// Below this cosine between a texel's direction and a point's plane, the point writes nothing into the
// texel with planes: the distance along the direction to a plane seen that edge-on says little.
VPLGI_CONST float kISMPlaneGrazing = 0.01f;

// With planes, the distance a point (toPoint, unit normal, light frame) writes into texel `texel` of
// the tile: along the texel's central direction to the point's plane, without the clamp of
// ismPlaneDistance (a clamped distance is off the plane the normal describes), and kVPLNoOccluder
// where the direction meets the plane at a grazing angle (kISMPlaneGrazing), behind the light, or
// farther than `reach` from the point (for a texel of the disk's ellipse: outside the disk, which
// the ellipse, a first-order image, overshoots when the disk is seen edge-on; the point's own texel
// passes a reach of kVPLNoOccluder: its centre ray is within a texel of the point).
VPLGI_FUNC float ismPlaneSplatDistance(vec3 toPoint, vec3 normal, float reach, ivec2 texel, int mapSize)
{
    vec3 w = vplParaboloidTexelDirection(texel, mapSize);
    float nw = dot(normal, w);
    if (!(abs(nw) >= kISMPlaneGrazing)) return kVPLNoOccluder;
    float t = dot(normal, toPoint) / nw;
    if (!(t > 0.0f) || !(length(t * w - toPoint) <= reach)) return kVPLNoOccluder;
    return t;
}

// Reach (ours, `<technique>.ismReach`, with planes): a disk centred near its surface's edge overhangs
// it, and what the overhang writes is a plane where there is no surface: on a scene of columns,
// arches and balustrades (Sponza) 19% of the map texels lay more than 10% nearer than the first
// surface along their central direction, and the plane rule shadowed 29% of the light-receiver pairs
// Embree sees lit. Each point carries its reach: per sector k of kISMReachSectors in its tangent
// plane (lightViewBasis(normal) columns 0 and 1, sector k centred on the angle k 2 pi / 8 from column
// 0), the fraction j / 4 (j = 0 .. 4, 3 bits each) of the disk radius up to which the surface
// continues (core/scene/surface_points.h, surfaceReach). A disk's texel whose central ray meets the
// point's plane farther from the point than that (in the sector of the meeting point) is not
// written; the point's own texel always is.
VPLGI_CONST int kISMReachSectors = 8;
VPLGI_CONST int kISMReachSteps = 4;          // reach j / kISMReachSteps of the radius, j = 0 .. 4
VPLGI_CONST uint kISMReachFull = 0x924924u;  // every sector's j = 4: the whole disk

// The sector (0 .. 7) of an offset with coordinates (a, b) along the tangent axes lightViewBasis(normal)
// columns 0 and 1.
VPLGI_FUNC int ismReachSector(float a, float b)
{
    // Turned by 22.5 degrees, so that sector k (the octant of (x, y)) is centred on k x 45 degrees.
    float x = 0.92387953f * a - 0.38268343f * b, y = 0.38268343f * a + 0.92387953f * b;
    if (y >= 0.0f) return x >= 0.0f ? (x >= y ? 0 : 1) : (-x <= y ? 2 : 3);
    return x < 0.0f ? (-x >= -y ? 4 : 5) : (x <= -y ? 6 : 7);
}

// Sector `sector`'s central direction in the tangent plane of `normal` (lightViewBasis(normal) columns
// 0 and 1, the angle sector x 2 pi / kISMReachSectors from column 0): where surfaceReach probes.
VPLGI_FUNC vec3 ismReachDirection(vec3 normal, int sector)
{
    mat3 basis = lightViewBasis(normal);
    float angle = 6.28318531f * float(sector) / float(kISMReachSectors);
    return cos(angle) * basis[0] + sin(angle) * basis[1];
}

// The reach of sector `sector` of a point's profile, as a fraction of its disk radius.
VPLGI_FUNC float ismReachFraction(uint profile, int sector)
{
    return float((profile >> uint(3 * sector)) & 7u) / float(kISMReachSteps);
}

// The tangent axes of a point's profile (lightViewBasis(worldNormal) columns 0 and 1) in the frame
// `frame` of a light's map, computed once per point by the splat.
VPLGI_FUNC void ismReachAxes(vec3 worldNormal, mat3 frame, VPLGI_OUT(vec3) axis0, VPLGI_OUT(vec3) axis1)
{
    mat3 basis = lightViewBasis(worldNormal);
    axis0 = transpose(frame) * basis[0];
    axis1 = transpose(frame) * basis[1];
}

// Whether a disk's texel whose central ray meets the point's plane at `offset` from the point (in the
// frame of the axes, ismReachAxes) lies within the point's reach (radius: the profile's unit, the
// light run's disk radius) plus `margin` [m]. The margin (`<technique>.ismReachMargin` x the set's
// spacing): an edge can lie up to about a spacing past the last probe that found its surface (the
// probe beyond found no point in the sliver of its tolerance left on the surface); without it, strips
// along edges that no disk of a map's sparse run covered let the sun's light into the sealed rooms'
// closed room (CI subset: closed-room maximum 3.3e-4 of the lit mean, 0 with 1.5 spacings).
VPLGI_FUNC bool ismWithinReach(uint profile, vec3 offset, vec3 axis0, vec3 axis1, float radius, float margin)
{
    if (profile == kISMReachFull) return true;
    int sector = ismReachSector(dot(offset, axis0), dot(offset, axis1));
    return length(offset) <= radius * ismReachFraction(profile, sector) + margin;
}

// Near field (ours, `<technique>.ismNearField`): the grid cell of world point `p`, cells of edge
// 1 / `inverseEdge` from `origin`. The CPU's sort by cell and the splat's lookup must agree bit for
// bit, so both call this one function, and it multiplies: GLSL rounds a subtraction and a product
// as IEEE does, a division only within 2.5 ulp.
VPLGI_FUNC ivec3 ismNearCell(vec3 p, vec3 origin, float inverseEdge)
{
    return ivec3(floor((p - origin) * inverseEdge));
}

// Near field: the hash slot of grid cell `cell` among `slotCount` slots (a power of two), where the
// scene's points are listed by cell (gl/passes/imperfect_shadow_maps.cpp); the cells that share a
// slot are told apart by the splat's cell test.
VPLGI_FUNC uint ismNearSlot(ivec3 cell, uint slotCount)
{
    uint h = (uint(cell.x) * 73856093u) ^ (uint(cell.y) * 19349663u) ^ (uint(cell.z) * 83492791u);
    return h & (slotCount - 1u);
}

// The packed normal a splat writes: unit `normal` (world) turned towards the light (a point's
// geometric normal may face away: the far side of a wall is splatted too).
VPLGI_FUNC uint ismPackNormal(vec3 normal, vec3 lightToPoint)
{
    vec3 n = dot(normal, lightToPoint) > 0.0f ? -normal : normal;
    return packSnorm2x16(octEncode(n));
}

// The first (lower-left) of the four texels (in the tile) around unit direction `directionLight`
// (light frame; below the hemisphere pulled up onto it), kept so that all four lie in the tile, and
// where the direction lies between their centres (0-1 along x and y) in `f`.
VPLGI_FUNC ivec2 ismPlaneNeighbours(vec3 directionLight, int mapSize, VPLGI_OUT(vec2) f)
{
    vec3 d = normalize(vec3(directionLight.x, directionLight.y, max(directionLight.z, 0.0f)));
    vec2 position = ismMapPosition(d, mapSize) - vec2(0.5f);
    vec2 first = clamp(floor(position), vec2(0.0f), vec2(float(mapSize - 2)));
    f = clamp(position - first, vec2(0.0f), vec2(1.0f));
    return ivec2(first);
}

// A paraboloid texel spans 2 / N (centre) to 4 / N (rim) radians: the plane rule's footprint takes the larger.
VPLGI_FUNC float ismPlaneTexelAngle(int mapSize)
{
    return 4.0f / float(mapSize);
}


// Gap filling (ours; `<technique>.ismGapReach`, with planes): a gap between splats is not empty but
// shows what lies behind the surface, and pull-push, which fills empty texels only, cannot close it
// (a wall with a gap lights the room behind it). A texel whose two opposite neighbours k texels away
// (left and right, below and above, or a diagonal pair) both saw one plane, which its own ray crosses
// near their points before its own hit, looked through a gap in that surface: it takes the plane.
// Past a surface's edge only one side sees it, so silhouettes stay where they are. The pass reads
// the splatted maps and writes a copy (glsl/passes/ism_gaps.comp), so the result does not depend on
// the order texels are filled in.

// The distance along texel j's central direction dJ to the plane both a and b saw (their central
// directions, distances and normals facing the light; k texels from j on opposite sides), when j's
// ray crosses it near both of their points (within k + 1/2 texels, texelAngle each, at their
// distance and slant) and before its own hit tJ (kVPLNoOccluder: none) by more than the plane rule's
// margin; kVPLNoOccluder otherwise. The two planes must agree: normals within about 25 degrees, the
// crossings within 1% of the distance.
VPLGI_FUNC float ismGapCrossing(vec3 dJ, float tJ, vec3 dA, float tA, vec3 nA, vec3 dB, float tB, vec3 nB,
                                float texelAngle, float k, float lift)
{
    if (!ismValid(tA) || !ismValid(tB)) return kVPLNoOccluder;
    float towardA = dot(nA, dJ), towardB = dot(nB, dJ);
    if (!(towardA < -kISMPlaneGrazing) || !(towardB < -kISMPlaneGrazing)) return kVPLNoOccluder;
    float sA = tA * dot(nA, dA) / towardA, sB = tB * dot(nB, dB) / towardB;
    if (!(sA > 0.0f) || !(sB > 0.0f)) return kVPLNoOccluder;
    float reachA = (k + 0.5f) * tA * texelAngle / max(abs(dot(nA, dA)), 0.05f);
    float reachB = (k + 0.5f) * tB * texelAngle / max(abs(dot(nB, dB)), 0.05f);
    if (!(dot(nA, nB) > 0.9f) || !(abs(sA - sB) <= 0.01f * max(sA, sB) + lift)) return kVPLNoOccluder;
    if (ismValid(tJ) && !(max(sA, sB) < tJ - (kPlaneMapRelative * tJ + lift))) return kVPLNoOccluder;
    if (!(length(sA * dJ - tA * dA) <= reachA) || !(length(sB * dJ - tB * dB) <= reachB)) return kVPLNoOccluder;
    return min(sA, sB);
}

// At the horizon (ours, with gap filling): when b lies beyond the paraboloid's rim (ismBeyondRim),
// a alone: the gap runs out to the light's own tangent plane, where no splat can close it (points
// near that plane are not splatted, kISMHorizonCosine), so a wall that meets the light's surface (a
// shared wall under the ceiling a light sits on) otherwise leaves a band of gaps along the rim.
// Light leaves there at grazing angles, a few texels from the horizon.
VPLGI_FUNC float ismGapCrossingAtRim(vec3 dJ, float tJ, vec3 dA, float tA, vec3 nA, float texelAngle, float k,
                                     float lift)
{
    if (!ismValid(tA)) return kVPLNoOccluder;
    float towardA = dot(nA, dJ);
    if (!(towardA < -kISMPlaneGrazing)) return kVPLNoOccluder;
    float s = tA * dot(nA, dA) / towardA;
    if (!(s > 0.0f)) return kVPLNoOccluder;
    if (ismValid(tJ) && !(s < tJ - (kPlaneMapRelative * tJ + lift))) return kVPLNoOccluder;
    float reachA = (k + 0.5f) * tA * texelAngle / max(abs(dot(nA, dA)), 0.05f);
    if (!(length(s * dJ - tA * dA) <= reachA)) return kVPLNoOccluder;
    return s;
}

// Whether texel `texel` (of the tile, any integers) lies beyond the paraboloid map's rim: its centre
// outside the unit disk (or the tile), where no direction of the hemisphere falls.
VPLGI_FUNC bool ismBeyondRim(ivec2 texel, int mapSize)
{
    vec2 st = 2.0f * (vec2(float(texel.x), float(texel.y)) + vec2(0.5f)) / float(mapSize) - vec2(1.0f);
    return dot(st, st) > 1.0f;
}

// The k-th opposite pair's offset from j (pair 0: along x, 1: along y, 2 and 3: the diagonals);
// a = j - offset, b = j + offset.
VPLGI_FUNC ivec2 ismGapOffset(int pair, int k)
{
    ivec2 unit = pair == 0 ? ivec2(1, 0) : (pair == 1 ? ivec2(0, 1) : (pair == 2 ? ivec2(1, 1) : ivec2(1, -1)));
    return unit * k;
}

// 1 = lit, 0 = shadowed: q's distance against the stored one with SMCIR's relative bias.
VPLGI_FUNC float ismVisibilityFromStored(float distanceToLight, float stored, float depthBias)
{
    return distanceToLight <= stored * (1.0f + depthBias) ? 1.0f : 0.0f;
}

// The weighted mean of the valid values (those with weight > 0) within (1 + depthRange) times the
// nearest of them; kVPLNoOccluder when none is valid. Pull and push both reduce to it.
VPLGI_FUNC float ismNearMean(vec4 values, vec4 weights, float depthRange)
{
    float nearest = kVPLNoOccluder;
    for (int i = 0; i < 4; ++i)
        if (weights[i] > 0.0f) nearest = min(nearest, values[i]);
    if (!ismValid(nearest)) return kVPLNoOccluder;
    float limit = nearest * (1.0f + depthRange);
    float sum = 0.0f;
    float weight = 0.0f;
    for (int i = 0; i < 4; ++i) {
        float d = values[i];
        if (weights[i] > 0.0f && ismValid(d) && d <= limit) {
            sum += weights[i] * d;
            weight += weights[i];
        }
    }
    return sum / weight;
}

// Pull: one coarser texel from its four finer ones (any order), equally weighted.
VPLGI_FUNC float ismPull(vec4 finer, float depthRange)
{
    return ismNearMean(finer, vec4(1.0f), depthRange);
}

// Push: an empty finer texel from the four coarser texels around its centre, `coarser` with
// `weights` (9/16 for the parent, 3/16 for the two beside it, 1/16 diagonal; 0 for a neighbour
// outside the tile). A valid `own` value is kept.
VPLGI_FUNC float ismPush(float own, vec4 coarser, vec4 weights, float depthRange)
{
    if (ismValid(own)) return own;
    return ismNearMean(coarser, weights, depthRange);
}

// The coarser texel (in the coarser level's tile, size coarseSize) that finer texel `finer` reads
// as neighbour `which` (0 parent, 1 beside in x, 2 beside in y, 3 diagonal), and that neighbour's
// weight (0 when it falls outside the tile): the 9-3-3-1 bilinear stencil.
VPLGI_FUNC ivec2 ismPushNeighbour(ivec2 finer, int which)
{
    ivec2 parent = ivec2(finer.x / 2, finer.y / 2);
    ivec2 step = ivec2(finer.x % 2 == 1 ? 1 : -1, finer.y % 2 == 1 ? 1 : -1);
    ivec2 offset = ivec2((which == 1 || which == 3) ? step.x : 0, (which == 2 || which == 3) ? step.y : 0);
    return parent + offset;
}

VPLGI_FUNC float ismPushWeight(ivec2 finer, int which, int coarseSize)
{
    ivec2 c = ismPushNeighbour(finer, which);
    if (c.x < 0 || c.y < 0 || c.x >= coarseSize || c.y >= coarseSize) return 0.0f;
    return which == 0 ? 9.0f / 16.0f : (which == 3 ? 1.0f / 16.0f : 3.0f / 16.0f);
}

VPLGI_SHARED_END

#endif // VPLGI_SHARED_ISM_H
