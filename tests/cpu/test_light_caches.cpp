// LightSkin light caches (core/lightskin/light_caches.h): counts on a plane and a box against what
// d_eps implies, areas against the surface area, the disk cache (hits, misses, damaged files), the
// shared lookup (glsl/shared/light_cache_lookup.h) against brute force, and determinism over TBB
// thread counts, the reach (no cache across a wall, against Embree rays). The [numbers] case prints counts and times
// for the built-in scenes
// (`vplgi_tests_cpu "[lightskin][numbers]"`).
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <tbb/global_control.h>

#include "core/lightskin/light_caches.h"
#include "core/lightskin/traced_visibility.h"
#include "core/scene/builtin_scenes.h"
#include "core/scene/surface_points.h"
#include "core/util/error.h"

using namespace vplgi;

namespace {

// Appends a rectangle origin + s edgeU + t edgeV, (s, t) in [0,1]^2, as nu x nv cells of two triangles,
// counter-clockwise seen from cross(edgeU, edgeV).
void addRect(Mesh& mesh, const glm::vec3& origin, const glm::vec3& edgeU, const glm::vec3& edgeV, int nu, int nv)
{
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    const glm::vec3 normal = glm::normalize(glm::cross(edgeU, edgeV));
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            Vertex v;
            v.position = origin + (static_cast<float>(i) / nu) * edgeU + (static_cast<float>(j) / nv) * edgeV;
            v.normal = normal;
            mesh.vertices.push_back(v);
        }
    const auto row = static_cast<std::uint32_t>(nu + 1);
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const std::uint32_t a = base + static_cast<std::uint32_t>(j) * row + static_cast<std::uint32_t>(i);
            mesh.indices.insert(mesh.indices.end(), {a, a + 1, a + row + 1, a, a + row + 1, a + row});
        }
}

Scene sceneOf(Mesh mesh, const glm::mat4& worldFromObject)
{
    Scene scene;
    scene.name = "test";
    scene.materials.push_back(Material{});
    scene.meshes.push_back(std::move(mesh));
    scene.instances.push_back(Instance{0, worldFromObject});
    return scene;
}

// A closed box [0, size]^3 with outward faces; cells per face edge chosen off the voxel grid (7) so that
// triangles cross voxel planes anywhere.
Mesh boxMesh(float size, int cells)
{
    Mesh mesh;
    const glm::vec3 x(size, 0, 0), y(0, size, 0), z(0, 0, size), o(0.0f);
    addRect(mesh, o, z, y, cells, cells); // -x: z cross y = -x
    addRect(mesh, x, y, z, cells, cells); // +x
    addRect(mesh, o, x, z, cells, cells); // -y: x cross z = -y
    addRect(mesh, y, z, x, cells, cells); // +y
    addRect(mesh, o, y, x, cells, cells); // -z: y cross x = -z
    addRect(mesh, z, x, y, cells, cells); // +z
    return mesh;
}

double worldArea(const Scene& scene, const Instance& instance)
{
    const Mesh& mesh = scene.meshes[static_cast<std::size_t>(instance.mesh)];
    const glm::dmat4 m(instance.worldFromObject);
    double area = 0.0;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        glm::dvec3 p[3];
        for (std::size_t k = 0; k < 3; ++k)
            p[k] = glm::dvec3(m * glm::dvec4(glm::dvec3(mesh.vertices[mesh.indices[t + k]].position), 1.0));
        area += 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
    }
    return area;
}

LightCacheParams paramsWith(float distance)
{
    LightCacheParams p;
    p.distance = distance;
    return p;
}

LightCacheSet distribute(const Scene& scene, const LightCacheParams& params, const std::string& dir = "")
{
    return distributeLightCaches(scene, params, ProgressSink{}, dir);
}

bool sameBits(const LightCacheSet& a, const LightCacheSet& b)
{
    return a.caches.size() == b.caches.size() &&
           std::memcmp(a.caches.data(), b.caches.data(), a.caches.size() * sizeof(LightCache)) == 0 &&
           a.grid.slots == b.grid.slots && a.grid.cacheIndices == b.grid.cacheIndices &&
           a.grid.slotMask == b.grid.slotMask && a.grid.maxProbe == b.grid.maxProbe && a.grid.origin == b.grid.origin &&
           a.grid.cellSize == b.grid.cellSize &&
           a.instanceStart == b.instanceStart && a.distance == b.distance;
}

// A fresh, empty directory under the system's temporary directory.
std::filesystem::path freshDirectory(const std::string& name)
{
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("vplgi-test-" + name + "-" + std::to_string(std::random_device{}()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

std::vector<std::filesystem::path> filesIn(const std::filesystem::path& dir)
{
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(dir))
        files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

} // namespace

TEST_CASE("light caches: parameters visit their four keys", "[lightskin][caches]")
{
    LightCacheParams params;
    ParamSetter setter({{"lightskin.cacheDistance", "0.5"},
                        {"lightskin.cacheAngle", "20"},
                        {"lightskin.cacheSnap", "false"},
                        {"lightskin.cacheJoin", "false"}});
    params.visitParams(setter);
    setter.finish();
    CHECK(params.distance == 0.5f);
    CHECK(params.angleDegrees == 20.0f);
    CHECK_FALSE(params.snap);
    CHECK_FALSE(params.join);
    ParamSetter outOfRange(Settings{{"lightskin.cacheAngle", "90"}});
    CHECK_THROWS_AS(params.visitParams(outOfRange), Error);
}

TEST_CASE("light caches: a plane gets one cache per d_eps/2 voxel, its normal, its area", "[lightskin][caches]")
{
    // W x H = 3 x 2 m at d_eps = 0.5: voxels of h = 0.25 m, (2W/d)(2H/d) = 12 x 8 = 96 voxels, one
    // cache each (one normal), each a voxel's h^2 of plane. Neighbouring caches are h apart, more than
    // the join distance h/2, so joining changes nothing. The 5 x 3 tessellation cuts across voxels; the
    // transform moves the plane off the origin and makes it face +x.
    Mesh mesh;
    addRect(mesh, glm::vec3(0.0f), glm::vec3(3, 0, 0), glm::vec3(0, 0, -2), 5, 3); // faces +y
    const glm::mat4 worldFromObject = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(1.3f, 0.7f, -2.1f)),
                                                  glm::radians(-90.0f), glm::vec3(0, 0, 1)); // +y -> +x
    const Scene scene = sceneOf(mesh, worldFromObject);
    const float d = 0.5f, h = 0.5f * d;
    for (const bool join : {true, false})
        for (const bool snap : {true, false}) {
            LightCacheParams params = paramsWith(d);
            params.join = join;
            params.snap = snap;
            const LightCacheSet set = distribute(scene, params);
            INFO("join " << join << ", snap " << snap);
            REQUIRE(set.caches.size() == 96u);
            double area = 0.0;
            int off = 0;
            for (const LightCache& c : set.caches) {
                area += c.area;
                off += glm::length(c.normal - glm::vec3(1, 0, 0)) < 1e-6f ? 0 : 1;
                // Every Voronoi cell is a voxel's square: pieces go to their own voxel's cache (at most
                // 0.36 h away) before any other (0.79 h). float sums of 4 pieces: ~1e-7 relative.
                CHECK(c.area == Approx(h * h).epsilon(1e-5));
                // On the plane x = 1.3 (snapping moves nothing there), at the voxel centres.
                CHECK(c.position.x == Approx(1.3f).margin(1e-5));
            }
            CHECK(off == 0);
            CHECK(area == Approx(6.0).epsilon(1e-5));
        }
}

TEST_CASE("light caches: a double-sided plane gets each cache on both sides, a mirrored one its own side, a tiny d_eps "
          "is refused",
          "[lightskin][caches]")
{
    Mesh mesh;
    addRect(mesh, glm::vec3(0.0f), glm::vec3(2, 0, 0), glm::vec3(0, 0, -1), 3, 2); // 2 x 1 m, faces +y
    Scene scene = sceneOf(mesh, glm::mat4(1.0f));
    const std::size_t oneSided = distribute(scene, paramsWith(0.5f)).caches.size();
    CHECK(oneSided == 32u); // (2W/d)(2H/d) = 8 x 4
    scene.materials[0].doubleSided = true;
    const LightCacheSet set = distribute(scene, paramsWith(0.5f));
    REQUIRE(set.caches.size() == 2 * oneSided);
    int up = 0, down = 0;
    for (const LightCache& c : set.caches) {
        up += c.normal.y > 0.999999f ? 1 : 0;
        down += c.normal.y < -0.999999f ? 1 : 0;
    }
    CHECK(up == 32);
    CHECK(down == 32);
    shared::LightCacheNeighbours found;
    CHECK(nearestLightCaches(set, glm::vec3(1.0f, 0.0f, -0.5f), glm::vec3(0, -1, 0), found) > 0); // seen from below

    // A mirroring instance transform reverses the winding, not the side the vertex normals give.
    scene.materials[0].doubleSided = false;
    scene.instances[0].worldFromObject = glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
    int mirroredUp = 0;
    for (const LightCache& c : distribute(scene, paramsWith(0.5f)).caches)
        mirroredUp += c.normal.y > 0.999999f ? 1 : 0;
    CHECK(mirroredUp == 32);

    // 2 m^2 cut into (d/4)^2 pieces: d = 1e-3 m would be 3.2e7 pieces, over the 1e7 limit.
    CHECK_THROWS_AS(distribute(scene, paramsWith(1e-3f)), Error);
}

TEST_CASE("light caches: a closed box gets the plane count per face and no cache across an edge", "[lightskin][caches]")
{
    // A 2 m cube at d_eps = 0.5: 8 x 8 caches per face, 384 in all. The voxels along an edge hold pieces
    // of two faces 90 degrees apart (more than theta_eps = 30 from any one bin centre), so they give two
    // caches, one on each face with that face's normal: no cache is tilted (45 degrees) at an edge. The
    // instance is rotated by 90 degrees about y (float cosines leave the faces ~1e-7 off the voxel
    // planes: the pieces must not produce slivers there) and moved.
    const glm::mat4 worldFromObject = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(-3.0f, 0.5f, 4.0f)),
                                                  glm::radians(90.0f), glm::vec3(0, 1, 0));
    const Scene scene = sceneOf(boxMesh(2.0f, 7), worldFromObject);
    const LightCacheSet set = distribute(scene, paramsWith(0.5f));
    REQUIRE(set.caches.size() == 384u);
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    int perFace[6] = {};
    int tilted = 0;
    double area = 0.0;
    for (const LightCache& c : set.caches) {
        area += c.area;
        int face = -1;
        for (int f = 0; f < 6; ++f)
            if (glm::dot(c.normal, axes[f]) > 1.0f - 1e-6f) face = f;
        if (face < 0)
            ++tilted;
        else
            ++perFace[face];
        CHECK(c.area == Approx(0.0625).epsilon(1e-5)); // every cache a voxel's square of its face
    }
    CHECK(tilted == 0);
    for (int f = 0; f < 6; ++f)
        CHECK(perFace[f] == 64);
    CHECK(area == Approx(24.0).epsilon(1e-5));

    // A d_eps that does not divide the box (voxels of 0.15 m):
    // still no tilted cache, and the areas still sum to the surface.
    const LightCacheSet coarse = distribute(scene, paramsWith(0.3f));
    int coarseTilted = 0;
    double coarseArea = 0.0;
    for (const LightCache& c : coarse.caches) {
        coarseArea += c.area;
        bool axis = false;
        for (const glm::vec3& a : axes)
            axis = axis || glm::dot(c.normal, a) > 1.0f - 1e-6f;
        coarseTilted += axis ? 0 : 1;
    }
    CHECK(coarseTilted == 0);
    CHECK(coarseArea == Approx(24.0).epsilon(1e-5));
    // 2 / 0.15 = 13.3 voxels per edge, so 14 x 14 per face, the last row a third of a voxel wide: its
    // caches lie 0.67 h from the full row's, beyond the join distance h / 2, so none merge.
    CHECK(coarse.caches.size() == 6u * 14u * 14u);
}

TEST_CASE("light caches: areas sum to the surface area, snapped caches lie on the surface", "[lightskin][caches]")
{
    SECTION("cornell, automatic d_eps, per instance")
    {
        const Scene scene = makeBuiltinScene("cornell");
        std::vector<std::pair<std::string, int>> calls;
        const LightCacheSet set = distributeLightCaches(
            scene, LightCacheParams{},
            [&](const std::string& task, int done, int total) {
                CHECK(total == static_cast<int>(scene.instances.size()));
                calls.emplace_back(task, done);
            },
            "");
        REQUIRE(calls.size() == scene.instances.size() + 1); // 0, then one per instance
        for (std::size_t i = 0; i < calls.size(); ++i) {
            CHECK(calls[i].first == "lightskin caches");
            CHECK(calls[i].second == static_cast<int>(i));
        }
        REQUIRE(set.instanceStart.size() == scene.instances.size() + 1);
        for (std::size_t i = 0; i < scene.instances.size(); ++i) {
            double area = 0.0;
            for (std::uint32_t c = set.instanceStart[i]; c < set.instanceStart[i + 1]; ++c)
                area += set.caches[c].area;
            INFO("instance " << i);
            // float areas of a few hundred caches summed in double: measured relative error < 1e-6.
            CHECK(area == Approx(worldArea(scene, scene.instances[i])).epsilon(3e-6));
        }
    }
    SECTION("sphere (the furnace, normals inwards): on the tessellation with snapping, inside without")
    {
        FurnaceParams furnace;
        furnace.rings = 24;
        furnace.segments = 48;
        const Scene scene = makeFurnace(furnace);
        const double total = worldArea(scene, scene.instances[0]);
        const Mesh& mesh = scene.meshes[0];
        // Distance from a point to the tessellated sphere (brute force over its triangles).
        auto distanceToMesh = [&](const glm::vec3& p) {
            double best = 1e30;
            for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
                const glm::dvec3 a(mesh.vertices[mesh.indices[t]].position),
                    b(mesh.vertices[mesh.indices[t + 1]].position), c(mesh.vertices[mesh.indices[t + 2]].position);
                const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
                const glm::dvec3 x(p);
                const glm::dvec3 q = x - glm::dot(x - a, n) * n;
                const bool inside = glm::dot(glm::cross(b - a, q - a), n) >= 0 &&
                                    glm::dot(glm::cross(c - b, q - b), n) >= 0 &&
                                    glm::dot(glm::cross(a - c, q - c), n) >= 0;
                if (inside) best = std::min(best, glm::length(x - q));
                for (const auto& [s, e] : {std::pair(a, b), std::pair(b, c), std::pair(c, a)}) {
                    const double along = std::clamp(glm::dot(x - s, e - s) / glm::dot(e - s, e - s), 0.0, 1.0);
                    best = std::min(best, glm::length(x - (s + along * (e - s))));
                }
            }
            return best;
        };
        for (const bool snap : {true, false}) {
            LightCacheParams params = paramsWith(0.25f);
            params.snap = snap;
            const LightCacheSet set = distribute(scene, params);
            double area = 0.0, worst = 0.0;
            for (const LightCache& c : set.caches) {
                area += c.area;
                worst = std::max(worst, distanceToMesh(c.position));
                CHECK(glm::length(c.normal) == Approx(1.0f).epsilon(1e-6));
                // The normals point inwards (towards the centre) like the surface's.
                CHECK(glm::dot(c.normal, -c.position) > 0.0f);
            }
            INFO("snap " << snap << ", caches " << set.caches.size() << ", worst distance " << worst);
            CHECK(area == Approx(total).epsilon(3e-6));
            if (snap)
                CHECK(worst < 1e-5); // measured 4e-8: rounding of the float positions
            else
                CHECK(worst > 1e-3); // a mean of a curved patch lies inside the sphere (measured 3.1e-3 m)
        }
    }
}

TEST_CASE("light caches: every surface point has a facing cache within d_eps", "[lightskin][caches]")
{
    // The paper's meaning of d_eps: the largest distance between a surface point and its cache.
    for (const char* name : {"cornell", "maze", "street"}) {
        const Scene scene = makeBuiltinScene(name);
        const LightCacheSet set = distribute(scene, LightCacheParams{});
        const SurfacePoints points = sampleSurfacePoints(scene, 20000, 7);
        int without = 0;
        shared::LightCacheNeighbours found;
        for (std::size_t i = 0; i < points.positions.size(); ++i)
            without += nearestLightCaches(set, points.positions[i], points.normals[i], found) > 0 ? 0 : 1;
        INFO(name << ": d_eps " << set.distance << " m, " << set.caches.size() << " caches");
        CHECK(without == 0);
    }
}

TEST_CASE("light caches: the shared lookup finds the k nearest facing caches as brute force does",
          "[lightskin][caches]")
{
    const Scene scene = makeBuiltinScene("cornell");
    LightCacheSet set = distribute(scene, LightCacheParams{});
    REQUIRE(set.caches.size() > 100u);

    // Brute force over all caches: n . n_c > 0, |x - c|^2 < r^2, sorted by (d^2, index), first k.
    auto bruteForce = [&](const glm::vec3& x, const glm::vec3& n, int k, float radius) {
        std::vector<std::pair<float, int>> all;
        for (std::size_t c = 0; c < set.caches.size(); ++c) {
            if (!(glm::dot(n, set.caches[c].normal) > 0.0f)) continue;
            const glm::vec3 offset = set.caches[c].position - x;
            const float d2 = glm::dot(offset, offset);
            if (d2 < radius * radius) all.emplace_back(d2, static_cast<int>(c));
        }
        std::sort(all.begin(), all.end());
        all.resize(std::min(all.size(), static_cast<std::size_t>(k)));
        return all;
    };
    auto compare = [&](const std::vector<glm::vec3>& xs, const std::vector<glm::vec3>& ns, int k) {
        int mismatches = 0, full = 0;
        double foundTotal = 0.0;
        shared::LightCacheNeighbours found;
        for (std::size_t i = 0; i < xs.size(); ++i) {
            const auto expected = bruteForce(xs[i], ns[i], k, set.grid.cellSize);
            nearestLightCaches(set, xs[i], ns[i], found, k);
            bool same = found.count == static_cast<int>(expected.size());
            for (int j = 0; same && j < found.count; ++j)
                same = found.index[j] == expected[static_cast<std::size_t>(j)].second &&
                       found.distance2[j] == expected[static_cast<std::size_t>(j)].first;
            mismatches += same ? 0 : 1;
            full += found.count == k ? 1 : 0;
            foundTotal += found.count;
        }
        INFO("k " << k << ", full sets " << full << " of " << xs.size() << ", mean count " << foundTotal / xs.size());
        CHECK(mismatches == 0);
        return full;
    };

    const SurfacePoints points = sampleSurfacePoints(scene, 3000, 11);
    compare(points.positions, points.normals, 16);
    // Within d_eps a plane holds about pi d^2 / h^2 = 12.6 caches, so 16 slots rarely fill there;
    // k = 4 fills, which exercises the insertion's eviction of the farthest entry.
    CHECK(compare(points.positions, points.normals, 4) > 1000);

    // Points anywhere in (and around) the bounds with random normals: cells at the grid's border and
    // beyond it, caches behind the point.
    std::mt19937 engine(5);
    auto uniform = [&]() { return static_cast<float>(engine() >> 8u) * 0x1p-24f; };
    const AABB bounds = scene.worldBounds();
    std::vector<glm::vec3> xs, ns;
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 t(uniform(), uniform(), uniform());
        xs.push_back(bounds.lower - 0.2f * bounds.extent() + 1.4f * t * bounds.extent());
        ns.push_back(glm::normalize(glm::vec3(uniform(), uniform(), uniform()) - 0.5f));
    }
    compare(xs, ns, 16);

    // Cells of 2 mm: about 2e7 cells over the 0.55 m box, five times the 4M cells the former dense grid
    // was capped at (it widened its cells, and the radius with them); the radius stays what was asked.
    buildLightCacheGrid(set, 2e-3f);
    CHECK(set.grid.cellSize == 2e-3f);
    CHECK(set.grid.slots.size() <= 4 * set.caches.size());
    compare(points.positions, points.normals, 16);
    // Cells of 5 cm, so that points find caches, and the slot table's probing: collisions happen.
    buildLightCacheGrid(set, 0.05f);
    CHECK(set.grid.maxProbe > 0);
    CHECK(compare(points.positions, points.normals, 4) > 100);
}

TEST_CASE("light caches: the lookup's spatial hash spans an open world at the asked radius", "[lightskin][caches]")
{
    // 20000 caches in clusters strewn over 200 km x 2 km x 200 km at d_eps 1 m: 4e13 cells, of which a
    // few thousand are occupied. Every query (near a cluster, between clusters, beyond the world) finds
    // what brute force finds, and the table holds at most four slots per cache.
    std::mt19937 engine(9);
    auto uniform = [&]() { return static_cast<float>(engine() >> 8u) * 0x1p-24f; };
    LightCacheSet set;
    std::vector<glm::vec3> centres;
    for (int c = 0; c < 400; ++c)
        centres.push_back(glm::vec3(2e5f * uniform(), 2e3f * uniform(), 2e5f * uniform()));
    for (int i = 0; i < 20000; ++i) {
        LightCache cache;
        cache.position = centres[static_cast<std::size_t>(i % 400)] + 2.0f * (glm::vec3(uniform(), uniform(), uniform()) - 0.5f);
        cache.normal = glm::normalize(glm::vec3(uniform(), uniform(), uniform()) - glm::vec3(0.5f, 0.2f, 0.5f));
        set.caches.push_back(cache);
    }
    buildLightCacheGrid(set, 1.0f);
    CHECK(set.grid.cellSize == 1.0f);
    CHECK(set.grid.slots.size() <= 4 * set.caches.size());
    CHECK(set.grid.maxProbe > 0);
    int found = 0, mismatches = 0;
    shared::LightCacheNeighbours near;
    for (int q = 0; q < 4000; ++q) {
        const glm::vec3 centre = centres[static_cast<std::size_t>(q % 400)];
        const glm::vec3 x = q % 8 == 7 ? glm::vec3(2.4e5f * uniform() - 2e4f, 2e3f * uniform(), 2.4e5f * uniform() - 2e4f)
                                       : centre + 3.0f * (glm::vec3(uniform(), uniform(), uniform()) - 0.5f);
        const glm::vec3 n = glm::normalize(glm::vec3(uniform(), uniform(), uniform()) - 0.5f);
        std::vector<std::pair<float, int>> expected;
        for (std::size_t c = 0; c < set.caches.size(); ++c) {
            const glm::vec3 offset = set.caches[c].position - x;
            const float d2 = glm::dot(offset, offset);
            if (glm::dot(n, set.caches[c].normal) > 0.0f && d2 < 1.0f) expected.emplace_back(d2, static_cast<int>(c));
        }
        std::sort(expected.begin(), expected.end());
        expected.resize(std::min<std::size_t>(expected.size(), 16));
        nearestLightCaches(set, x, n, near, 16);
        bool same = near.count == static_cast<int>(expected.size());
        for (int j = 0; same && j < near.count; ++j)
            same = near.index[j] == expected[static_cast<std::size_t>(j)].second;
        mismatches += same ? 0 : 1;
        found += near.count;
    }
    INFO("caches found " << found << ", slots " << set.grid.slots.size() << ", max probe " << set.grid.maxProbe);
    CHECK(found > 6000); // 12351 measured: the queries near a cluster find about 3.5 caches each
    CHECK(mismatches == 0);
    // More than 2^21 cells along an axis: one clear error, not a silently wider radius.
    LightCacheSet wide;
    wide.caches.resize(2);
    wide.caches[1].position = glm::vec3(3e6f, 0.0f, 0.0f);
    CHECK_THROWS_WITH(buildLightCacheGrid(wide, 1.0f), Catch::Contains("2^21"));
}

TEST_CASE("light caches: the reach is exact for a straight wall and a concave corner", "[lightskin][caches]")
{
    // Reach records made from the closed form (a wall x = a, and a corner x = a, y = b, in the cache's
    // tangent frame: ray i stops at min(a / cos, b / sin) where positive), then every point of a grid
    // over the search disk: lightCacheReaches must accept exactly the points on the cache's side, up
    // to the lift plus two quantization steps (1/255 of the radius each). Measured 0 wrong of about
    // 30,000 points each; tried: with the chord between two hits alone (no walls through the outer
    // neighbours) the corner has 20 points wrong.
    const float radius = 1.0f, a = 0.3f, b = 0.45f;
    const glm::vec3 normal = glm::normalize(glm::vec3(0.2f, 0.3f, 0.9f));
    const glm::mat3 frame = shared::lightViewBasis(normal);
    for (const bool corner : {false, true}) {
        glm::uvec4 reach(0u);
        for (int i = 0; i <= shared::kLightCacheReachAzimuths; ++i) {
            const float azimuth = 6.28318531f * static_cast<float>(i) / shared::kLightCacheReachAzimuths;
            float t = radius;
            if (i < shared::kLightCacheReachAzimuths) {
                if (std::cos(azimuth) > 0.0f) t = std::min(t, a / std::cos(azimuth));
                if (corner && std::sin(azimuth) > 0.0f) t = std::min(t, b / std::sin(azimuth));
            }
            reach[i / 4] |= static_cast<std::uint32_t>(std::floor(t / radius * 255.0f)) << (8 * (i % 4));
        }
        const float tolerance = shared::kLightCacheReachLift * radius + 2.0f * radius / 255.0f;
        int wrong = 0, checked = 0;
        for (int iy = -100; iy <= 100; ++iy)
            for (int ix = -100; ix <= 100; ++ix) {
                const glm::vec2 q(0.01f * static_cast<float>(ix), 0.01f * static_cast<float>(iy));
                if (glm::length(q) >= radius) continue;
                const float beyond = std::max(q.x - a, corner ? q.y - b : -1.0f); // > 0: behind a wall
                if (std::abs(beyond) < tolerance) continue;
                ++checked;
                const bool accepted = shared::lightCacheReaches(reach, normal, frame[0] * q.x + frame[1] * q.y, radius);
                wrong += accepted == (beyond < 0.0f) ? 0 : 1;
            }
        INFO((corner ? "corner" : "wall") << ": " << wrong << " of " << checked << " points on the wrong side");
        CHECK(checked > 25000);
        CHECK(wrong == 0);
    }
}

TEST_CASE("light caches: with their reach, no cache lights the other side of a wall", "[lightskin][caches]")
{
    // `sealed`: two rooms side by side behind a 10 cm wall, their floors (and ceilings) in one plane
    // with one normal: within d_eps of a point near the wall lie caches of the other room. A point of
    // either room may only take caches inside its own room (the boxes below, 1 mm of slack), and
    // without the reach some do, so the check can fail.
    const Scene scene = makeBuiltinScene("sealed");
    LightCacheSet set = distribute(scene, LightCacheParams{});
    const SurfacePoints points = sampleSurfacePoints(scene, 20000, 13);
    struct Box {
        glm::vec3 lower, upper;
        bool holds(const glm::vec3& p) const
        {
            return glm::all(glm::greaterThan(p, lower - 1e-3f)) && glm::all(glm::lessThan(p, upper + 1e-3f));
        }
    };
    const Box rooms[2] = {{glm::vec3(-4.0f, 0.0f, -2.0f), glm::vec3(0.0f, 3.0f, 2.0f)},
                          {glm::vec3(0.1f, 0.0f, -2.0f), glm::vec3(4.1f, 3.0f, 2.0f)}};
    auto count = [&](int& crossing, int& without, int& inside) {
        crossing = without = inside = 0;
        shared::LightCacheNeighbours found;
        for (std::size_t i = 0; i < points.positions.size(); ++i)
            for (const Box& room : rooms) {
                if (!room.holds(points.positions[i])) continue;
                ++inside;
                const int n = nearestLightCaches(set, points.positions[i], points.normals[i], found);
                without += n == 0 ? 1 : 0;
                for (int j = 0; j < n; ++j)
                    if (!room.holds(set.caches[static_cast<std::size_t>(found.index[j])].position)) {
                        ++crossing;
                        break;
                    }
            }
    };
    int crossing = 0, without = 0, inside = 0;
    count(crossing, without, inside);
    INFO("d_eps " << set.distance << " m, " << set.caches.size() << " caches, " << inside
                  << " points inside the rooms");
    CHECK(inside > 5000);
    CHECK(crossing > 500); // without the reach: measured 2245 points take a cache of the other room
    set.reach = traceLightCacheReach(RayScene(scene), set.caches, set.grid.cellSize);
    count(crossing, without, inside);
    CHECK(crossing == 0);
    CHECK(without == 0); // the reach leaves no point of a room without a cache (no fallback either: 0 measured)
}

TEST_CASE("light caches: the reach agrees with Embree rays along each cache-point pair", "[lightskin][caches]")
{
    // An independent check of lightCacheReaches, the 15-ray summary, against a ray per pair: for points
    // the scene's cameras see (first hits of random rays from each camera) and every cache within d_eps
    // whose normal is within 45 degrees of the point's (the pairs eq. (8) weighs; at right angles the
    // weight vanishes), the path the reach rays take, in the pair's own direction: from the cache
    // lifted by the reach's lift, rising at kLightCacheReachSlope to above the point, and up the
    // cache's normal to the point's height. The summary misses openings narrower than the ray spacing
    // and cuts convex corners, so the two differ; the bounds are about 2.5x the measured disagreement
    // (measured: accepted but blocked 0.80% / 0.12% / 0 of the pairs, rejected but open 2.1% / 5.3% /
    // 0.1% of the rejected ones, on maze / canyon / sealed). Also bounds how often a point no cache
    // reaches falls back to the caches without the test (measured 0.04% / 0.10% / 0 of the points).
    for (const char* name : {"maze", "canyon", "sealed"}) {
        const Scene scene = makeBuiltinScene(name);
        LightCacheSet set = distribute(scene, LightCacheParams{});
        const RayScene rays(scene);
        set.reach = traceLightCacheReach(rays, set.caches, set.grid.cellSize);
        const float radius = set.grid.cellSize, lift = shared::kLightCacheReachLift * radius;
        std::mt19937 engine(3);
        std::normal_distribution<float> gaussian;
        std::vector<glm::vec3> xs, ns;
        for (int i = 0; i < 8000; ++i) {
            Ray ray;
            ray.origin = scene.cameras[static_cast<std::size_t>(i) % scene.cameras.size()].position;
            ray.direction = glm::normalize(glm::vec3(gaussian(engine), gaussian(engine), gaussian(engine)));
            const Hit hit = rays.intersect(ray);
            if (!hit.valid()) continue;
            const glm::vec3 n = glm::normalize(hit.geometricNormal);
            xs.push_back(ray.origin + hit.t * ray.direction);
            ns.push_back(glm::dot(n, ray.direction) > 0.0f ? -n : n);
        }
        int pairs = 0, acceptedBlocked = 0, rejected = 0, rejectedOpen = 0, fallbacks = 0;
        shared::LightCacheNeighbours found;
        for (std::size_t i = 0; i < xs.size(); ++i) {
            const int count = nearestLightCaches(set, xs[i], ns[i], found);
            bool reached = count == 0;
            for (int j = 0; j < count && !reached; ++j) {
                const auto c = static_cast<std::size_t>(found.index[j]);
                reached = glm::dot(ns[i], set.caches[c].normal) > shared::kLightCacheReachMinCos &&
                          shared::lightCacheReaches(set.reach[c], set.caches[c].normal, xs[i] - set.caches[c].position,
                                                    radius);
            }
            fallbacks += reached ? 0 : 1;
            if (i % 4 != 0) continue; // the brute force over every cache on a quarter of the points
            for (std::size_t c = 0; c < set.caches.size(); ++c) {
                const LightCache& cache = set.caches[c];
                const glm::vec3 offset = xs[i] - cache.position;
                if (!(glm::dot(ns[i], cache.normal) > 0.7f) || !(glm::dot(offset, offset) < radius * radius)) continue;
                ++pairs;
                const float height = glm::dot(offset, cache.normal);
                const glm::vec3 tangential = offset - height * cache.normal;
                const float along = glm::length(tangential);
                const glm::vec3 from = cache.position + lift * cache.normal;
                bool open =
                    height >= -lift - shared::kLightCacheReachSlope * along &&
                    rays.visible(from, from + tangential + shared::kLightCacheReachSlope * along * cache.normal);
                if (open && height > 0.0f) {
                    Ray up;
                    up.origin = from;
                    up.direction = cache.normal;
                    up.tMax = height;
                    open = !rays.occluded(up);
                }
                if (shared::lightCacheReaches(set.reach[c], cache.normal, offset, radius)) {
                    acceptedBlocked += open ? 0 : 1;
                } else {
                    ++rejected;
                    rejectedOpen += open ? 1 : 0;
                }
            }
        }
        INFO(name << ": " << xs.size() << " points, " << fallbacks << " fell back; " << pairs << " pairs, "
                  << acceptedBlocked << " accepted but blocked, " << rejected << " rejected, " << rejectedOpen
                  << " of them open");
        CHECK(xs.size() > 2500u); // canyon: 3119 of the 8000 rays hit (the rest is sky)
        CHECK(pairs > 5000);
        CHECK(rejected > 100);
        CHECK(acceptedBlocked <= 0.02 * pairs);
        CHECK(rejectedOpen <= 0.13 * rejected);
        CHECK(fallbacks <= 0.0025 * static_cast<double>(xs.size()));
    }
}

TEST_CASE("light caches: the disk cache hits, misses on a changed vertex or parameter, survives damage",
          "[lightskin][caches]")
{
    Scene scene = makeBuiltinScene("cornell");
    const std::filesystem::path dir = freshDirectory("light-caches");
    const LightCacheParams params;
    const int instances = static_cast<int>(scene.instances.size());

    const LightCacheSet first = distribute(scene, params, dir.string());
    CHECK(first.instancesComputed == instances);
    CHECK(first.instancesLoaded == 0);
    const std::vector<std::filesystem::path> files = filesIn(dir / "lightskin");
    CHECK(files.size() == static_cast<std::size_t>(instances)); // cornell's instances all differ

    const LightCacheSet second = distribute(scene, params, dir.string());
    CHECK(second.instancesLoaded == instances);
    CHECK(second.instancesComputed == 0);
    CHECK(sameBits(first, second));
    CHECK(sameBits(first, distribute(scene, params))); // and the same as without a disk cache

    SECTION("a changed parameter misses")
    {
        LightCacheParams other = params;
        other.angleDegrees = 25.0f;
        const LightCacheSet changed = distribute(scene, other, dir.string());
        CHECK(changed.instancesComputed == instances);
        LightCacheParams noJoin = params;
        noJoin.join = false;
        CHECK(distribute(scene, noJoin, dir.string()).instancesComputed == instances);
    }
    SECTION("one changed vertex misses for the instances of its mesh only")
    {
        scene.meshes[0].vertices[0].position.x += 1e-3f;
        int users = 0;
        for (const Instance& i : scene.instances)
            users += i.mesh == 0 ? 1 : 0;
        const LightCacheSet changed = distribute(scene, params, dir.string());
        CHECK(changed.instancesComputed == users);
        CHECK(changed.instancesLoaded == instances - users);
    }
    SECTION("a truncated, corrupted or misnamed file is recomputed, to the same result")
    {
        std::filesystem::resize_file(files[0], std::filesystem::file_size(files[0]) - 5);
        {
            std::fstream f(files[1], std::ios::in | std::ios::out | std::ios::binary);
            f.seekp(40); // inside the first cache record
            f.put('\x7f');
        }
        {
            std::ofstream f(files[2], std::ios::binary | std::ios::trunc);
            f << "not a cache";
        }
        // A valid file under another instance's name (copied over it): the key inside tells.
        std::filesystem::copy_file(files[4], files[3], std::filesystem::copy_options::overwrite_existing);
        const LightCacheSet repaired = distribute(scene, params, dir.string());
        CHECK(repaired.instancesComputed == 4);
        CHECK(repaired.instancesLoaded == instances - 4);
        CHECK(sameBits(first, repaired));
        // ... and rewritten: the next call loads everything again.
        CHECK(distribute(scene, params, dir.string()).instancesLoaded == instances);
    }
    std::filesystem::remove_all(dir);
}

TEST_CASE("light caches: the same bits at 1, 2 and 4 TBB threads", "[lightskin][caches]")
{
    for (const char* name : {"cornell", "maze"}) {
        const Scene scene = makeBuiltinScene(name);
        auto run = [&](int threads) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
            return distribute(scene, LightCacheParams{});
        };
        const LightCacheSet one = run(1);
        INFO(name);
        CHECK(sameBits(one, run(2)));
        CHECK(sameBits(one, run(4)));
    }
}

TEST_CASE("light caches: the automatic importance clamp is 1 m on street and follows the scene's scale", "[lightskin][caches]")
{
    // resolveImportanceClamp: sqrt(A / 93148 m^2). street's surface is 93,147.5 m^2 (the counts
    // table below), so its clamp is the paper's 1 m; float areas summed in double differ by < 1e-6.
    const Scene street = makeBuiltinScene("street");
    CHECK(resolveImportanceClamp(street, 0.0f) == Approx(1.0).epsilon(1e-5));
    CHECK(resolveImportanceClamp(street, 0.25f) == 0.25f); // a clamp set by hand is used as it is
    // The same scene in millimetres (every coordinate x 1000) gets 1000x the clamp, so eq. (11)
    // weighs its VALs as the metre scene's; a fixed 1 would clamp at 1 mm there.
    for (const char* name : {"cornell", "maze", "canyon"}) {
        Scene scene = makeBuiltinScene(name);
        const float metres = resolveImportanceClamp(scene, 0.0f);
        for (Instance& instance : scene.instances)
            instance.worldFromObject = glm::scale(glm::mat4(1.0f), glm::vec3(1000.0f)) * instance.worldFromObject;
        INFO(name << ": " << metres << " m");
        CHECK(metres > 0.0f);
        CHECK(resolveImportanceClamp(scene, 0.0f) == Approx(1000.0 * metres).epsilon(1e-5));
    }
    Scene empty;
    empty.name = "empty";
    CHECK_THROWS_AS(resolveImportanceClamp(empty, 0.0f), Error);
}

TEST_CASE("light caches: counts and times of the built-in scenes", "[lightskin][numbers]")
{
    // Prints the table the report quotes (times are printed, never asserted); checks what must hold
    // whatever the timing: the areas are the scenes' surface areas, fewer caches for a larger d_eps,
    // and the automatic d_eps gives "a few thousand" caches on each scene.
    std::printf("%-8s %10s %9s %9s %10s %14s\n", "scene", "d_eps [m]", "caches", "time [s]", "area [m2]",
                "caches d^2/4A");
    for (const char* name : {"street", "cornell", "maze"}) {
        const Scene scene = makeBuiltinScene(name);
        double surface = 0.0;
        for (const Instance& i : scene.instances)
            surface += worldArea(scene, i);
        const float automatic = resolveLightCacheDistance(scene, LightCacheParams{});
        std::size_t previous = 0;
        for (const float d : {0.5f * automatic, automatic, 2.0f * automatic, 4.0f * automatic}) {
            const auto start = std::chrono::steady_clock::now();
            const LightCacheSet set = distribute(scene, paramsWith(d));
            const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            double area = 0.0;
            for (const LightCache& c : set.caches)
                area += c.area;
            // caches d^2 / 4A: 1 for a flat scene, more for the edges, corners and small parts.
            std::printf("%-8s %10.3g %9zu %9.3f %10.1f %14.2f%s\n", name, static_cast<double>(d), set.caches.size(),
                        seconds, area, static_cast<double>(set.caches.size()) * d * d / (4.0 * area),
                        d == automatic ? "  (automatic)" : "");
            INFO(name << " at d_eps " << d);
            CHECK(area == Approx(surface).epsilon(3e-6)); // float areas summed in double: < 1e-6 measured
            if (previous > 0) CHECK(set.caches.size() < previous);
            previous = set.caches.size();
            if (d == automatic) {
                CHECK(set.caches.size() >= 1000u);
                CHECK(set.caches.size() <= 10000u);
            }
        }
    }
}
