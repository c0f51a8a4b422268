// Virtual point lights on the GPU and the arithmetic the VPL shading passes share with the CPU
// (the SMCIR and IR techniques: gl/techniques/vpl_technique.h).
//
// GpuVPL mirrors core/vpl/vpl.h's VPL: position, normal and the intensity I(y) = L(y)/p(y)
// [W/sr] of a cosine emitter; invalid slots have w = 0 in positionValid and are skipped.
//
// Interleaved sampling (SMCIR section 4, Keller & Heidrich 2001; MATH.md 7): the image is cut into
// tiles of T x T pixels (T = 4 in the paper), and pixel (x, y) belongs to class
//     c = (x mod T) + T (y mod T)
// which gathers the disjoint VPL subset S_c = {i : i mod T^2 = c}. With n valid VPLs the full
// estimator is (1/n) sum_i; a pixel of class c estimates it by (T^2/n) sum_{i in S_c}, so the mean
// of the T^2 classes over an aligned tile is exactly the full estimator (whatever the count of
// valid VPLs in each subset: the sums over the subsets add up to the sum over all VPLs).
#ifndef VPLGI_SHARED_VPL_H
#define VPLGI_SHARED_VPL_H
#include "compat.h"
#include "light_view.h"

VPLGI_SHARED_BEGIN

struct GpuVPL {
    vec4 positionValid; // xyz position [m], w = 1 valid, 0 empty slot
    vec4 normal;        // xyz unit normal (the side it emits towards), w unused
    vec4 intensity;     // rgb I(y) = L(y) / p(y) [W/sr], w unused
};

// The interleaving class of pixel `pixel` with tiles of `tile` x `tile` pixels (tile >= 1).
VPLGI_FUNC int vplInterleaveClass(ivec2 pixel, int tile)
{
    return (pixel.x % tile) + tile * (pixel.y % tile);
}

// The factor in front of a pixel's sum over its subset: classes / n (classes = tile^2; 1/n when
// every pixel gathers every VPL, tile = 1). 0 when there is no valid VPL.
VPLGI_FUNC float vplEstimatorScale(int validCount, int tile)
{
    return validCount > 0 ? float(tile * tile) / float(validCount) : 0.0f;
}

// The clamped geometry term between a shaded point x (normal nx) and a VPL y (normal ny), toVPL
// = y - x: cos+(nx . w) cos+(ny . -w) / |y - x|^2, at most clampGeometry when that is > 0 (MATH.md
// 1.2; core/vpl/vpl_gather.cpp computes the same in C++).
VPLGI_FUNC float vplGeometryTerm(vec3 nx, vec3 ny, vec3 toVPL, float clampGeometry)
{
    float distance2 = dot(toVPL, toVPL);
    if (!(distance2 > 0.0f)) return 0.0f;
    vec3 w = toVPL / sqrt(distance2);
    float cosX = dot(nx, w);
    float cosY = -dot(ny, w);
    if (cosX <= 0.0f || cosY <= 0.0f) return 0.0f;
    float g = cosX * cosY / distance2;
    return clampGeometry > 0.0f ? min(g, clampGeometry) : g;
}

// A VPL whose hemisphere faces are in the face atlas being resampled (gl/passes/vpl_shadow_maps).
struct VPLBatchItem {
    vec4 position; // xyz [m]
    vec4 normal;   // xyz unit
    ivec4 slot;    // x = the VPL's slot (its paraboloid map), y = its index in the batch (face tiles)
};

// The distance from the eye along unit direction `directionCube` (cube coordinates, MATH.md 6.3)
// of what a hemisphere face stored as window depth `depth` (0..1; 1 = nothing): the face's depth
// is linear-perspective in the axial distance z = 2 f n / ((f + n) - z_ndc (f - n)), and the
// direction's axial component is its component along the face's axis (MATH.md 6.4). Returns
// kVPLNoOccluder when nothing was drawn there.
VPLGI_CONST float kVPLNoOccluder = 1.0e30f;
VPLGI_FUNC float vplFaceDistance(float depth, vec3 directionCube, int face, float zNear, float zFar)
{
    if (depth >= 1.0f) return kVPLNoOccluder;
    float zNdc = 2.0f * depth - 1.0f;
    float axialDistance = 2.0f * zFar * zNear / ((zFar + zNear) - zNdc * (zFar - zNear));
    return axialDistance / max(directionCube[face], 1e-6f);
}

// The unit direction in the light frame of paraboloid texel `texel` of a map of `size` texels:
// the inverse map at the texel centre, with centres outside the unit disk pulled onto its rim (the
// horizon), so that every texel a lookup can reach holds a hemisphere direction.
VPLGI_FUNC vec3 vplParaboloidTexelDirection(ivec2 texel, int size)
{
    vec2 st = 2.0f * (vec2(float(texel.x), float(texel.y)) + vec2(0.5f)) / float(size) - vec2(1.0f);
    float r2 = dot(st, st);
    if (r2 > 1.0f) st = st / sqrt(r2);
    return paraboloidDirectionFromMap(0.5f * st + vec2(0.5f));
}

// The paraboloid texel a direction (light frame, z >= 0) falls in.
VPLGI_FUNC ivec2 vplParaboloidTexel(vec3 directionLight, int size)
{
    vec2 uv = paraboloidMapFromDirection(directionLight);
    ivec2 texel = ivec2(floor(uv * float(size)));
    return clamp(texel, ivec2(0), ivec2(size - 1));
}

VPLGI_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(vplgi::shared::VPLBatchItem) == 48, "VPLBatchItem must match std430");
static_assert(sizeof(vplgi::shared::GpuVPL) == 48, "GpuVPL must match std430");
#endif

#endif // VPLGI_SHARED_VPL_H
