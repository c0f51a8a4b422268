// LightSkin light caches: the precomputed surface samples that gather indirect light as proxy lights
// and hand it on to the pixels (paper 004 section 3, "Cache Distribution"; issue 11 part 1).
//
// Intro. LightSkin lights a few thousand caches spread over the scene instead of every pixel, then
// interpolates the caches' proxy lights to the pixels (eq. 8-9). A cache is a position, a normal, the
// area it represents (a Voronoi cell of the surface; the occlusion estimate turns it into a disk) and
// the mean reflectance of that surface. The two controls are the paper's: d_eps, the largest distance
// between a cache and the surface points it represents, and theta_eps, the largest angle between
// their normals.
//
// Overview (paper steps 1-5, per instance in world space; light_caches.cpp explains each choice):
//  1. Voxelise at edge d_eps / 2: clip every triangle against a grid of edge d_eps / 4 (exact pieces,
//     each with an area, centroid and geometric normal, on the side of the vertex normals); a piece
//     belongs to the d_eps / 2 voxel holding its centroid.
//  2. Bin the pieces' normals per voxel: cube-map faces x 8 x 8 direction bins.
//  3. Per voxel, while pieces remain: take the bin with the largest area; the cache is the
//     area-weighted mean position and normal of the remaining pieces within theta_eps of that bin's
//     centre normal (and the bin's own pieces); remove them.
//  4. Snap (optional): move each cache to the nearest point of the pieces it averaged.
//  5. Join (optional): merge caches closer than d_eps / 4 whose normals differ by less than theta_eps.
//  Area: every piece goes to the nearest cache within theta_eps of its normal (else the nearest
//  facing one, else the nearest); a cache's area is the sum of its pieces' areas.
//
// Double-sided materials get each cache twice, once per side (normal and area the same, the normal
// negated), as the G-buffer shows them from both sides.
//
// Per model: the paper distributes per model in model space; our scenes are instances of meshes, so
// caches are distributed per instance in world space, and the disk cache is keyed by the hash of the
// mesh's positions, normals and indices, the instance transform, the resolved parameters and the
// algorithm's constants (file version, direction bins, split epsilon); the file stores its key too.
//
// References: Lensing & Broll 2013 (LightSkin), Lensing 2014 (thesis); the BRSM + LightSkin paper in
// ../shared/papers/004_e7a2a609166487da.txt; ../shared/MATH.md section 9.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/scene.h"
#include "core/util/params.h"
#include "core/util/progress.h"
#include "glsl/shared/light_cache_lookup.h"

namespace vplgi {

struct LightCacheParams {
    // d_eps [m]; 0: automatic, d_eps = 2 sqrt(A / 2048) for the scene's total triangle area A,
    // rounded to two significant digits (a flat scene of area A then gets about 2048 caches; see
    // resolveLightCacheDistance).
    float distance = 0.0f;
    // N of the automatic d_eps = 2 sqrt(A / N) (ours, not in the paper): about the caches a flat scene
    // gets. The viewer on a software rasterizer halves it (app/view_command.cpp).
    int target = 2048;
    // theta_eps [degrees]. The paper gives no value. 30: the caches of two faces meeting at 90 degrees
    // (the corners of our architectural scenes) never mix (that needs an angle >= 45), a tessellated
    // curve of radius R merges into one cache per voxel once R > about 2 voxel edges, and the
    // cos(n_x, n_c) factor of eq. (8) stays above cos 30 = 0.87 for the surface a cache averaged.
    float angleDegrees = 30.0f;
    bool snap = true; // step 4: move each cache onto the surface it averaged
    bool join = true; // step 5: merge near-duplicate caches of neighbouring voxels
    void visitParams(ParamVisitor& visitor);
};

// clang-format off: one line per vec4 row, as the GPU reads it
struct LightCache { // world space; four vec4 rows, std430 as it is (64 bytes)
    glm::vec3 position{0.0f};
    float area = 0.0f; // area: the surface it represents (Voronoi) [m^2]
    glm::vec3 normal{0.0f, 1.0f, 0.0f};
    float roughness = 1.0f; // unit normal; perceptual roughness
    glm::vec3 diffuse{0.0f};
    float metallic = 0.0f; // (1 - metallic) baseColor (see below)
    glm::vec3 specular{0.0f};
    float backTwin = 0.0f; // F0 = mix(0.04 specular, baseColor, metallic); 1: the second cache of a double-sided pair
};
// clang-format on
static_assert(sizeof(LightCache) == 64, "LightCache is four vec4 rows");
// Material columns: an instance has one mesh and a mesh one material, so every cache of an instance
// has that material, untextured: the material factors times the means of their textures
// (computeUntexturedMaterials, the same table SMCIR's untextured VPLs use).

// The per-pixel lookup's cells: a spatial hash of a uniform grid (glsl/shared/light_cache_lookup.h).
struct LightCacheGrid {
    glm::vec3 origin{0.0f}; // the caches' lower corner: cell (0, 0, 0) starts here
    float cellSize = 1.0f;  // d_eps
    std::uint32_t slotMask = 0; // slots - 1: at least twice the occupied cells, a power of two
    int maxProbe = 0;           // the furthest an occupied cell's slot lies past its hash
    std::vector<glm::uvec4> slots;           // key low, key high (kLightCacheEmptySlot: free), begin, end
    std::vector<std::uint32_t> cacheIndices; // caches of each occupied cell, slot by slot, sorted by index
};

struct LightCacheSet {
    std::vector<LightCache> caches;
    LightCacheGrid grid;
    float distance = 0;                       // the d_eps used [m] (resolved when params.distance = 0)
    std::vector<std::uint32_t> instanceStart; // caches of instance i: [instanceStart[i], instanceStart[i+1])
    // Each cache's reach record (glsl/shared/light_cache_lookup.h; traceLightCacheReach in
    // traced_visibility.h): empty = no reach test, as the paper.
    std::vector<glm::uvec4> reach;
    int instancesLoaded = 0;   // instances read from the disk cache
    int instancesComputed = 0; // instances distributed (and written when a cacheDir is given)
};

// The d_eps that `params` ask for on `scene`: params.distance, or the automatic rule above when it is 0.
// Throws Error when the rule is needed and the scene has no triangle of positive area.
float resolveLightCacheDistance(const Scene& scene, const LightCacheParams& params);

// Eq. (11)'s clamp distance for `lightskin.importanceClamp` = `clamp`: clamp itself when > 0, else
// the automatic rule (ours): the paper's 1 scene unit, taken as 1 m on a street scene like the
// paper's (`street`: 93,148 m^2 of surface, whose automatic d_eps gives the paper's cache count),
// scaled with the scene's linear size: sqrt(A / 93148 m^2) for surface area A. The same scene in
// millimetres gets the same selection. Not the default (`lightskin.importanceClamp` 1, the paper's):
// over 8 seeds it narrowed the seeds' spread on cornell and canyon but widened it 4x on maze, a
// building in metres that it clamps at 0.2 m (docs/lightskin.md, "Scaling"). Throws Error when the
// rule is needed and the scene has no triangle of positive area.
float resolveImportanceClamp(const Scene& scene, float clamp);

// Distributes caches over every instance's triangles (see "per model" above), with progress
// ("lightskin caches", instances done / total), reading and writing the on-disk cache under
// `cacheDir` ("" = no disk cache): cacheDir/lightskin/<hex>.bin per instance. A missing, corrupt,
// truncated or misnamed (another key's) file is recomputed (a warning on stderr for all but the
// first); a file that cannot be written
// is a warning, not an error. Deterministic: the same input gives the same bits at any TBB thread count.
LightCacheSet distributeLightCaches(const Scene& scene, const LightCacheParams& params, const ProgressSink& progress,
                                    const std::string& cacheDir);

// Builds `set.grid` over set.caches with cell size `cellSize`: one slot per two occupied cells or
// fewer, cells inserted in key order (deterministic). Throws Error when the caches span
// kLightCacheCellAxisLimit cells or more along an axis. distributeLightCaches calls it with d_eps.
void buildLightCacheGrid(LightCacheSet& set, float cellSize);

// Readers for glsl/shared/light_cache_lookup.h (found by argument-dependent lookup).
inline glm::uvec4 lightCacheSlot(const LightCacheSet& set, int slot)
{
    return set.grid.slots[static_cast<std::size_t>(slot)];
}
inline std::uint32_t lightCacheIndex(const LightCacheSet& set, int i)
{
    return set.grid.cacheIndices[static_cast<std::size_t>(i)];
}
inline glm::vec3 lightCachePosition(const LightCacheSet& set, int cache)
{
    return set.caches[static_cast<std::size_t>(cache)].position;
}
inline glm::vec3 lightCacheNormal(const LightCacheSet& set, int cache)
{
    return set.caches[static_cast<std::size_t>(cache)].normal;
}
inline glm::uvec4 lightCacheReach(const LightCacheSet& set, int cache)
{
    return set.reach.empty() ? glm::uvec4(shared::kLightCacheReachOpen) : set.reach[static_cast<std::size_t>(cache)];
}

// The k <= 16 nearest caches to x facing n (n . n_c > 0) within the grid's cell size, nearest first,
// within their reach when set.reach is filled (the C++ instance of glsl/shared/light_cache_lookup.h).
// Returns out.count.
inline int nearestLightCaches(const LightCacheSet& set, const glm::vec3& x, const glm::vec3& n,
                              shared::LightCacheNeighbours& out, int k = shared::kMaxLightCacheNeighbours)
{
    out.count = 0;
    if (set.grid.slots.empty()) return 0;
    shared::findNearestLightCaches(set, set.grid.origin, set.grid.cellSize, set.grid.slotMask, set.grid.maxProbe, x, n,
                                   k, !set.reach.empty(), out);
    return out.count;
}

} // namespace vplgi
