#include "surface_points.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/scene/surface.h"
#include "core/util/error.h"
#include "core/util/random.h"

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

} // namespace vplgi
