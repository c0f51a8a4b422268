// LightSkin's per-point cache lookup (paper 004 section 3, "Interpolation using the Proxy Lights"):
// the k <= 16 caches nearest to a surface point x, for the Ward-style weights of eq. (8) and the
// interpolation of eq. (9). Compiled as GLSL (the interpolation pass) and as C++
// (core/lightskin/light_caches.h, nearestLightCaches: the CPU twin the tests check against brute force).
//
// The caches live in a uniform grid (LightCacheGrid): cell c holds the caches whose position falls in
// it, as cacheIndices[cellStart[c] .. cellStart[c+1]), sorted by cache index. A point's own cell and
// its 26 neighbours contain every cache closer than one cell edge, in every direction; caches further
// away are only partly covered (some directions reach two cells, others one), so the search takes
// exactly the caches with |x - c|^2 < cellSize^2: a fixed ball, the same in every direction. The grid
// is built with cellSize = d_eps (larger only when the cell count is capped), and d_eps is the largest
// distance between a surface point and its cache (paper section 3), so the ball holds the caches that
// can represent x.
//
// Only caches facing the point's side are candidates: eq. (8) weights a cache by (n_x . n_c)+, so a
// cache with n_x . n_c <= 0 gets weight zero and would only take a slot (and stretch d_c,max, the
// largest distance of the set, which eq. (8) divides by).
//
// The result is sorted by (squared distance, cache index): insertion into a fixed array of k slots,
// with the index breaking ties, so the set does not depend on the order cells are visited.
//
// The includer provides four readers, declared before including this header:
//   GLSL: uint lightCacheCellStart(int cell); uint lightCacheIndex(int i);
//         vec3 lightCachePosition(int cache); vec3 lightCacheNormal(int cache);
//   C++:  the same functions with a leading `const Caches&` argument, found by argument-dependent
//         lookup when findNearestLightCaches<Caches> is instantiated.
// LightCacheNeighbours holds arrays: it is a function-local result, never uploaded, so the "no
// arrays" rule of compat.h (which is about buffer layouts) does not apply to it.
#ifndef VPLGI_SHARED_LIGHT_CACHE_LOOKUP_H
#define VPLGI_SHARED_LIGHT_CACHE_LOOKUP_H
#include "compat.h"

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

// The k (clamped to [0, 16]) nearest caches to x with n_x . n_c > 0 and |x - c| < cellSize, searched
// in the 3 x 3 x 3 cells around x of the grid (origin, cellSize, dims). A point outside the grid
// searches the cells of its block that exist.
VPLGI_CACHES_TEMPLATE
VPLGI_FUNC void findNearestLightCaches(VPLGI_CACHES_PARAM vec3 gridOrigin, float cellSize, ivec3 gridDims, vec3 x,
                                       vec3 n, int k, VPLGI_OUT(LightCacheNeighbours) result)
{
    result.count = 0;
    int slots = min(max(k, 0), kMaxLightCacheNeighbours);
    if (slots == 0) return;
    float radius2 = cellSize * cellSize;
    vec3 cellPosition = floor((x - gridOrigin) / cellSize);
    // Clamp before converting: a point far outside the grid must not overflow int.
    cellPosition = clamp(cellPosition, vec3(-2.0f), vec3(gridDims) + vec3(1.0f));
    ivec3 centre = ivec3(cellPosition);
    for (int dz = -1; dz <= 1; ++dz) {
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                ivec3 cell = centre + ivec3(dx, dy, dz);
                if (cell.x < 0 || cell.y < 0 || cell.z < 0 || cell.x >= gridDims.x || cell.y >= gridDims.y ||
                    cell.z >= gridDims.z)
                    continue;
                int cellIndex = (cell.z * gridDims.y + cell.y) * gridDims.x + cell.x;
                int begin = int(lightCacheCellStart(VPLGI_CACHES cellIndex));
                int end = int(lightCacheCellStart(VPLGI_CACHES cellIndex + 1));
                for (int i = begin; i < end; ++i) {
                    int cache = int(lightCacheIndex(VPLGI_CACHES i));
                    if (!(dot(n, lightCacheNormal(VPLGI_CACHES cache)) > 0.0f)) continue; // eq. (8) weight 0
                    vec3 offset = lightCachePosition(VPLGI_CACHES cache) - x;
                    float d2 = dot(offset, offset);
                    if (!(d2 < radius2)) continue;
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

VPLGI_SHARED_END

#endif // VPLGI_SHARED_LIGHT_CACHE_LOOKUP_H
