#include "surface_points.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/util/error.h"
#include "core/util/random.h"

namespace vplgi {

namespace {

struct WorldTriangle {
    glm::vec3 p0, p1, p2;
};

} // namespace

SurfacePoints sampleSurfacePoints(const Scene& scene, int count, std::uint64_t seed)
{
    require(count >= 0, "surface points: count must be >= 0 (got " + std::to_string(count) + ")");
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
            const double area = 0.5 * static_cast<double>(glm::length(glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0)));
            if (!(area > 0.0)) continue; // degenerate triangles get no points (and have no normal)
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
    for (int i = 0; i < count; ++i) {
        // Triangle by area: the first whose inclusive prefix sum exceeds u * total.
        const double target = static_cast<double>(rng.uniform()) * points.totalArea;
        const auto it = std::upper_bound(cumulativeArea.begin(), cumulativeArea.end(), target);
        const std::size_t index = std::min(static_cast<std::size_t>(it - cumulativeArea.begin()), triangles.size() - 1);
        const WorldTriangle& tri = triangles[index];
        // Uniform barycentrics (square-root warp; Turk 1990, pbrt's SampleUniformTriangle).
        const float su = std::sqrt(rng.uniform());
        const float u2 = rng.uniform();
        const float b1 = su * (1.0f - u2);
        const float b2 = su * u2;
        points.positions.push_back((1.0f - b1 - b2) * tri.p0 + b1 * tri.p1 + b2 * tri.p2);
        points.normals.push_back(glm::normalize(glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0)));
    }
    return points;
}

} // namespace vplgi
