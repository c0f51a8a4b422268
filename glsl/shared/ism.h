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
#include "shadow_atlas.h"
#include "vpl.h"

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
    vec3 w = vplParaboloidTexelDirection(texel, mapSize);
    float nw = dot(normal, w);
    float t = abs(nw) > 1.0e-6f ? dot(normal, toPoint) / nw : d;
    return clamp(t, max(d - radius, 0.0f), d + radius);
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
