// LightSkin cache distribution (paper 004 section 3, steps 1-5). The header has the overview; here
// each step says what the paper leaves open and what we chose.
#include "core/lightskin/light_caches.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <system_error>
#include <utility>

#include <glm/gtc/type_precision.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/scene/surface.h"
#include "core/util/content_hash.h"
#include "core/util/error.h"

namespace vplgi {

void LightCacheParams::visitParams(ParamVisitor& v)
{
    v.field("lightskin.cacheDistance", distance, 0.0f, 1e4f,
            "d_eps: largest distance between a light cache and the surface it represents [m]; "
            "0 = automatic, 2 sqrt(A / N) for the scene's surface area A and N = lightskin.cacheTarget");
    v.field("lightskin.cacheTarget", target, 16, 1 << 20,
            "N of the automatic d_eps: about the light caches a flat scene gets (not in the paper)");
    v.field("lightskin.cacheAngle", angleDegrees, 1.0f, 89.0f,
            "theta_eps: largest angle between a light cache's normal and its surface's normals [degrees]");
    v.field("lightskin.cacheSnap", snap, "move each light cache onto the surface it averaged (paper step 4)");
    v.field("lightskin.cacheJoin", join, "merge near-duplicate light caches of neighbouring voxels (paper step 5)");
}

namespace {

constexpr int kBinsPerFaceEdge = 8;       // step 2: 6 x 8 x 8 direction bins
constexpr double kSplitEpsilon = 1e-4;    // [fine voxel edges]: see splitAlong
constexpr std::uint32_t kFileVersion = 2; // bump when the distribution or the file layout changes (2: the key inside)
constexpr char kFileMagic[8] = {'V', 'P', 'L', 'G', 'L', 'S', 'C', 'A'};
constexpr double kMaxPieces = 1e7;          // step 1 pieces per instance (one at a time): about 2 GB

// The geometry of one cache before the material is attached (what the disk cache stores).
struct CacheGeometry {
    glm::vec3 position;
    glm::vec3 normal;
    float area;
};
static_assert(sizeof(CacheGeometry) == 28, "seven floats per cache on disk");

// --- Step 1: voxelisation by clipping --------------------------------------------------------------

using Polygon = std::vector<glm::dvec3>; // convex, planar, in fine-voxel coordinates

// Splits `poly` by the plane coordinate[axis] = k into the parts below and above (a vertex on the
// plane goes to both). The intersection point gets exactly k on the axis, so neighbouring pieces
// share their boundary bit for bit.
void clipAt(const Polygon& poly, int axis, double k, Polygon& below, Polygon& above)
{
    below.clear();
    above.clear();
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3& p = poly[i];
        const glm::dvec3& q = poly[(i + 1) % n];
        const double dp = p[axis] - k, dq = q[axis] - k;
        if (dp <= 0.0) below.push_back(p);
        if (dp >= 0.0) above.push_back(p);
        if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) {
            glm::dvec3 r = p + (dp / (dp - dq)) * (q - p);
            r[axis] = k;
            below.push_back(r);
            above.push_back(r);
        }
    }
}

// Cuts `poly` at every integer plane of `axis` it crosses by more than kSplitEpsilon on both sides.
// The margin is what keeps slivers out: a face that should lie on a grid plane (a box of size a
// multiple of the voxel edge) lands a rounding error beside it, and cutting there would give a piece
// of zero width in the next voxel and with it a spurious cache. Uncut, the piece overhangs its voxel
// by less than 1e-4 edges and belongs to the voxel of its centroid like every piece.
void splitAlong(const Polygon& poly, int axis, std::vector<Polygon>& out)
{
    double lo = poly[0][axis], hi = lo;
    for (const glm::dvec3& p : poly) {
        lo = std::min(lo, p[axis]);
        hi = std::max(hi, p[axis]);
    }
    const double first = std::floor(lo + kSplitEpsilon) + 1.0;
    const double last = std::ceil(hi - kSplitEpsilon) - 1.0;
    Polygon current = poly, below, above;
    for (double k = first; k <= last; k += 1.0) {
        clipAt(current, axis, k, below, above);
        if (below.size() >= 3) out.push_back(below);
        current.swap(above);
        if (current.size() < 3) return;
    }
    out.push_back(std::move(current));
}

// A part of one triangle inside one fine voxel: the "surface points" of steps 1-3 and of the area.
struct Piece {
    glm::dvec3 centroid; // world [m]
    glm::dvec3 normal;   // unit geometric normal (triangle winding), world
    double area;         // [m^2]
    std::uint64_t voxel; // key of its d_eps / 2 voxel
    int bin;             // step 2 direction bin of `normal`
    std::uint32_t firstVertex;
    std::uint32_t vertexCount;
};

struct Pieces {
    std::vector<Piece> pieces;
    std::vector<glm::dvec3> vertices; // polygons of the pieces, world, for snapping
};

// The voxel grid of one instance. Voxels (edge h = d_eps / 2) are indexed from the instance's lower
// bound; pieces come from a grid of edge h / 2 nested in it (every voxel plane is also a fine plane),
// so each voxel's surface is split into about four pieces per h^2 of area: finer means and a finer
// Voronoi partition for the area, at four times the pieces of a plain d_eps / 2 clip.
struct VoxelGrid {
    glm::dvec3 origin{0.0};
    double edge = 1.0;    // h [m]
    glm::i64vec3 dims{1}; // voxels per axis

    std::uint64_t key(const glm::i64vec3& v) const
    {
        return static_cast<std::uint64_t>(v.x + dims.x * (v.y + dims.y * v.z));
    }
    glm::i64vec3 voxelOf(const glm::dvec3& world) const
    {
        const glm::dvec3 u = glm::floor((world - origin) / edge);
        return glm::clamp(glm::i64vec3(u), glm::i64vec3(0), dims - glm::i64vec3(1));
    }
};

// --- Step 2: direction bins ---------------------------------------------------------------------------

// Cube-map face (the largest |component|, x before y before z on a tie) times an 8 x 8 grid on it.
int binOf(const glm::dvec3& n)
{
    const glm::dvec3 a = glm::abs(n);
    const int axis = (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
    const int face = 2 * axis + (n[axis] < 0.0 ? 1 : 0);
    const double major = a[axis];
    const double s = n[(axis + 1) % 3] / major, t = n[(axis + 2) % 3] / major;
    const int i = std::clamp(static_cast<int>((s + 1.0) * 0.5 * kBinsPerFaceEdge), 0, kBinsPerFaceEdge - 1);
    const int j = std::clamp(static_cast<int>((t + 1.0) * 0.5 * kBinsPerFaceEdge), 0, kBinsPerFaceEdge - 1);
    return (face * kBinsPerFaceEdge + j) * kBinsPerFaceEdge + i;
}

glm::dvec3 binCentre(int bin)
{
    const int i = bin % kBinsPerFaceEdge;
    const int j = (bin / kBinsPerFaceEdge) % kBinsPerFaceEdge;
    const int face = bin / (kBinsPerFaceEdge * kBinsPerFaceEdge);
    const int axis = face / 2;
    glm::dvec3 v(0.0);
    v[axis] = (face % 2 == 0) ? 1.0 : -1.0;
    v[(axis + 1) % 3] = (i + 0.5) / kBinsPerFaceEdge * 2.0 - 1.0;
    v[(axis + 2) % 3] = (j + 0.5) / kBinsPerFaceEdge * 2.0 - 1.0;
    return glm::normalize(v);
}

// `world`: vertex positions; `side`: per vertex a direction on the surface's outer side (the world
// shading normal), which decides the side of each triangle's geometric normal.
Pieces clipInstance(const std::vector<glm::dvec3>& world, const std::vector<glm::dvec3>& side,
                    const std::vector<std::uint32_t>& indices, const VoxelGrid& grid)
{
    const double fine = 0.5 * grid.edge;
    const std::size_t triangles = indices.size() / 3;
    constexpr std::size_t kBlock = 256;
    const std::size_t blocks = (triangles + kBlock - 1) / kBlock;
    std::vector<Pieces> perBlock(blocks);
    // Blocks of triangles in parallel; the blocks are concatenated in order, so the pieces (and
    // everything after) do not depend on the thread count.
    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t block) {
        Pieces& out = perBlock[block];
        std::vector<Polygon> stage, next;
        for (std::size_t t = block * kBlock; t < std::min(triangles, (block + 1) * kBlock); ++t) {
            const glm::dvec3& a = world[indices[3 * t]];
            const glm::dvec3& b = world[indices[3 * t + 1]];
            const glm::dvec3& c = world[indices[3 * t + 2]];
            const glm::dvec3 cross = glm::cross(b - a, c - a);
            const double length = glm::length(cross);
            if (!(length > 0.0) || !std::isfinite(length)) continue; // degenerate: no area to represent
            // The geometric normal on the side of the vertex normals, as the renderer keeps it
            // (core/scene/surface.cpp): a mirroring transform reverses the winding, not the side.
            const glm::dvec3 shading = side[indices[3 * t]] + side[indices[3 * t + 1]] + side[indices[3 * t + 2]];
            const glm::dvec3 winding = cross / length; // the pieces' vertex order: their areas are > 0 along it
            const glm::dvec3 normal = glm::dot(cross, shading) < 0.0 ? -winding : winding;
            stage.assign(1, Polygon{(a - grid.origin) / fine, (b - grid.origin) / fine, (c - grid.origin) / fine});
            for (int axis = 0; axis < 3; ++axis) {
                next.clear();
                for (const Polygon& p : stage)
                    splitAlong(p, axis, next);
                stage.swap(next);
            }
            for (const Polygon& p : stage) {
                // Fan triangulation (the piece is convex): area and centroid in world units.
                double area = 0.0;
                glm::dvec3 centroid(0.0);
                std::vector<glm::dvec3> corners;
                for (const glm::dvec3& u : p)
                    corners.push_back(grid.origin + u * fine);
                for (std::size_t i = 1; i + 1 < corners.size(); ++i) {
                    const double part =
                        0.5 * glm::dot(glm::cross(corners[i] - corners[0], corners[i + 1] - corners[0]), winding);
                    area += part;
                    centroid += part * (corners[0] + corners[i] + corners[i + 1]) / 3.0;
                }
                if (!(area > 0.0)) continue;
                centroid /= area;
                Piece piece;
                piece.centroid = centroid;
                piece.normal = normal;
                piece.area = area;
                piece.voxel = grid.key(grid.voxelOf(centroid));
                piece.bin = binOf(normal);
                piece.firstVertex = static_cast<std::uint32_t>(out.vertices.size());
                piece.vertexCount = static_cast<std::uint32_t>(corners.size());
                out.vertices.insert(out.vertices.end(), corners.begin(), corners.end());
                out.pieces.push_back(piece);
            }
        }
    });
    Pieces all;
    for (Pieces& block : perBlock) {
        const auto offset = static_cast<std::uint32_t>(all.vertices.size());
        for (Piece& p : block.pieces) {
            p.firstVertex += offset;
            all.pieces.push_back(p);
        }
        all.vertices.insert(all.vertices.end(), block.vertices.begin(), block.vertices.end());
    }
    return all;
}

// --- Step 3: caches per voxel ----------------------------------------------------------------------

struct Cluster {
    glm::dvec3 position{0.0};
    glm::dvec3 normal{0.0, 1.0, 0.0};
    double weight = 0.0;               // area of the pieces averaged [m^2]
    std::vector<std::uint32_t> pieces; // indices into Pieces::pieces, ascending
};

// Area-weighted mean position and normal of `members`.
Cluster averagePieces(const Pieces& all, std::vector<std::uint32_t> members)
{
    Cluster c;
    glm::dvec3 positionSum(0.0), normalSum(0.0);
    for (std::uint32_t m : members) {
        const Piece& p = all.pieces[m];
        positionSum += p.area * p.centroid;
        normalSum += p.area * p.normal;
        c.weight += p.area;
    }
    c.position = positionSum / c.weight;
    // theta_eps < 90 degrees keeps every member within 90 degrees of one centre, so the sum is not 0.
    c.normal = glm::normalize(normalSum);
    c.pieces = std::move(members);
    return c;
}

// Paper step 3 for one voxel (its pieces in ascending order). The reference direction is the centre
// of the bin with the largest area (the lowest bin on a tie); a cache takes the remaining pieces within
// theta_eps of it, and always the bin's own pieces: with theta_eps narrower than a bin (about 11
// degrees across), the centre might be further than theta_eps from every piece in the bin, and the
// loop would never end.
void clusterVoxel(const Pieces& all, std::vector<std::uint32_t> remaining, double cosTheta, std::vector<Cluster>& out)
{
    std::vector<std::pair<int, double>> binAreas;
    while (!remaining.empty()) {
        binAreas.clear();
        for (std::uint32_t m : remaining)
            binAreas.emplace_back(all.pieces[m].bin, all.pieces[m].area);
        std::stable_sort(binAreas.begin(), binAreas.end(),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
        int bestBin = -1;
        double bestArea = -1.0;
        for (std::size_t i = 0; i < binAreas.size();) {
            double sum = 0.0;
            std::size_t j = i;
            for (; j < binAreas.size() && binAreas[j].first == binAreas[i].first; ++j)
                sum += binAreas[j].second;
            if (sum > bestArea) {
                bestArea = sum;
                bestBin = binAreas[i].first;
            }
            i = j;
        }
        const glm::dvec3 centre = binCentre(bestBin);
        std::vector<std::uint32_t> taken, kept;
        for (std::uint32_t m : remaining) {
            const Piece& p = all.pieces[m];
            if (p.bin == bestBin || glm::dot(p.normal, centre) >= cosTheta)
                taken.push_back(m);
            else
                kept.push_back(m);
        }
        out.push_back(averagePieces(all, std::move(taken)));
        remaining.swap(kept);
    }
}

// --- Step 4: snapping ---------------------------------------------------------------------------------

glm::dvec3 closestOnSegment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b)
{
    const glm::dvec3 ab = b - a;
    const double len2 = glm::dot(ab, ab);
    if (!(len2 > 0.0)) return a;
    return a + std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) * ab;
}

// The nearest point of triangle abc to p: the projection onto its plane when that falls inside
// (inside all three edges), else the nearest point of its edges.
glm::dvec3 closestOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c)
{
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const double n2 = glm::dot(n, n);
    if (n2 > 0.0) {
        const glm::dvec3 q = p - (glm::dot(p - a, n) / n2) * n;
        if (glm::dot(glm::cross(b - a, q - a), n) >= 0.0 && glm::dot(glm::cross(c - b, q - b), n) >= 0.0 &&
            glm::dot(glm::cross(a - c, q - c), n) >= 0.0)
            return q;
    }
    glm::dvec3 best = closestOnSegment(p, a, b);
    for (const glm::dvec3& candidate : {closestOnSegment(p, b, c), closestOnSegment(p, c, a)})
        if (glm::dot(candidate - p, candidate - p) < glm::dot(best - p, best - p)) best = candidate;
    return best;
}

// Paper step 4: the nearest point of the pieces the cache averaged. A cache averaged over a bent
// surface (a tessellated cylinder, two faces less than 2 theta_eps apart) sits off it; on a flat
// surface the mean is already on it and snapping moves it by rounding only.
void snapCluster(const Pieces& all, Cluster& c)
{
    glm::dvec3 best = c.position;
    double bestDistance2 = std::numeric_limits<double>::infinity();
    for (std::uint32_t m : c.pieces) {
        const Piece& p = all.pieces[m];
        const glm::dvec3* v = &all.vertices[p.firstVertex];
        for (std::uint32_t i = 1; i + 1 < p.vertexCount; ++i) {
            const glm::dvec3 q = closestOnTriangle(c.position, v[0], v[i], v[i + 1]);
            const double d2 = glm::dot(q - c.position, q - c.position);
            if (d2 < bestDistance2) {
                bestDistance2 = d2;
                best = q;
            }
        }
    }
    c.position = best;
}

// --- Cache buckets (for the join's pairs and the area's nearest cache) -----------------------------------

// Cluster indices sorted by the voxel-sized cell of their position (cells may lie one outside the
// voxel grid: snapping and joining keep caches within the instance's bounds up to rounding).
class Buckets {
public:
    Buckets(const VoxelGrid& grid, const std::vector<Cluster>& clusters) : mGrid(grid)
    {
        for (std::size_t i = 0; i < clusters.size(); ++i)
            mEntries.emplace_back(key(cellOf(clusters[i].position)), static_cast<std::uint32_t>(i));
        std::sort(mEntries.begin(), mEntries.end());
    }
    glm::i64vec3 cellOf(const glm::dvec3& p) const
    {
        const glm::dvec3 u = glm::floor((p - mGrid.origin) / mGrid.edge);
        return glm::clamp(glm::i64vec3(u), glm::i64vec3(-1), mGrid.dims);
    }
    // Calls f(cluster index) for every cluster in `cell` (cells outside [-1, dims] hold none).
    template <class F> void forCell(const glm::i64vec3& cell, F&& f) const
    {
        if (glm::any(glm::lessThan(cell, glm::i64vec3(-1))) || glm::any(glm::greaterThan(cell, mGrid.dims))) return;
        const std::uint64_t k = key(cell);
        auto it = std::lower_bound(mEntries.begin(), mEntries.end(), std::make_pair(k, std::uint32_t(0)));
        for (; it != mEntries.end() && it->first == k; ++it)
            f(it->second);
    }
    std::int64_t maxRing() const { return std::max({mGrid.dims.x, mGrid.dims.y, mGrid.dims.z}) + 2; }

private:
    std::uint64_t key(const glm::i64vec3& c) const
    {
        const glm::i64vec3 d = mGrid.dims + glm::i64vec3(2);
        return static_cast<std::uint64_t>((c.x + 1) + d.x * ((c.y + 1) + d.y * (c.z + 1)));
    }
    const VoxelGrid& mGrid;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> mEntries;
};

// --- Step 5: joining --------------------------------------------------------------------------------------

// Paper step 5 ("caches with similar properties (generated in separate voxels) are joined"). Our rule:
// two caches closer than h / 2 = d_eps / 4 whose normals differ by less than theta_eps are merged into
// their area-weighted mean (snapped again when snapping is on). Caches of one flat surface are one
// voxel edge h apart, so a regular cover is left alone; what merges are the near-duplicates a
// surface makes when it cuts the corner or edge of a voxel and leaves a small piece there, beside the
// neighbouring voxel's cache. Pairs merge greedily, nearest first ((d^2, i, j) order), each cache at most
// once per pass, passes repeating until nothing merges: deterministic, and merged caches stay within
// about d_eps of what they represent.
void joinClusters(const Pieces& all, const VoxelGrid& grid, double cosTheta, bool snap, std::vector<Cluster>& clusters)
{
    const double limit2 = 0.25 * grid.edge * grid.edge;
    for (;;) {
        Buckets buckets(grid, clusters);
        struct Pair {
            double distance2;
            std::uint32_t i, j;
        };
        std::vector<Pair> pairs;
        for (std::uint32_t i = 0; i < clusters.size(); ++i) {
            const glm::i64vec3 cell = buckets.cellOf(clusters[i].position);
            for (int dz = -1; dz <= 1; ++dz)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx)
                        buckets.forCell(cell + glm::i64vec3(dx, dy, dz), [&](std::uint32_t j) {
                            if (j <= i) return;
                            const glm::dvec3 d = clusters[j].position - clusters[i].position;
                            const double d2 = glm::dot(d, d);
                            if (d2 < limit2 && glm::dot(clusters[i].normal, clusters[j].normal) >= cosTheta)
                                pairs.push_back({d2, i, j});
                        });
        }
        if (pairs.empty()) return;
        std::sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) {
            return a.distance2 != b.distance2 ? a.distance2 < b.distance2 : (a.i != b.i ? a.i < b.i : a.j < b.j);
        });
        std::vector<char> used(clusters.size(), 0), dead(clusters.size(), 0);
        for (const Pair& p : pairs) {
            if (used[p.i] || used[p.j]) continue;
            used[p.i] = used[p.j] = 1;
            dead[p.j] = 1;
            std::vector<std::uint32_t> members = clusters[p.i].pieces;
            members.insert(members.end(), clusters[p.j].pieces.begin(), clusters[p.j].pieces.end());
            std::sort(members.begin(), members.end());
            clusters[p.i] = averagePieces(all, std::move(members));
            if (snap) snapCluster(all, clusters[p.i]);
        }
        std::vector<Cluster> kept;
        for (std::size_t i = 0; i < clusters.size(); ++i)
            if (!dead[i]) kept.push_back(std::move(clusters[i]));
        clusters.swap(kept);
    }
}

// --- Area: a Voronoi partition of the surface ---------------------------------------------------------

// Each piece goes to the nearest cache within theta_eps of its normal; failing that, the nearest
// facing one (n . n_c > 0); failing that, the nearest. The search grows rings of cells around the
// piece: after ring r every cache closer than r cells is seen, so the nearest of a tier is final once
// it is closer than that.
std::vector<std::uint32_t> assignPieces(const Pieces& all, const VoxelGrid& grid, double cosTheta,
                                        const std::vector<Cluster>& clusters)
{
    const Buckets buckets(grid, clusters);
    std::vector<std::uint32_t> owner(all.pieces.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, all.pieces.size(), 512), [&](const auto& range) {
        for (std::size_t m = range.begin(); m != range.end(); ++m) {
            const Piece& piece = all.pieces[m];
            const glm::i64vec3 cell = buckets.cellOf(piece.centroid);
            std::array<double, 3> bestDistance2;
            bestDistance2.fill(std::numeric_limits<double>::infinity());
            std::array<std::uint32_t, 3> best{0, 0, 0};
            auto consider = [&](std::uint32_t c) {
                const glm::dvec3 d = clusters[c].position - piece.centroid;
                const double d2 = glm::dot(d, d);
                const double cosine = glm::dot(clusters[c].normal, piece.normal);
                const int tier = cosine >= cosTheta ? 0 : (cosine > 0.0 ? 1 : 2);
                for (int t = tier; t < 3; ++t) // a compatible cache also counts as facing and as any
                    if (d2 < bestDistance2[t] || (d2 == bestDistance2[t] && c < best[t])) {
                        bestDistance2[t] = d2;
                        best[t] = c;
                    }
            };
            const std::int64_t rings = buckets.maxRing();
            int tier = -1;
            for (std::int64_t r = 0; r <= rings && tier < 0; ++r) {
                for (std::int64_t dz = -r; dz <= r; ++dz)
                    for (std::int64_t dy = -r; dy <= r; ++dy)
                        for (std::int64_t dx = -r; dx <= r; ++dx) {
                            if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != r) continue;
                            buckets.forCell(cell + glm::i64vec3(dx, dy, dz), consider);
                        }
                const double covered = static_cast<double>(r) * grid.edge;
                if (bestDistance2[0] < covered * covered) tier = 0;
            }
            if (tier < 0)
                tier = bestDistance2[0] < std::numeric_limits<double>::infinity()   ? 0
                       : bestDistance2[1] < std::numeric_limits<double>::infinity() ? 1
                                                                                    : 2;
            owner[m] = best[static_cast<std::size_t>(tier)];
        }
    });
    return owner;
}

// --- One instance, steps 1-5 and the area --------------------------------------------------------------

std::vector<CacheGeometry> distributeInstance(const Scene& scene, const Instance& instance, double distance,
                                              const LightCacheParams& params)
{
    const Mesh& mesh = scene.meshes[static_cast<std::size_t>(instance.mesh)];
    if (mesh.indices.empty()) return {};
    const glm::dmat4 worldFromObject(instance.worldFromObject);
    const glm::dmat3 normalFromObject = glm::transpose(glm::inverse(glm::dmat3(worldFromObject)));
    std::vector<glm::dvec3> world(mesh.vertices.size()), side(mesh.vertices.size());
    VoxelGrid grid;
    grid.edge = 0.5 * distance;
    glm::dvec3 lower(std::numeric_limits<double>::infinity()), upper(-std::numeric_limits<double>::infinity());
    for (std::size_t i = 0; i < world.size(); ++i) {
        world[i] = glm::dvec3(worldFromObject * glm::dvec4(glm::dvec3(mesh.vertices[i].position), 1.0));
        side[i] = normalFromObject * glm::dvec3(mesh.vertices[i].normal);
        lower = glm::min(lower, world[i]);
        upper = glm::max(upper, world[i]);
    }
    grid.origin = lower;
    grid.dims = glm::i64vec3(glm::floor((upper - lower) / grid.edge)) + glm::i64vec3(1);
    const glm::dvec3 span = glm::dvec3(grid.dims);
    require(span.x * span.y * span.z < 9e18, "light caches: d_eps " + std::to_string(distance) +
                                                 " m is too small for instance of mesh '" + mesh.name + "'");

    const double cosTheta = std::cos(glm::radians(static_cast<double>(params.angleDegrees)));
    const Pieces all = clipInstance(world, side, mesh.indices, grid);
    if (all.pieces.empty()) return {};

    // Steps 2-3: pieces grouped by voxel (ascending key, then piece order), voxels in parallel, results
    // concatenated in voxel order.
    std::vector<std::uint32_t> order(all.pieces.size());
    for (std::size_t i = 0; i < order.size(); ++i)
        order[i] = static_cast<std::uint32_t>(i);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return all.pieces[a].voxel < all.pieces[b].voxel; });
    std::vector<std::size_t> groupStart;
    for (std::size_t i = 0; i < order.size(); ++i)
        if (i == 0 || all.pieces[order[i]].voxel != all.pieces[order[i - 1]].voxel) groupStart.push_back(i);
    groupStart.push_back(order.size());
    std::vector<std::vector<Cluster>> perVoxel(groupStart.size() - 1);
    tbb::parallel_for(std::size_t(0), perVoxel.size(), [&](std::size_t g) {
        std::vector<std::uint32_t> members(order.begin() + static_cast<std::ptrdiff_t>(groupStart[g]),
                                           order.begin() + static_cast<std::ptrdiff_t>(groupStart[g + 1]));
        clusterVoxel(all, std::move(members), cosTheta, perVoxel[g]);
        if (params.snap)
            for (Cluster& c : perVoxel[g])
                snapCluster(all, c);
    });
    std::vector<Cluster> clusters;
    for (std::vector<Cluster>& v : perVoxel)
        for (Cluster& c : v)
            clusters.push_back(std::move(c));

    if (params.join) joinClusters(all, grid, cosTheta, params.snap, clusters);

    const std::vector<std::uint32_t> owner = assignPieces(all, grid, cosTheta, clusters);
    std::vector<double> area(clusters.size(), 0.0);
    for (std::size_t m = 0; m < owner.size(); ++m)
        area[owner[m]] += all.pieces[m].area; // in piece order

    std::vector<CacheGeometry> caches;
    for (std::size_t i = 0; i < clusters.size(); ++i) {
        // A cache every one of whose pieces found a nearer one represents no surface: dropped.
        if (!(area[i] > 0.0)) continue;
        caches.push_back({glm::vec3(clusters[i].position), glm::vec3(clusters[i].normal), static_cast<float>(area[i])});
    }
    return caches;
}

// --- Disk cache ------------------------------------------------------------------------------------------

std::string instanceKey(const Scene& scene, const Instance& instance, float distance, const LightCacheParams& params)
{
    const Mesh& mesh = scene.meshes[static_cast<std::size_t>(instance.mesh)];
    Hasher h;
    h.text("lightskin caches");
    h.value(kFileVersion);
    // The algorithm's constants, so that changing one misses instead of loading stale caches.
    h.value(kBinsPerFaceEdge);
    h.value(kSplitEpsilon);
    h.value(mesh.vertices.size());
    for (const Vertex& v : mesh.vertices) { // positions place the caches, normals choose their side
        h.value(v.position);
        h.value(v.normal);
    }
    h.value(mesh.indices.size());
    h.bytes(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
    h.value(instance.worldFromObject);
    h.value(distance);
    h.value(params.angleDegrees);
    h.value(static_cast<std::uint8_t>(params.snap));
    h.value(static_cast<std::uint8_t>(params.join));
    return h.hex();
}

std::uint64_t payloadChecksum(const std::vector<CacheGeometry>& caches)
{
    Hasher h;
    h.bytes(caches.data(), caches.size() * sizeof(CacheGeometry));
    return h.digest();
}

void warn(const std::string& message)
{
    std::fprintf(stderr, "warning: %s\n", message.c_str());
}

// The key as the file stores it: a digest of the key text (the file name), so that a file copied or
// renamed to another key is not taken for it.
std::uint64_t keyDigest(const std::string& key)
{
    Hasher h;
    h.text(key);
    return h.digest();
}

// Layout: magic[8], version u32, reserved u32, key digest u64, count u64, caches (7 floats each),
// FNV-1a of the caches u64. The key is also the file name. Returns false (with a warning when the
// file exists but is not valid or is another key's) when the caller must compute.
bool readInstanceFile(const std::filesystem::path& path, const std::string& key, std::vector<CacheGeometry>& caches)
{
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return false;
    std::ifstream in(path, std::ios::binary);
    char magic[8] = {};
    std::uint32_t version = 0, reserved = 0;
    std::uint64_t storedKey = 0, count = 0, checksum = 0;
    in.read(magic, sizeof magic);
    in.read(reinterpret_cast<char*>(&version), sizeof version);
    in.read(reinterpret_cast<char*>(&reserved), sizeof reserved);
    in.read(reinterpret_cast<char*>(&storedKey), sizeof storedKey);
    in.read(reinterpret_cast<char*>(&count), sizeof count);
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    const std::uintmax_t header = sizeof magic + 2 * sizeof(std::uint32_t) + 2 * sizeof(std::uint64_t);
    const bool headerOk = in && !ec && std::memcmp(magic, kFileMagic, sizeof magic) == 0 && version == kFileVersion &&
                          count <= (size - std::min(size, header)) / sizeof(CacheGeometry) &&
                          size == header + count * sizeof(CacheGeometry) + sizeof checksum;
    if (!headerOk) {
        warn(path.string() + ": not a valid light cache file (wrong header or size); recomputing");
        return false;
    }
    if (storedKey != keyDigest(key)) {
        warn(path.string() + ": light cache file of another key (copied or renamed); recomputing");
        return false;
    }
    caches.resize(static_cast<std::size_t>(count));
    in.read(reinterpret_cast<char*>(caches.data()), static_cast<std::streamsize>(count * sizeof(CacheGeometry)));
    in.read(reinterpret_cast<char*>(&checksum), sizeof checksum);
    if (!in || checksum != payloadChecksum(caches)) {
        warn(path.string() + ": light cache file is corrupt (checksum); recomputing");
        caches.clear();
        return false;
    }
    return true;
}

// Written to a temporary sibling and renamed into place, so a reader never sees half a file.
void writeInstanceFile(const std::filesystem::path& path, const std::string& key, const std::vector<CacheGeometry>& caches)
{
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);
    std::random_device rd;
    const std::filesystem::path temporary =
        path.parent_path() / ("." + path.stem().string() + ".partial-" + std::to_string(rd()));
    bool ok = false;
    {
        std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
        const std::uint32_t version = kFileVersion, reserved = 0;
        const std::uint64_t storedKey = keyDigest(key), count = caches.size(), checksum = payloadChecksum(caches);
        out.write(kFileMagic, sizeof kFileMagic);
        out.write(reinterpret_cast<const char*>(&version), sizeof version);
        out.write(reinterpret_cast<const char*>(&reserved), sizeof reserved);
        out.write(reinterpret_cast<const char*>(&storedKey), sizeof storedKey);
        out.write(reinterpret_cast<const char*>(&count), sizeof count);
        out.write(reinterpret_cast<const char*>(caches.data()),
                  static_cast<std::streamsize>(caches.size() * sizeof(CacheGeometry)));
        out.write(reinterpret_cast<const char*>(&checksum), sizeof checksum);
        out.close();
        ok = !out.fail();
    }
    if (ok) std::filesystem::rename(temporary, path, ec);
    if (!ok || ec) {
        std::filesystem::remove(temporary, ec);
        warn(path.string() + ": cannot write the light cache file; continuing without it");
    }
}

} // namespace

float resolveLightCacheDistance(const Scene& scene, const LightCacheParams& params)
{
    if (params.distance > 0.0f) return params.distance;
    // A flat surface of area A holds A / h^2 voxels of edge h = d_eps / 2, one cache each, so
    // d_eps = 2 sqrt(A / N) gives about N caches. Edges, corners and small parts add to that: on
    // `street` the rule's N = 2048 gives about 5700 caches (the paper's street had about 5500),
    // on `cornell` about 2300, on `maze` about 4700. Two significant digits keep the value (and with
    // it the disk cache) stable under small scene edits.
    const double area = sceneSurfaceArea(scene);
    require(area > 0.0 && std::isfinite(area),
            "light caches: scene '" + scene.name + "' has no surface area for the automatic d_eps");
    require(params.target >= 16 && params.target <= (1 << 20), "light caches: lightskin.cacheTarget must be in [16, 1048576]");
    const double raw = 2.0 * std::sqrt(area / params.target);
    const double scale = std::pow(10.0, std::floor(std::log10(raw)) - 1.0);
    return static_cast<float>(std::round(raw / scale) * scale);
}

float resolveImportanceClamp(const Scene& scene, float clamp)
{
    if (clamp > 0.0f) return clamp;
    const double area = sceneSurfaceArea(scene);
    require(area > 0.0 && std::isfinite(area),
            "lightskin: scene '" + scene.name + "' has no surface area for the automatic importance clamp");
    constexpr double kStreetArea = 93148.0; // `street`'s surface [m^2]: the clamp is 1 m there
    return static_cast<float>(std::sqrt(area / kStreetArea));
}

void buildLightCacheGrid(LightCacheSet& set, float cellSize)
{
    require(cellSize > 0.0f && std::isfinite(cellSize), "light caches: grid cell size must be > 0");
    LightCacheGrid& grid = set.grid;
    glm::vec3 lower(0.0f), upper(0.0f);
    if (!set.caches.empty()) {
        lower = upper = set.caches[0].position;
        for (const LightCache& c : set.caches) {
            lower = glm::min(lower, c.position);
            upper = glm::max(upper, c.position);
        }
    }
    grid.origin = lower;
    grid.cellSize = cellSize;
    const glm::dvec3 span = glm::floor(glm::dvec3(upper - lower) / static_cast<double>(cellSize));
    require(glm::all(glm::lessThan(span, glm::dvec3(shared::kLightCacheCellAxisLimit))),
            "light caches: the scene spans more than 2^21 cache distances along an axis (d_eps " +
                std::to_string(cellSize) + " m); set lightskin.cacheDistance larger");
    // Each cache's cell, by the same expression as glsl/shared/light_cache_lookup.h (>= 0: the origin
    // is the lower corner), keyed; sorted by (key, index), so each cell's caches are in index order.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(set.caches.size());
    std::vector<glm::ivec3> cellOf(set.caches.size()); // by cache index, for the hash below
    for (std::size_t i = 0; i < set.caches.size(); ++i) {
        const glm::ivec3 cell =
            glm::clamp(glm::ivec3(glm::floor((set.caches[i].position - grid.origin) / grid.cellSize)), glm::ivec3(0),
                       glm::ivec3(shared::kLightCacheCellAxisLimit - 1));
        cellOf[i] = cell;
        const glm::uvec2 key = shared::lightCacheCellKey(cell);
        keyed[i] = {(static_cast<std::uint64_t>(key.y) << 32u) | key.x, static_cast<std::uint32_t>(i)};
    }
    std::sort(keyed.begin(), keyed.end());
    std::size_t cells = 0;
    for (std::size_t i = 0; i < keyed.size(); ++i)
        cells += i == 0 || keyed[i].first != keyed[i - 1].first ? 1 : 0;
    std::size_t slotCount = 1;
    while (slotCount < 2 * cells) slotCount *= 2;
    grid.slotMask = static_cast<std::uint32_t>(slotCount - 1);
    grid.maxProbe = 0;
    grid.slots.assign(slotCount, glm::uvec4(0u, shared::kLightCacheEmptySlot, 0u, 0u));
    // Linear probing, cells in key order; each occupied slot first gets its cell's range in `keyed`.
    for (std::size_t first = 0; first < keyed.size();) {
        std::size_t last = first + 1;
        while (last < keyed.size() && keyed[last].first == keyed[first].first) ++last;
        const std::uint64_t key = keyed[first].first;
        std::uint32_t slot = shared::lightCacheCellHash(cellOf[keyed[first].second]) & grid.slotMask;
        int probe = 0;
        while (grid.slots[slot].y != shared::kLightCacheEmptySlot) {
            slot = (slot + 1u) & grid.slotMask;
            ++probe;
        }
        grid.maxProbe = std::max(grid.maxProbe, probe);
        grid.slots[slot] = glm::uvec4(static_cast<std::uint32_t>(key), static_cast<std::uint32_t>(key >> 32u),
                                      static_cast<std::uint32_t>(first), static_cast<std::uint32_t>(last));
        first = last;
    }
    // The index list slot by slot; each slot's range rewritten to point into it.
    grid.cacheIndices.clear();
    grid.cacheIndices.reserve(keyed.size());
    for (glm::uvec4& s : grid.slots) {
        if (s.y == shared::kLightCacheEmptySlot) continue;
        const auto begin = static_cast<std::uint32_t>(grid.cacheIndices.size());
        for (std::uint32_t i = s.z; i < s.w; ++i)
            grid.cacheIndices.push_back(keyed[i].second);
        s.z = begin;
        s.w = static_cast<std::uint32_t>(grid.cacheIndices.size());
    }
}

LightCacheSet distributeLightCaches(const Scene& scene, const LightCacheParams& params, const ProgressSink& progress,
                                    const std::string& cacheDir)
{
    require(params.angleDegrees >= 1.0f && params.angleDegrees <= 89.0f,
            "light caches: lightskin.cacheAngle must be in [1, 89] degrees");
    require(params.distance >= 0.0f && std::isfinite(params.distance),
            "light caches: lightskin.cacheDistance must be >= 0");
    LightCacheSet set;
    set.distance = resolveLightCacheDistance(scene, params);
    // Pieces (step 1) cost about 200 bytes each, A / (d_eps / 4)^2 of them: refuse a d_eps that would
    // need gigabytes rather than run out of memory.
    // Instances are cut one at a time, so the bound is per instance (a large world of many
    // instances is fine; issue "LightSkin's indirect shadows", part 4).
    const double fine = 0.25 * static_cast<double>(set.distance);
    double largestArea = 0.0;
    for (const Instance& instance : scene.instances) largestArea = std::max(largestArea, instanceSurfaceArea(scene, instance));
    const double pieces = largestArea / (fine * fine);
    require(pieces <= kMaxPieces, "light caches: lightskin.cacheDistance = " + std::to_string(set.distance) +
                                      " m would cut an instance into about " + std::to_string(pieces) +
                                      " pieces (at most " + std::to_string(kMaxPieces) + "); use a larger distance");
    const UntexturedMaterials materials = computeUntexturedMaterials(scene);
    std::vector<float> coverage; // per material (alphaCoverage: 1 unless alpha-masked)
    for (const Material& m : scene.materials)
        coverage.push_back(alphaCoverage(scene, m));
    const int total = static_cast<int>(scene.instances.size());
    if (progress) progress("lightskin caches", 0, total);
    set.instanceStart.push_back(0);
    for (int i = 0; i < total; ++i) {
        const Instance& instance = scene.instances[static_cast<std::size_t>(i)];
        std::vector<CacheGeometry> geometry;
        std::filesystem::path file;
        std::string key;
        bool loaded = false;
        if (!cacheDir.empty()) {
            key = instanceKey(scene, instance, set.distance, params);
            file = std::filesystem::path(cacheDir) / "lightskin" / (key + ".bin");
            loaded = readInstanceFile(file, key, geometry);
        }
        if (loaded) {
            ++set.instancesLoaded;
        } else {
            geometry = distributeInstance(scene, instance, set.distance, params);
            ++set.instancesComputed;
            if (!cacheDir.empty()) writeInstanceFile(file, key, geometry);
        }
        const std::size_t material =
            static_cast<std::size_t>(scene.meshes[static_cast<std::size_t>(instance.mesh)].material);
        const glm::vec3 base = materials.baseColor[material];
        const float metallic = materials.metallic[material];
        const float specular = scene.materials[material].specular;
        // Alpha masks (not in the paper): a cache stands for the part of its surface the mask keeps,
        // taken as the material's mean coverage, as its albedo is the material's mean (the untextured
        // table). A cache's exact cut-out would need the texture over each piece.
        for (const CacheGeometry& g : geometry) {
            LightCache c;
            c.position = g.position;
            c.normal = g.normal;
            c.area = g.area * coverage[material];
            c.roughness = materials.roughness[material];
            c.metallic = metallic;
            c.diffuse = (1.0f - metallic) * base;
            c.specular = glm::mix(glm::vec3(0.04f * specular), base, metallic);
            set.caches.push_back(c);
        }
        // A double-sided surface is lit and seen from both sides (the G-buffer turns its normal towards
        // the viewer), so it gets the same caches facing the other way: without them the lookup, which
        // takes only facing caches, finds none on its back.
        if (scene.materials[material].doubleSided) {
            const std::size_t front = set.caches.size() - geometry.size();
            for (std::size_t k = front; k < front + geometry.size(); ++k) {
                LightCache back = set.caches[k];
                back.normal = -back.normal;
                back.backTwin = 1.0f;
                set.caches.push_back(back);
            }
        }
        set.instanceStart.push_back(static_cast<std::uint32_t>(set.caches.size()));
        if (progress) progress("lightskin caches", i + 1, total);
    }
    buildLightCacheGrid(set, set.distance);
    return set;
}

} // namespace vplgi
