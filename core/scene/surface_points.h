// Points spread uniformly over a scene's surface area: the point set that imperfect shadow maps
// splat (gl/passes/imperfect_shadow_maps.h; Ritschel et al. 2008, MATH.md 10.2).
//
// Every triangle of every instance (in world space) is chosen with probability proportional to its
// area, then a point is drawn uniformly inside it (barycentrics (1 - sqrt(u1), sqrt(u1) (1 - u2),
// sqrt(u1) u2)). The points are i.i.d., so every run of consecutive points is itself a uniform
// sample of the surface: the ISM pass hands each light such a run. One PCG32 stream keyed by the
// seed: the same scene and seed give the same points on every machine and thread count.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/scene.h"

namespace vplgi {

struct SurfacePoints {
    std::vector<glm::vec3> positions; // world space [m]
    std::vector<glm::vec3> normals;   // unit geometric normals of the front (Instance::winding), world space
    double totalArea = 0.0;           // world-space area of all triangles [m^2]; with alpha masks, the part
                                      // they keep as the draws estimate it (exact without masks)
};

// `count` points (>= 0) uniform over the surface area of `scene` that its alpha masks keep (throws
// Error when count > 0 and the scene has no triangle of positive area, or its masks keep almost none). blockSize 0: i.i.d. points. blockSize n > 0 (ours,
// for imperfect shadow maps): each block of n consecutive points (points i with the same i / n) is a
// stratified sample, the k-th drawn from the k-th n-th of the area in triangle order, so every
// triangle gets its share of a block within one point, and any n consecutive points still cover the
// area once (a run that starts inside a block ends at the same place of the next).
SurfacePoints sampleSurfacePoints(const Scene& scene, int count, std::uint64_t seed, int blockSize = 0);

// How far each point's disk of radius `radius` in its tangent plane stays on the surface the points
// sample (ours, the imperfect shadow maps' reach: glsl/shared/ism.h, ismWithinReach), packed per
// point as that function reads it: for each of the 8 sectors around the point, 4 when the spot at
// the whole radius along the sector's central direction finds the surface, else the largest j < 4
// such that every spot at i radius / 4, i = 1 .. j, does; a spot finds the surface when some point
// of the set lies within `tolerance` of it with a normal within 45 degrees of the point's own
// (either orientation). (The spot at the whole radius first: most sectors end there, 8 probes per
// point instead of 32.) A wall's points reach the whole radius inside it and stop at
// its edges; a column's stop where it curves away. tolerance = max(radius / 4, 1.5 x the set's
// spacing sqrt(totalArea / n)), so that a spot on a flat surface expects at least pi 1.5^2 = 7
// points within it and misses with probability about e^-7 = 0.1%; with a tolerance as large as the
// radius (a sparse set) every point gets the whole disk. The imperfect shadow maps' defaults (64 set
// points per run point) give a tolerance of about radius / 4. Deterministic; runs in parallel (TBB).
std::vector<std::uint32_t> surfaceReach(const SurfacePoints& points, float radius);

} // namespace vplgi
