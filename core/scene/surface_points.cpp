#include "surface_points.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/scene/surface.h"
#include "core/util/error.h"
#include "core/util/random.h"
#include "glsl/shared/ism.h"

namespace vplgi {

namespace {

struct WorldTriangle {
    glm::vec3 p0, p1, p2;
    float winding = 1.0f;             // Instance::winding
    const Material* masked = nullptr; // an alpha-masked material, else nullptr
    const Mesh* mesh = nullptr;       // and the triangle (masked only)
    int triangle = 0;
};

// Draws after which a point that keeps landing where alpha masks cut the surface gives up.
constexpr int kMaxMaskedDraws = 4096;

} // namespace

SurfacePoints sampleSurfacePoints(const Scene& scene, int count, std::uint64_t seed, int blockSize)
{
    require(count >= 0, "surface points: count must be >= 0 (got " + std::to_string(count) + ")");
    require(blockSize >= 0, "surface points: block size must be >= 0 (got " + std::to_string(blockSize) + ")");
    SurfacePoints points;
    std::vector<WorldTriangle> triangles;
    std::vector<double> cumulativeArea; // inclusive prefix sums, in double: 10^6 triangles sum exactly enough
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[static_cast<std::size_t>(instance.mesh)];
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            WorldTriangle tri;
            tri.p0 = glm::vec3(instance.worldFromObject * glm::vec4(mesh.vertices[mesh.indices[t]].position, 1.0f));
            tri.p1 = glm::vec3(instance.worldFromObject * glm::vec4(mesh.vertices[mesh.indices[t + 1]].position, 1.0f));
            tri.p2 = glm::vec3(instance.worldFromObject * glm::vec4(mesh.vertices[mesh.indices[t + 2]].position, 1.0f));
            tri.winding = instance.winding();
            const double area = 0.5 * static_cast<double>(glm::length(glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0)));
            if (!(area > 0.0)) continue; // degenerate triangles get no points (and have no normal)
            const Material& material = scene.materials[static_cast<std::size_t>(mesh.material)];
            if (material.isMasked()) {
                tri.masked = &material;
                tri.mesh = &mesh;
                tri.triangle = static_cast<int>(t / 3);
            }
            points.totalArea += area;
            triangles.push_back(tri);
            cumulativeArea.push_back(points.totalArea);
        }
    }
    if (count == 0) return points;
    require(!triangles.empty(), "surface points: scene '" + scene.name + "' has no triangle of positive area");

    points.positions.reserve(static_cast<std::size_t>(count));
    points.normals.reserve(static_cast<std::size_t>(count));
    Pcg32 rng(mix64(seed), 0x15u);
    double blockOffset = 0.0;
    const double totalArea = points.totalArea;
    std::uint64_t draws = 0;
    for (int i = 0; i < count; ++i) {
        if (blockSize > 0 && i % blockSize == 0) blockOffset = static_cast<double>(rng.uniform());
        // Triangle by area: the first whose inclusive prefix sum exceeds u * total; in blocks, u is
        // stratified: (k + xi) / blockSize for the block's k-th point.
        const double u = blockSize > 0
                             ? (static_cast<double>(i % blockSize) + static_cast<double>(rng.uniform())) / blockSize
                             : static_cast<double>(rng.uniform());
        const double target = u * points.totalArea;
        const auto it = std::upper_bound(cumulativeArea.begin(), cumulativeArea.end(), target);
        const std::size_t index = std::min(static_cast<std::size_t>(it - cumulativeArea.begin()), triangles.size() - 1);
        const WorldTriangle& tri = triangles[index];
        // Uniform barycentrics (square-root warp; Turk 1990, pbrt's SampleUniformTriangle). In blocks
        // the first coordinate is where u fell inside the triangle's share (the triangle's points
        // are stratified along it) and the second the golden-ratio sequence of the stratum index k
        // with the block's random offset: the points of a triangle form a jittered Fibonacci
        // lattice (k / m, frac(k / phi)), whose gaps are all about the same size.
        const double lowerArea = index > 0 ? cumulativeArea[index - 1] : 0.0;
        const double inside = blockSize > 0 ? std::clamp((target - lowerArea) / (cumulativeArea[index] - lowerArea), 0.0, 1.0)
                                            : static_cast<double>(rng.uniform());
        const float su = std::sqrt(static_cast<float>(inside));
        double golden = 0.0;
        if (blockSize > 0) {
            const double g = static_cast<double>(i % blockSize) * 0.6180339887498949 + blockOffset;
            golden = g - std::floor(g);
        }
        const float u2 = blockSize > 0 ? static_cast<float>(golden) : rng.uniform();
        float b1 = su * (1.0f - u2);
        float b2 = su * u2;
        // Alpha masks (glsl/shared/alpha_mask.h): a point where the mask cuts the surface is drawn
        // again, i.i.d. over all the area, until it lands on kept surface (rejection sampling: uniform
        // over the kept area; the block's lattice loses those points' places).
        const WorldTriangle* at = &tri;
        auto cut = [&](const WorldTriangle& t, float c1, float c2) {
            return t.masked && !alphaMaskKeeps(scene, *t.masked, *t.mesh, t.triangle, glm::vec2(c1, c2));
        };
        ++draws;
        for (int tries = 1; cut(*at, b1, b2); ++tries) {
            require(tries < kMaxMaskedDraws, "surface points: the alpha masks of scene '" + scene.name +
                                                 "' keep almost none of its surface (" + std::to_string(tries) +
                                                 " draws cut away in a row)");
            const double again = static_cast<double>(rng.uniform()) * totalArea;
            const auto hit = std::upper_bound(cumulativeArea.begin(), cumulativeArea.end(), again);
            at = &triangles[std::min(static_cast<std::size_t>(hit - cumulativeArea.begin()), triangles.size() - 1)];
            const float s = std::sqrt(rng.uniform()), v = rng.uniform();
            b1 = s * (1.0f - v);
            b2 = s * v;
            ++draws;
        }
        points.positions.push_back((1.0f - b1 - b2) * at->p0 + b1 * at->p1 + b2 * at->p2);
        points.normals.push_back(at->winding * glm::normalize(glm::cross(at->p1 - at->p0, at->p2 - at->p0))); // the front
    }
    // The kept area: the acceptance rate of the draws estimates the fraction the masks keep.
    if (draws > static_cast<std::uint64_t>(count)) points.totalArea *= static_cast<double>(count) / static_cast<double>(draws);
    return points;
}

std::vector<std::uint32_t> surfaceReach(const SurfacePoints& points, float radius)
{
    const std::size_t n = points.positions.size();
    std::vector<std::uint32_t> reach(n, shared::kISMReachFull);
    if (n == 0 || !(radius > 0.0f) || !(points.totalArea > 0.0)) return reach;
    const float spacing = static_cast<float>(std::sqrt(points.totalArea / static_cast<double>(n)));
    const float tolerance = std::max(0.25f * radius, 1.5f * spacing);
    if (tolerance >= radius) return reach; // the probes could not tell an edge from a gap between points

    // A dense grid of cells at least `tolerance` wide (wider when the bounds would need more than 2^22
    // cells), its points sorted by cell: the 3^3 cells around a spot hold every point within
    // `tolerance` of it.
    glm::vec3 lower(std::numeric_limits<float>::max()), upper(std::numeric_limits<float>::lowest());
    for (const glm::vec3& p : points.positions) {
        lower = glm::min(lower, p);
        upper = glm::max(upper, p);
    }
    const glm::vec3 extent = glm::max(upper - lower, glm::vec3(1e-6f));
    float edge = tolerance;
    constexpr double kMaxCells = 4194304.0;
    const double cellsAtTolerance = static_cast<double>(std::floor(extent.x / edge) + 1) *
                                    (std::floor(extent.y / edge) + 1) * (std::floor(extent.z / edge) + 1);
    if (cellsAtTolerance > kMaxCells) edge *= static_cast<float>(std::cbrt(cellsAtTolerance / kMaxCells)) * 1.01f;
    const glm::ivec3 dims = glm::ivec3(glm::floor(extent / edge)) + glm::ivec3(1);
    // A spot's position in cell units (its cell: the floor); the points' cells clamped into the grid.
    const auto inCells = [&](const glm::vec3& p) { return (p - lower) / edge; };
    const auto cellOf = [&](const glm::vec3& p) {
        return glm::clamp(glm::ivec3(glm::floor(inCells(p))), glm::ivec3(0), dims - glm::ivec3(1));
    };
    const auto indexOf = [&](const glm::ivec3& c) {
        return (static_cast<std::size_t>(c.z) * static_cast<std::size_t>(dims.y) + static_cast<std::size_t>(c.y)) *
                   static_cast<std::size_t>(dims.x) +
               static_cast<std::size_t>(c.x);
    };
    const std::size_t cellCount = static_cast<std::size_t>(dims.x) * dims.y * dims.z;
    std::vector<std::uint32_t> start(cellCount + 1, 0), cellOfPoint(n);
    for (std::size_t i = 0; i < n; ++i) {
        cellOfPoint[i] = static_cast<std::uint32_t>(indexOf(cellOf(points.positions[i])));
        ++start[cellOfPoint[i] + 1];
    }
    for (std::size_t c = 1; c <= cellCount; ++c) start[c] += start[c - 1];
    std::vector<std::uint32_t> sorted(n), next(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) sorted[next[cellOfPoint[i]]++] = static_cast<std::uint32_t>(i);
    // Positions and normals in cell order, side by side: the probes read them cell by cell.
    struct Sorted {
        glm::vec3 position, normal;
    };
    std::vector<Sorted> cellOrder(n);
    for (std::size_t k = 0; k < n; ++k) cellOrder[k] = {points.positions[sorted[k]], points.normals[sorted[k]]};

    const float tolerance2 = tolerance * tolerance;
    // The 27 cells around a spot's, its own first (where a spot on the surface mostly finds a point).
    std::array<glm::ivec3, 27> offsets;
    for (int k = 0; k < 27; ++k) offsets[static_cast<std::size_t>(k)] = glm::ivec3(k % 3, (k / 3) % 3, k / 9) - glm::ivec3(1);
    std::stable_sort(offsets.begin(), offsets.end(), [](const glm::ivec3& a, const glm::ivec3& b) {
        return glm::dot(glm::vec3(a), glm::vec3(a)) < glm::dot(glm::vec3(b), glm::vec3(b));
    });
    // Whether some point within the tolerance of `spot` has a normal within 45 degrees of `normal`
    // (either orientation).
    const auto surfaceAt = [&](const glm::vec3& spot, const glm::vec3& normal) {
        const glm::vec3 inCell = inCells(spot); // not clamped: a spot beyond the grid skips the missing cells
        const glm::ivec3 centre = glm::ivec3(glm::floor(inCell));
        const glm::vec3 fraction = inCell - glm::vec3(centre);
        for (const glm::ivec3& offset : offsets) {
            const glm::ivec3 c = centre + offset;
            if (glm::any(glm::lessThan(c, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(c, dims))) continue;
            // The cell's nearest point to the spot, in cells: skip cells wholly beyond the tolerance.
            const glm::vec3 gap = glm::max(glm::vec3(0.0f), glm::max(glm::vec3(offset) - fraction,
                                                                      fraction - glm::vec3(offset) - glm::vec3(1.0f)));
            if (glm::dot(gap, gap) * edge * edge > tolerance2) continue;
            const std::size_t cell = indexOf(c);
            for (std::uint32_t k = start[cell]; k < start[cell + 1]; ++k) {
                const glm::vec3 d = cellOrder[k].position - spot;
                if (glm::dot(d, d) <= tolerance2 && std::abs(glm::dot(cellOrder[k].normal, normal)) >= 0.70710678f)
                    return true;
            }
        }
        return false;
    };
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& range) {
        // In cell order: neighbouring points probe neighbouring cells.
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
            const std::size_t i = sorted[k];
            const glm::vec3 p = cellOrder[k].position, nrm = cellOrder[k].normal;
            std::uint32_t profile = 0;
            for (int sector = 0; sector < shared::kISMReachSectors; ++sector) {
                const glm::vec3 u = shared::ismReachDirection(nrm, sector);
                // The whole radius first: where the surface goes on there (most sectors), the steps
                // between are not probed.
                int j = surfaceAt(p + radius * u, nrm) ? shared::kISMReachSteps : 0;
                while (j < shared::kISMReachSteps &&
                       surfaceAt(p + (static_cast<float>(j + 1) / shared::kISMReachSteps) * radius * u, nrm))
                    ++j;
                profile |= static_cast<std::uint32_t>(j) << (3 * sector);
            }
            reach[i] = profile;
        }
    });
    return reach;
}

} // namespace vplgi
