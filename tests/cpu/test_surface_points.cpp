// Surface points for imperfect shadow maps (core/scene/surface_points.h): triangles are chosen in
// proportion to their area, points are uniform inside them, and the same seed gives the same points.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

#include "core/scene/builtin_scenes.h"
#include "core/scene/surface_points.h"
#include "core/util/error.h"

using namespace vplgi;

namespace {

// Two unit quads in z = 0, [0,1]^2, facing +z: the first as it is (area 1), the second scaled by
// (2, 1.5) and moved to z = 5 (area 3).
Scene twoQuads()
{
    Scene scene;
    scene.name = "two quads";
    scene.materials.push_back(Material{});
    Mesh mesh;
    for (glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)}) {
        Vertex v;
        v.position = p;
        v.normal = {0, 0, 1};
        mesh.vertices.push_back(v);
    }
    mesh.indices = {0, 1, 2, 0, 2, 3};
    scene.meshes.push_back(mesh);
    scene.instances.push_back(Instance{0, glm::mat4(1.0f)});
    scene.instances.push_back(
        Instance{0, glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5)), glm::vec3(2.0f, 1.5f, 1.0f))});
    return scene;
}

} // namespace

TEST_CASE("surface points: area-proportional, uniform inside triangles, on the surface", "[surfacepoints]")
{
    const Scene scene = twoQuads();
    const int n = 40000;
    const SurfacePoints points = sampleSurfacePoints(scene, n, 3);
    REQUIRE(points.positions.size() == static_cast<std::size_t>(n));
    REQUIRE(points.normals.size() == static_cast<std::size_t>(n));
    CHECK(points.totalArea == Approx(4.0).epsilon(1e-6));

    int onFirst = 0;
    int cells[4][4] = {};
    int offSurface = 0;
    for (int i = 0; i < n; ++i) {
        const glm::vec3 p = points.positions[static_cast<std::size_t>(i)];
        const glm::vec3 nrm = points.normals[static_cast<std::size_t>(i)];
        offSurface += std::abs(nrm.z - 1.0f) < 1e-6f ? 0 : 1;
        if (p.z == 0.0f) {
            ++onFirst;
            // Convex combinations of the corners: inside up to float rounding.
            offSurface += p.x >= -1e-6f && p.x <= 1.0f + 1e-6f && p.y >= -1e-6f && p.y <= 1.0f + 1e-6f ? 0 : 1;
            ++cells[std::min(3, static_cast<int>(p.x * 4.0f))][std::min(3, static_cast<int>(p.y * 4.0f))];
        } else {
            offSurface += std::abs(p.z - 5.0f) < 1e-5f && p.x >= -1e-5f && p.x <= 2.0f + 1e-5f && p.y >= -1e-5f &&
                                  p.y <= 1.5f + 1e-5f
                              ? 0
                              : 1;
        }
    }
    CHECK(offSurface == 0);
    // Area 1 of 4: a binomial fraction with sigma = sqrt(0.25 * 0.75 / n) = 0.0022; 4 sigma fails
    // a correct sampler about once in 16000 runs (the stream is fixed, so never here).
    const double fraction = static_cast<double>(onFirst) / n;
    const double sigma = std::sqrt(0.25 * 0.75 / n);
    std::printf("surface points: fraction on the quad of area 1 of 4 = %.4f (sigma %.4f)\n", fraction, sigma);
    CHECK(std::abs(fraction - 0.25) < 4.0 * sigma);
    // Uniform inside the quad (both of its triangles): Pearson's chi-square over a 4 x 4 grid, 15
    // degrees of freedom; 37.7 is the 0.999 quantile.
    double chiSquare = 0.0;
    const double expected = onFirst / 16.0;
    for (auto& row : cells)
        for (int count : row)
            chiSquare += (count - expected) * (count - expected) / expected;
    std::printf("surface points: chi-square over 4 x 4 cells = %.2f (15 dof, 0.999 quantile 37.7)\n", chiSquare);
    CHECK(chiSquare < 37.7);
}

TEST_CASE("surface points: the same seed gives the same points, another seed others", "[surfacepoints]")
{
    const Scene scene = makeBuiltinScene("cornell");
    const SurfacePoints a = sampleSurfacePoints(scene, 1000, 9);
    const SurfacePoints b = sampleSurfacePoints(scene, 1000, 9);
    const SurfacePoints c = sampleSurfacePoints(scene, 1000, 10);
    CHECK(a.positions == b.positions);
    CHECK(a.normals == b.normals);
    CHECK(a.positions != c.positions);
    CHECK(sampleSurfacePoints(scene, 0, 1).positions.empty());
    Scene empty;
    empty.name = "empty";
    CHECK_THROWS_AS(sampleSurfacePoints(empty, 10, 1), Error);
    CHECK_NOTHROW(sampleSurfacePoints(empty, 0, 1));
}

TEST_CASE("surface points: blocks are stratified, every triangle gets its share of each block", "[surfacepoints]")
{
    // Four triangles of areas 0.5, 0.5 (the unit quad) and 1.5, 1.5 (the scaled one); a block of 1000
    // points owes them 125, 125, 375, 375. Stratified draws (one per 1/1000 of the area) give each
    // triangle its share within 2 points (the strata at its two ends may fall either way); i.i.d.
    // draws miss by about sqrt(n p (1 - p)) = 10-15 points, so the check fails for them.
    const Scene scene = twoQuads();
    const int block = 1000, blocks = 6;
    const SurfacePoints points = sampleSurfacePoints(scene, block * blocks + 500, 5, block);
    const SurfacePoints iid = sampleSurfacePoints(scene, block, 5);
    auto triangleOf = [](const glm::vec3& p) { // 0, 1: the unit quad's (x >= y or not); 2, 3 the other's
        const bool second = p.z > 1.0f;
        const float x = second ? p.x / 2.0f : p.x, y = second ? p.y / 1.5f : p.y;
        return (second ? 2 : 0) + (y > x ? 1 : 0);
    };
    const double share[4] = {125.0, 125.0, 375.0, 375.0};
    double worst = 0.0, worstIID = 0.0;
    // Runs of `block` consecutive points starting anywhere (aligned or not) cover the area once.
    for (int start : {0, 1000, 2500, 3999, 5000}) {
        int counts[4] = {};
        for (int i = start; i < start + block; ++i)
            ++counts[triangleOf(points.positions[static_cast<std::size_t>(i)])];
        for (int t = 0; t < 4; ++t)
            worst = std::max(worst, std::abs(counts[t] - share[t]));
    }
    int counts[4] = {};
    for (const glm::vec3& p : iid.positions)
        ++counts[triangleOf(p)];
    for (int t = 0; t < 4; ++t)
        worstIID = std::max(worstIID, std::abs(counts[t] - share[t]));
    std::printf("surface points: worst miss of a triangle's share in a run of 1000, stratified %.1f, i.i.d. %.1f\n",
                worst, worstIID);
    CHECK(worst < 2.0);
    CHECK(worstIID > 2.0); // the check above can fail (measured: see the print)
    // Still on the surface and the same stream for the same seed.
    const SurfacePoints again = sampleSurfacePoints(scene, block * blocks + 500, 5, block);
    CHECK(again.positions == points.positions);
    CHECK_THROWS_AS(sampleSurfacePoints(scene, 10, 1, -1), Error);
}
