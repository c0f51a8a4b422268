// LightSkin's per-point cache lookup (paper 004 section 3, "Interpolation using the Proxy Lights"):
// the k <= 16 caches nearest to a surface point x, for the Ward-style weights of eq. (8) and the
// interpolation of eq. (9). Compiled as GLSL (the interpolation pass) and as C++
// (core/lightskin/light_caches.h, nearestLightCaches: the CPU twin the tests check against brute force).
//
// The caches live in cells of a uniform grid (LightCacheGrid) kept as a spatial hash (ours; the paper
// does not say how the lookup finds its caches): only cells that hold a cache are stored, each in one
// slot of a table of 2^m slots found by hashing its integer coordinates (lightCacheCellHash) and
// probing linearly. A slot holds the cell's key and the range cacheIndices[begin .. end) of its
// caches, sorted by cache index. Memory follows the caches, not the scene's extent, so an open world
// keeps cellSize = d_eps (a dense grid had to be capped, and widened its cells and the search radius
// with them). A point's own cell and its 26 neighbours contain every cache closer than one cell edge,
// in every direction; caches further away are only partly covered (some directions reach two cells,
// others one), so the search takes exactly the caches with |x - c|^2 < cellSize^2: a fixed ball, the
// same in every direction. cellSize = d_eps, the largest distance between a surface point and its
// cache (paper section 3), so the ball holds the caches that can represent x.
//
// Only caches facing the point's side are candidates: eq. (8) weights a cache by (n_x . n_c)+, so a
// cache with n_x . n_c <= 0 gets weight zero and would only take a slot (and stretch d_c,max, the
// largest distance of the set, which eq. (8) divides by).
//
// The result is sorted by (squared distance, cache index): insertion into a fixed array of k slots,
// with the index breaking ties, so the set does not depend on the order cells are visited.
//
// Reach (ours, not in the paper; issue "LightSkin's indirect shadows", part 2): eq. (8) weighs caches
// by distance and normal only, so a cache on a floor lights the coplanar floor behind a wall, and a
// floor cache the floor of the storey above. Each cache carries its reach (lightCacheReaches): how
// far it sees along 15 directions around its normal, rising at kLightCacheReachSlope, and straight up
// its normal, traced once with Embree when the caches are made (core/lightskin/light_caches.h,
// traceLightCacheReach). A point beyond a cache's reach, or behind the cache's own surface, is not a
// candidate of that cache.
//
// The includer provides five readers, declared before including this header:
//   GLSL: uvec4 lightCacheSlot(int slot); uint lightCacheIndex(int i);
//         vec3 lightCachePosition(int cache); vec3 lightCacheNormal(int cache);
//         uvec4 lightCacheReach(int cache);
//   C++:  the same functions with a leading `const Caches&` argument, found by argument-dependent
//         lookup when findNearestLightCaches<Caches> is instantiated.
// LightCacheNeighbours holds arrays: it is a function-local result, never uploaded, so the "no
// arrays" rule of compat.h (which is about buffer layouts) does not apply to it.
#ifndef VPLGI_SHARED_LIGHT_CACHE_LOOKUP_H
#define VPLGI_SHARED_LIGHT_CACHE_LOOKUP_H
#include "compat.h"
#include "light_view.h"

#ifdef __cplusplus
#define VPLGI_CACHES_TEMPLATE template <typename Caches>
#define VPLGI_CACHES_PARAM const Caches &caches,
#define VPLGI_CACHES caches,
#else
#define VPLGI_CACHES_TEMPLATE
#define VPLGI_CACHES_PARAM
#define VPLGI_CACHES
#endif

VPLGI_SHARED_BEGIN

VPLGI_CONST int kMaxLightCacheNeighbours = 16; // the paper's 16 caches per point

struct LightCacheNeighbours {
    int count;                                 // valid entries, <= k
    int index[kMaxLightCacheNeighbours];       // cache indices, nearest first
    float distance2[kMaxLightCacheNeighbours]; // squared distances |x - c|^2 [m^2], ascending
};

// True when candidate (d2, i) sorts before (e2, j): nearer first, the lower index on a tie.
VPLGI_FUNC bool lightCacheBefore(float d2, int i, float e2, int j)
{
    return d2 < e2 || (d2 == e2 && i < j);
}

// --- The cells' spatial hash ---------------------------------------------------------------------
// Cell coordinates count from the grid's origin (the caches' lower corner), each below
// kLightCacheCellAxisLimit (2^21 cells of d_eps: 2000 km at 1 m), so a cell's key packs into 63 bits.
VPLGI_CONST int kLightCacheCellAxisLimit = 1 << 21;
VPLGI_CONST uint kLightCacheEmptySlot = 0xffffffffu; // a slot record's key-high word when the slot is free

// A slot record is a uvec4: the key's low and high words, then the first and the end entry of the
// cell's caches in cacheIndices. The key of a cell in [0, kLightCacheCellAxisLimit)^3: x in bits 0-20,
// y in 21-41, z in 42-62 (so the high word is below 2^31 and never kLightCacheEmptySlot).
VPLGI_FUNC uvec2 lightCacheCellKey(ivec3 cell)
{
    uint x = uint(cell.x), y = uint(cell.y), z = uint(cell.z);
    return uvec2(x | (y << 21u), (y >> 11u) | (z << 10u));
}

// The slot a cell's probing starts at, before masking (Teschner et al. 2003's three primes).
VPLGI_FUNC uint lightCacheCellHash(ivec3 cell)
{
    return (uint(cell.x) * 73856093u) ^ (uint(cell.y) * 19349663u) ^ (uint(cell.z) * 83492791u);
}

// Finds the slot of `cell` (inside [0, kLightCacheCellAxisLimit)^3) in a table of slotMask + 1 slots
// where no cell lies more than maxProbe slots past its hash: true and the slot's record, or false
// when the cell holds no cache (a free slot, or maxProbe + 1 slots without its key).
VPLGI_CACHES_TEMPLATE
VPLGI_FUNC bool findLightCacheCell(VPLGI_CACHES_PARAM ivec3 cell, uint slotMask, int maxProbe, VPLGI_OUT(uvec4) record)
{
    uvec2 key = lightCacheCellKey(cell);
    uint slot = lightCacheCellHash(cell) & slotMask;
    for (int probe = 0; probe <= maxProbe; ++probe) {
        record = lightCacheSlot(VPLGI_CACHES int(slot));
        if (record.x == key.x && record.y == key.y) return true;
        if (record.y == kLightCacheEmptySlot) return false;
        slot = (slot + 1u) & slotMask;
    }
    return false;
}

// --- Reach -----------------------------------------------------------------------------------------
// A cache's reach record is one uvec4 of 16 bytes (byte i is bits 8 (i % 4) .. +7 of word i / 4):
// bytes 0-14 the reach along the directions at azimuths 2 pi i / 15 in the cache's frame
// (lightViewBasis: x, y tangents, z its normal), byte 15 the reach along the normal. A byte b is the
// distance b / 255 of the search radius, measured in the tangent plane for the azimuths (floored: a
// record never reaches further than the ray did); 255 = nothing within the radius.
VPLGI_CONST int kLightCacheReachAzimuths = 15;
// The rays start kLightCacheReachLift of the search radius above the cache (off its own surface) and
// rise at this slope: tan 15 degrees, half the default theta_eps (LightCacheParams::angleDegrees). A
// concave surface whose normal turns by at most theta_eps within the search radius stays below the
// ray: the chord from the cache to a point at arc length s rises at (theta_eps / 2) (s / radius) at
// most. The same slope bounds how far below the cache's tangent plane a point of a convex surface
// may lie (the "behind" test).
VPLGI_CONST float kLightCacheReachSlope = 0.26795f;
VPLGI_CONST float kLightCacheReachLift = 1.0f / 64.0f;
VPLGI_CONST uint kLightCacheReachOpen = 0xffffffffu; // every word of a record that reaches everywhere
// With the reach, a cache is a candidate only within 60 degrees of the point's normal (cos 60 = 0.5):
// a cache at right angles to the point (a wall's cache for a floor point) has an eq. (8) weight near
// 0 but would take the whole weight where it is the only candidate, and its tangent-plane reach
// cannot tell on which side of a wall the point lies (the sealed rooms' floor beside the shared wall
// took the other room's wall caches). Every surface point has a cache within theta_eps = 30 degrees
// of its normal and d_eps of its position (the distribution's guarantee), so no point loses its own.
VPLGI_CONST float kLightCacheReachMinCos = 0.5f;

// The unit direction of reach ray i (i < 15: azimuth i, rising; i = 15: along the normal).
VPLGI_FUNC vec3 lightCacheReachDirection(vec3 normal, int i)
{
    if (i >= kLightCacheReachAzimuths) return normal;
    mat3 frame = lightViewBasis(normal);
    float azimuth = 6.28318531f * float(i) / float(kLightCacheReachAzimuths);
    vec3 tangent = cos(azimuth) * frame[0] + sin(azimuth) * frame[1];
    return normalize(tangent + kLightCacheReachSlope * normal);
}

// Byte i of a reach record as a distance in units of the search radius.
VPLGI_FUNC float lightCacheReachFraction(uvec4 reach, int i)
{
    return float((reach[i / 4] >> uint(8 * (i % 4))) & 0xffu) / 255.0f;
}

// The distance along the unit direction u (tangent-plane coordinates) to the line through p and q,
// at most `radius`; `radius` when u runs parallel to the line or away from it.
VPLGI_FUNC float lightCacheReachToLine(vec2 u, vec2 p, vec2 q, float radius)
{
    vec2 d = q - p;
    float denominator = u.x * d.y - u.y * d.x;
    float t = denominator != 0.0f ? (p.x * d.y - p.y * d.x) / denominator : -1.0f;
    return t > 0.0f ? min(t, radius) : radius;
}

// The distance along u to the wall through the hit points p and q of two reach rays
// (lightCacheReachToLine), or `radius` when either ray hit nothing.
VPLGI_FUNC float lightCacheReachToWall(bool hitP, vec2 p, bool hitQ, vec2 q, vec2 u, float radius)
{
    return hitP && hitQ ? lightCacheReachToLine(u, p, q, radius) : radius;
}

// cos and sin of the angle between neighbouring reach rays, 2 pi / 15.
VPLGI_CONST float kLightCacheReachStepCos = 0.91354546f;
VPLGI_CONST float kLightCacheReachStepSin = 0.40673664f;

// d turned by +-2 pi / 15 in the tangent plane.
VPLGI_FUNC vec2 lightCacheReachTurn(vec2 d, float sign)
{
    return vec2(kLightCacheReachStepCos * d.x - sign * kLightCacheReachStepSin * d.y,
                sign * kLightCacheReachStepSin * d.x + kLightCacheReachStepCos * d.y);
}

// True when the point at `offset` (x - c) from a cache with normal `normal` lies within the cache's
// reach (search radius `radius`): not behind the cache's own surface, not beyond what lies above the
// cache, and no further along the tangent plane than the cache sees in that direction. Between two
// azimuths whose rays both hit, the obstacle is the line through the two hits (exact for a straight
// wall) or, beyond it, the nearer of the lines through each hit and its outer neighbour (exact in a
// concave corner); where one of them hit nothing, the line through the other hit and the hit beyond it,
// extended (so a wall seen from a cache beside it ends where it runs parallel to the direction, not
// at the open ray's radius); a lone hit counts up to the half-way azimuth. Tolerance: the lift
// (quantization takes up to 1/255 of the radius).
// Speed (not in the paper): the four rays around the point's azimuth (before, i0, i1, after) are read
// once, their directions come from one cos/sin pair turned by the fixed step, and the three walls are
// evaluated for every case, then selected: on llvmpipe each branch costs what its costliest lane does
// and every call to cos/sin counts, and this test took about half of the interpolation pass when each
// wall computed its own two directions (docs/lightskin.md, "The technique": the lookup's probes).
VPLGI_FUNC bool lightCacheReaches(uvec4 reach, vec3 normal, vec3 offset, float radius)
{
    float lift = kLightCacheReachLift * radius;
    float height = dot(normal, offset);
    vec3 tangential = offset - height * normal;
    float along = length(tangential);
    if (height < -lift - kLightCacheReachSlope * along) return false; // behind the cache's surface
    if (height > lightCacheReachFraction(reach, kLightCacheReachAzimuths) * radius + lift) return false;
    if (along <= lift) return true;
    mat3 frame = lightViewBasis(normal);
    vec2 u = vec2(dot(tangential, frame[0]), dot(tangential, frame[1])) / along;
    float azimuth = atan(u.y, u.x);
    float s = (azimuth < 0.0f ? azimuth + 6.28318531f : azimuth) * (float(kLightCacheReachAzimuths) / 6.28318531f);
    int n = kLightCacheReachAzimuths;
    int i0 = min(int(floor(s)), n - 1);
    int i1 = (i0 + 1) % n, before = (i0 + n - 1) % n, after = (i1 + 1) % n;
    float fBefore = lightCacheReachFraction(reach, before), f0 = lightCacheReachFraction(reach, i0);
    float f1 = lightCacheReachFraction(reach, i1), fAfter = lightCacheReachFraction(reach, after);
    bool hitBefore = fBefore < 1.0f, hit0 = f0 < 1.0f, hit1 = f1 < 1.0f, hitAfter = fAfter < 1.0f;
    // Where each ray stopped, in the tangent plane's (x, y) [m] (a ray that hit nothing: the radius).
    // Ray i0's direction is u turned back by the angle t past it, t in [0, 2 pi / 15]: cos t and
    // sin t by their Taylor series to t^8 and t^9 (truncation below 2e-10 at t = 0.42; cheaper than
    // cos and sin of the full angle on llvmpipe).
    float t = (s - float(i0)) * (6.28318531f / float(kLightCacheReachAzimuths));
    float t2 = t * t;
    float cosT = 1.0f + t2 * (-1.0f / 2.0f + t2 * (1.0f / 24.0f + t2 * (-1.0f / 720.0f + t2 * (1.0f / 40320.0f))));
    float sinT = t * (1.0f + t2 * (-1.0f / 6.0f + t2 * (1.0f / 120.0f + t2 * (-1.0f / 5040.0f + t2 * (1.0f / 362880.0f)))));
    vec2 d0 = vec2(cosT * u.x + sinT * u.y, cosT * u.y - sinT * u.x);
    vec2 d1 = lightCacheReachTurn(d0, 1.0f);
    vec2 p0 = f0 * radius * d0, p1 = f1 * radius * d1;
    vec2 pBefore = fBefore * radius * lightCacheReachTurn(d0, -1.0f);
    vec2 pAfter = fAfter * radius * lightCacheReachTurn(d1, 1.0f);
    float chord = lightCacheReachToWall(hit0, p0, hit1, p1, u, radius);
    float wallBefore = lightCacheReachToWall(hitBefore, pBefore, hit0, p0, u, radius);
    float wallAfter = lightCacheReachToWall(hit1, p1, hitAfter, pAfter, u, radius);
    bool nearHalf0 = s - float(i0) <= 0.5f;
    float reachHere = radius;
    if (hit0 && hit1)
        // The chord through the two hits, or the nearer of the walls through their outer neighbours
        // where that lies beyond the chord: a concave corner between the rays (the chord would cut
        // it off; the room is the intersection of its walls' half-planes).
        reachHere = max(chord, min(wallBefore, wallAfter));
    else if (hit1)
        reachHere = hitAfter ? wallAfter : (!nearHalf0 ? f1 * radius : radius);
    else if (hit0)
        reachHere = hitBefore ? wallBefore : (nearHalf0 ? f0 * radius : radius);
    return along <= reachHere + lift;
}

// The k (clamped to [0, 16]) nearest caches to x with n_x . n_c > 0 and |x - c| < cellSize, searched
// in the 3 x 3 x 3 cells around x of the grid (origin, cellSize; its hash table of slotMask + 1
// slots, maxProbe as findLightCacheCell). A point outside the grid searches the cells of its block
// that exist. With `useReach`, only caches whose reach holds x
// (lightCacheReaches with the radius cellSize) and within 60 degrees of n (kLightCacheReachMinCos);
// when no cache reaches x (0.1-0.2% of the points the
// built-in scenes' cameras see, in doorways and tight corners where the 15 rays miss an opening),
// the caches without the test rather than a black pixel.
VPLGI_CACHES_TEMPLATE
VPLGI_FUNC void findNearestLightCaches(VPLGI_CACHES_PARAM vec3 gridOrigin, float cellSize, uint slotMask, int maxProbe,
                                       vec3 x, vec3 n, int k, bool useReach, VPLGI_OUT(LightCacheNeighbours) result)
{
    result.count = 0;
    int slots = min(max(k, 0), kMaxLightCacheNeighbours);
    if (slots == 0) return;
    float radius2 = cellSize * cellSize;
    for (int pass = useReach ? 0 : 1; pass < 2 && result.count == 0; ++pass) {
        vec3 cellPosition = floor((x - gridOrigin) / cellSize);
        // Clamp before converting: a point far outside the grid must not overflow int.
        cellPosition = clamp(cellPosition, vec3(-2.0f), vec3(float(kLightCacheCellAxisLimit) + 1.0f));
        ivec3 centre = ivec3(cellPosition);
        for (int dz = -1; dz <= 1; ++dz) {
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    ivec3 cell = centre + ivec3(dx, dy, dz);
                    if (cell.x < 0 || cell.y < 0 || cell.z < 0 || cell.x >= kLightCacheCellAxisLimit ||
                        cell.y >= kLightCacheCellAxisLimit || cell.z >= kLightCacheCellAxisLimit)
                        continue;
                    // Speed only: a cell whose box lies wholly outside the search ball holds no candidate
                    // (the box grown by a thousandth of a cell, so a cache that rounding put in the cell
                    // from just outside it is still searched). A corner cell is skipped for about half
                    // the points, an edge cell for a fifth.
                    vec3 cellMin = gridOrigin + vec3(cell) * cellSize;
                    vec3 gap = max(max(cellMin - x, x - cellMin - vec3(cellSize)) - vec3(1e-3f * cellSize), vec3(0.0f));
                    if (!(dot(gap, gap) < radius2)) continue;
                    uvec4 record = uvec4(0u);
                    if (!findLightCacheCell(VPLGI_CACHES cell, slotMask, maxProbe, record)) continue;
                    int begin = int(record.z);
                    int end = int(record.w);
                    for (int i = begin; i < end; ++i) {
                        int cache = int(lightCacheIndex(VPLGI_CACHES i));
                        vec3 cacheNormal = lightCacheNormal(VPLGI_CACHES cache);
                        if (!(dot(n, cacheNormal) > 0.0f)) continue; // eq. (8) weight 0
                        vec3 offset = x - lightCachePosition(VPLGI_CACHES cache);
                        float d2 = dot(offset, offset);
                        if (!(d2 < radius2)) continue;
                        if (pass == 0 &&
                            (!(dot(n, cacheNormal) > kLightCacheReachMinCos) ||
                             !lightCacheReaches(lightCacheReach(VPLGI_CACHES cache), cacheNormal, offset, cellSize)))
                            continue;
                        if (result.count == slots &&
                            !lightCacheBefore(d2, cache, result.distance2[slots - 1], result.index[slots - 1]))
                            continue;
                        // Insertion: shift the farther entries one slot up (the last one drops out when full).
                        int j = min(result.count, slots - 1);
                        while (j > 0 && lightCacheBefore(d2, cache, result.distance2[j - 1], result.index[j - 1])) {
                            result.distance2[j] = result.distance2[j - 1];
                            result.index[j] = result.index[j - 1];
                            --j;
                        }
                        result.distance2[j] = d2;
                        result.index[j] = cache;
                        result.count = min(result.count + 1, slots);
                    }
                }
            }
        }
    }
}

VPLGI_SHARED_END

#endif // VPLGI_SHARED_LIGHT_CACHE_LOOKUP_H
