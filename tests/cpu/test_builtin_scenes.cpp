// Built-in scenes: validity, the measured Cornell data, the furnace's geometry and closed forms,
// consistent winding, and the maze's and street's stated properties (size, occlusion, sun).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/builtin_scenes.h"
#include "core/util/error.h"

using namespace vplgi;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Triangle {
    glm::vec3 a, b, c;
};

std::vector<Triangle> worldTriangles(const Scene& scene)
{
    std::vector<Triangle> triangles;
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[instance.mesh];
        auto world = [&](std::uint32_t index) {
            return glm::vec3(instance.worldFromObject * glm::vec4(mesh.vertices[index].position, 1.0f));
        };
        for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
            triangles.push_back({world(mesh.indices[i]), world(mesh.indices[i + 1]), world(mesh.indices[i + 2])});
    }
    return triangles;
}

// Brute-force segment test (Moeller-Trumbore); the segment's own end points do not count.
bool segmentBlocked(const std::vector<Triangle>& triangles, const glm::vec3& from, const glm::vec3& to)
{
    const glm::vec3 d = to - from;
    for (const Triangle& t : triangles) {
        const glm::vec3 e1 = t.b - t.a, e2 = t.c - t.a;
        const glm::vec3 p = glm::cross(d, e2);
        const float det = glm::dot(e1, p);
        if (std::abs(det) < 1e-12f) continue;
        const float inv = 1.0f / det;
        const glm::vec3 s = from - t.a;
        const float u = glm::dot(s, p) * inv;
        if (u < 0.0f || u > 1.0f) continue;
        const glm::vec3 q = glm::cross(s, e1);
        const float v = glm::dot(d, q) * inv;
        if (v < 0.0f || u + v > 1.0f) continue;
        const float hit = glm::dot(e2, q) * inv;
        if (hit > 1e-4f && hit < 1.0f - 1e-4f) return true;
    }
    return false;
}

// Counts the rays from `origin` (26 directions, tilted off the axes so they graze nothing) whose
// nearest hit is a triangle's back side: a surface facing away from open space.
int backFacingHits(const std::vector<Triangle>& triangles, const glm::vec3& origin)
{
    int backFacing = 0;
    for (int i = 0; i < 27; ++i) {
        const glm::vec3 axis(i % 3 - 1, i / 3 % 3 - 1, i / 9 - 1);
        if (i == 13) continue; // zero
        const glm::vec3 d = glm::normalize(axis + glm::vec3(0.0131f, 0.0217f, 0.0173f));
        float nearest = 1e30f;
        glm::vec3 normal(0.0f);
        for (const Triangle& t : triangles) {
            const glm::vec3 e1 = t.b - t.a, e2 = t.c - t.a;
            const glm::vec3 p = glm::cross(d, e2);
            const float det = glm::dot(e1, p);
            if (std::abs(det) < 1e-12f) continue;
            const glm::vec3 s = origin - t.a;
            const float u = glm::dot(s, p) / det;
            if (u < 0.0f || u > 1.0f) continue;
            const glm::vec3 q = glm::cross(s, e1);
            const float v = glm::dot(d, q) / det;
            if (v < 0.0f || u + v > 1.0f) continue;
            const float hit = glm::dot(e2, q) / det;
            if (hit > 1e-4f && hit < nearest) {
                nearest = hit;
                normal = glm::cross(e1, e2);
            }
        }
        if (nearest < 1e30f && glm::dot(normal, d) >= 0.0f) ++backFacing;
    }
    return backFacing;
}

const Material& materialNamed(const Scene& scene, const std::string& name)
{
    for (const Material& m : scene.materials)
        if (m.name == name) return m;
    FAIL("no material " << name);
    throw Error("unreachable");
}

int materialIndex(const Scene& scene, const std::string& name)
{
    for (std::size_t i = 0; i < scene.materials.size(); ++i)
        if (scene.materials[i].name == name) return static_cast<int>(i);
    FAIL("no material " << name);
    return -1;
}

} // namespace

TEST_CASE("builtin scenes: names, validity, default camera, source")
{
    const std::vector<std::string> expected{"cornell", "furnace", "maze", "street"};
    REQUIRE(builtinSceneNames() == expected);
    CHECK_FALSE(isBuiltinScene("Cornell"));
    CHECK_FALSE(isBuiltinScene(""));
    for (const std::string& name : expected) {
        INFO(name);
        CHECK(isBuiltinScene(name));
        const Scene scene = makeBuiltinScene(name);
        CHECK_NOTHROW(scene.validate());
        CHECK(scene.name == name);
        CHECK(scene.source == "builtin:" + name);
        REQUIRE_FALSE(scene.cameras.empty());
        CHECK(scene.cameras[0].name == "default");
        CHECK(scene.triangleCount() > 0);
        for (const Instance& instance : scene.instances) {
            // Proper rigid placements only: winding and normals stay valid in world space.
            CHECK(glm::determinant(glm::mat3(instance.worldFromObject)) == Approx(1.0f).margin(1e-5));
        }
    }
}

TEST_CASE("builtin scenes: unknown name throws Error naming the choices")
{
    CHECK_THROWS_AS(makeBuiltinScene("nope"), Error);
    CHECK_THROWS_WITH(makeBuiltinScene("nope"),
                      "unknown scene \"nope\" (built-in scenes: cornell, furnace, maze, street)");
}

TEST_CASE("builtin scenes: triangle winding agrees with the vertex normals")
{
    FurnaceParams coarse;
    coarse.rings = 5;
    coarse.segments = 7;
    std::vector<std::pair<std::string, Scene>> scenes;
    for (const std::string& name : builtinSceneNames()) scenes.emplace_back(name, makeBuiltinScene(name));
    scenes.emplace_back("coarse furnace", makeFurnace(coarse));
    for (const auto& [name, scene] : scenes) {
        for (const Mesh& mesh : scene.meshes) {
            std::size_t bad = 0, badNormals = 0, firstBad = 0;
            for (const Vertex& v : mesh.vertices)
                if (std::abs(glm::length(v.normal) - 1.0f) > 1e-4f) ++badNormals;
            for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
                const Vertex& a = mesh.vertices[mesh.indices[3 * t]];
                const Vertex& b = mesh.vertices[mesh.indices[3 * t + 1]];
                const Vertex& c = mesh.vertices[mesh.indices[3 * t + 2]];
                const glm::vec3 face = glm::cross(b.position - a.position, c.position - a.position);
                const float length = glm::length(face);
                // Counter-clockwise seen from the normal's side; also no degenerate triangles.
                const bool ok = length > 0.0f && glm::dot(face, a.normal) > 0.5f * length &&
                                glm::dot(face, b.normal) > 0.5f * length && glm::dot(face, c.normal) > 0.5f * length;
                if (!ok && bad++ == 0) firstBad = t;
            }
            INFO(name << ": mesh " << mesh.name << ", first bad triangle " << firstBad);
            CHECK(bad == 0);
            CHECK(badNormals == 0);
        }
    }
}

TEST_CASE("builtin scenes: every surface seen from open space shows its front")
{
    std::vector<std::pair<std::string, std::vector<glm::vec3>>> viewpoints{
        {"cornell", {glm::vec3(-0.278f, 0.4f, -0.1f), glm::vec3(-0.1f, 0.1f, -0.5f)}},
        {"furnace", {glm::vec3(0.0f), glm::vec3(0.3f, -0.5f, 0.2f)}},
        {"street", {glm::vec3(0.0f, 10.0f, -60.0f), glm::vec3(-3.0f, 2.0f, 0.0f), glm::vec3(4.0f, 20.0f, 60.0f)}},
        {"maze", {}},
    };
    // Street: above both rows of roofs.
    for (float z = -60.0f; z <= 60.0f; z += 20.0f) {
        viewpoints[2].second.emplace_back(-15.0f, 45.0f, z);
        viewpoints[2].second.emplace_back(15.0f, 45.0f, z);
    }
    // Maze: every room's centre (no furniture there), alternately at eye height and just under
    // the ceiling (to see the tops of the furniture).
    int room = 0;
    for (float x = -12.0f; x <= 12.0f; x += 6.0f)
        for (float z = -9.0f; z <= 9.0f; z += 6.0f, ++room)
            viewpoints.back().second.emplace_back(x, room % 2 == 0 ? 1.5f : 2.8f, z);
    for (const auto& [name, points] : viewpoints) {
        const Scene scene = makeBuiltinScene(name);
        const std::vector<Triangle> triangles = worldTriangles(scene);
        std::vector<glm::vec3> origins = points;
        for (const Camera& camera : scene.cameras) origins.push_back(camera.position);
        for (const glm::vec3& origin : origins) {
            INFO(name << " from " << origin.x << " " << origin.y << " " << origin.z);
            CHECK(backFacingHits(triangles, origin) == 0);
        }
    }
}

TEST_CASE("cornell: measured dimensions, light and materials")
{
    const Scene scene = makeBuiltinScene("cornell");
    const AABB bounds = scene.worldBounds();
    // Measured data in metres, turned 180 degrees about y: x in [-0.556, 0], z in [-0.5592, 0].
    CHECK(bounds.lower.x == Approx(-0.556).margin(1e-3));
    CHECK(bounds.lower.y == Approx(0.0).margin(1e-3));
    CHECK(bounds.lower.z == Approx(-0.5592).margin(1e-3));
    CHECK(bounds.upper.x == Approx(0.0).margin(1e-3));
    CHECK(bounds.upper.y == Approx(0.5488).margin(1e-3));
    CHECK(bounds.upper.z == Approx(0.0).margin(1e-3));
    CHECK(scene.triangleCount() < 2000);
    CHECK(scene.lights.empty());

    const Material& light = materialNamed(scene, "light");
    CHECK(light.emission.r == 17.0f);
    CHECK(light.emission.g == 12.0f);
    CHECK(light.emission.b == 4.0f);
    int emissive = 0;
    for (const Material& m : scene.materials) {
        emissive += m.isEmissive() ? 1 : 0;
        INFO(m.name);
        CHECK(m.metallic == 0.0f); // pure Lambert
        CHECK(m.roughness == 1.0f);
        CHECK(m.specular == 0.0f);
    }
    CHECK(emissive == 1);
    CHECK(glm::vec3(materialNamed(scene, "white").baseColor) == glm::vec3(0.725f, 0.71f, 0.68f));
    CHECK(glm::vec3(materialNamed(scene, "red").baseColor) == glm::vec3(0.63f, 0.065f, 0.05f));
    CHECK(glm::vec3(materialNamed(scene, "green").baseColor) == glm::vec3(0.14f, 0.45f, 0.091f));

    const int lightMaterial = materialIndex(scene, "light");
    int lightVertices = 0;
    for (const Mesh& mesh : scene.meshes) {
        if (mesh.material != lightMaterial) continue;
        for (const Vertex& v : mesh.vertices) {
            ++lightVertices;
            CHECK(v.position.y == Approx(0.5487).margin(1e-6)); // just below the ceiling
            CHECK(v.position.x >= -0.343f - 1e-6f);
            CHECK(v.position.x <= -0.213f + 1e-6f);
            CHECK(v.position.z >= -0.332f - 1e-6f);
            CHECK(v.position.z <= -0.227f + 1e-6f);
            CHECK(v.normal == glm::vec3(0.0f, -1.0f, 0.0f)); // faces down
        }
    }
    CHECK(lightVertices >= 4);

    const Camera& camera = scene.cameras[0];
    CHECK(camera.position.x == Approx(-0.278));
    CHECK(camera.position.y == Approx(0.273));
    CHECK(camera.position.z == Approx(0.8));
    CHECK(camera.target.z == Approx(-0.2796));
    CHECK(camera.fovY == Approx(39.3 * kPi / 180.0));
}

TEST_CASE("cornell: closed on five sides, open towards the camera")
{
    const Scene scene = makeBuiltinScene("cornell");
    const std::vector<Triangle> triangles = worldTriangles(scene);
    const glm::vec3 centre(-0.278f, 0.2744f, -0.2796f);
    CHECK_FALSE(segmentBlocked(triangles, scene.cameras[0].position, centre + glm::vec3(0.0f, 0.0f, 0.2f)));
    for (const glm::vec3& away :
         {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, -1, 0), glm::vec3(0, 0, -1)}) {
        INFO("direction " << away.x << " " << away.y << " " << away.z);
        // Offset sideways so the blocks are not what stops the segment.
        CHECK(segmentBlocked(triangles, centre + glm::vec3(0.0f, 0.25f, 0.2f), centre + 2.0f * away));
    }
}

TEST_CASE("cornell: red wall left and green wall right in the default camera's image")
{
    const Scene scene = makeBuiltinScene("cornell");
    const glm::mat4 viewFromWorld = scene.cameras[0].viewFromWorld();
    const int red = materialIndex(scene, "red"), green = materialIndex(scene, "green");
    int redVertices = 0, greenVertices = 0;
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[instance.mesh];
        if (mesh.material != red && mesh.material != green) continue;
        for (const Vertex& v : mesh.vertices) {
            const glm::vec4 view = viewFromWorld * instance.worldFromObject * glm::vec4(v.position, 1.0f);
            CHECK(view.z < 0.0f); // in front of the camera
            if (mesh.material == red) {
                ++redVertices;
                CHECK(view.x < 0.0f);
            } else {
                ++greenVertices;
                CHECK(view.x > 0.0f);
            }
        }
    }
    CHECK(redVertices > 0);
    CHECK(greenVertices > 0);
}

TEST_CASE("furnace: inward sphere of radius R, centre light, camera")
{
    FurnaceParams params;
    params.radius = 2.5f;
    params.albedo = 0.7f;
    params.intensity = 3.0f;
    params.rings = 16;
    params.segments = 32;
    for (const FurnaceParams& p : {FurnaceParams{}, params}) {
        const Scene scene = makeFurnace(p);
        INFO("R = " << p.radius);
        REQUIRE(scene.meshes.size() == 1);
        const Mesh& sphere = scene.meshes[0];
        CHECK(sphere.triangleCount() == static_cast<std::size_t>(2 * p.segments * (p.rings - 1)));
        std::size_t badPosition = 0, badNormal = 0, outward = 0;
        for (const Vertex& v : sphere.vertices) {
            if (std::abs(glm::length(v.position) - p.radius) > 1e-5f) ++badPosition;
            if (glm::length(v.normal + v.position / p.radius) > 1e-5f) ++badNormal;
        }
        for (std::size_t t = 0; t < sphere.triangleCount(); ++t) {
            const glm::vec3 a = sphere.vertices[sphere.indices[3 * t]].position;
            const glm::vec3 b = sphere.vertices[sphere.indices[3 * t + 1]].position;
            const glm::vec3 c = sphere.vertices[sphere.indices[3 * t + 2]].position;
            // Counter-clockwise seen from inside: the face normal points at the centre.
            if (glm::dot(glm::cross(b - a, c - a), a + b + c) >= 0.0f) ++outward;
        }
        CHECK(badPosition == 0);
        CHECK(badNormal == 0);
        CHECK(outward == 0);

        const Material& wall = scene.materials[sphere.material];
        CHECK(glm::vec3(wall.baseColor) == glm::vec3(p.albedo));
        CHECK(wall.specular == 0.0f);
        CHECK(wall.metallic == 0.0f);
        REQUIRE(scene.lights.size() == 1);
        const Light& light = scene.lights[0];
        CHECK(light.name == "center");
        CHECK(light.type == LightType::Point);
        CHECK(light.position == glm::vec3(0.0f));
        CHECK(light.radiantIntensity() == glm::vec3(p.intensity));
        const Camera& camera = scene.cameras[0];
        CHECK(camera.position == glm::vec3(0.0f));
        CHECK(camera.target == glm::vec3(0.0f, 0.0f, -1.0f));
        CHECK(camera.fovY == Approx(kPi / 3.0));
        CHECK(camera.zNear == Approx(0.01f));
        CHECK(camera.zFar == Approx(4.0f * p.radius));
    }
}

TEST_CASE("furnace: closed forms (MATH.md section 3)")
{
    FurnaceParams pbrt; // rho = 0.5, I0 = pi (as a float), R = 1: pbrt's "radiance of 1"
    pbrt.radius = 1.0f;
    pbrt.albedo = 0.5f;
    pbrt.intensity = static_cast<float>(kPi);
    CHECK(furnaceRadianceAll(pbrt) == Approx(1.0).epsilon(1e-6)); // float pi is off by 3e-8
    CHECK(furnaceRadianceBounce(pbrt, 0) == 0.0);

    FurnaceParams other;
    other.radius = 2.0f;
    other.albedo = 0.8f;
    other.intensity = 3.0f;
    for (const FurnaceParams& p : {pbrt, other}) {
        const double rho = p.albedo, direct = rho * p.intensity / (kPi * p.radius * p.radius);
        CHECK(furnaceRadianceBounce(p, 1) == Approx(direct).epsilon(1e-12));
        CHECK(furnaceRadianceBounce(p, 2) == Approx(rho * direct).epsilon(1e-12));
        CHECK(furnaceRadianceAll(p) == Approx(direct / (1.0 - rho)).epsilon(1e-12));
        double sum = 0.0;
        for (int n = 1; n <= 400; ++n) sum += furnaceRadianceBounce(p, n); // rho^400 < 1e-38
        CHECK(std::abs(sum - furnaceRadianceAll(p)) < 1e-9);
    }
}

TEST_CASE("maze: size, lamps, determinism")
{
    const Scene scene = makeBuiltinScene("maze");
    CHECK(scene.triangleCount() >= 200000);
    CHECK(scene.triangleCount() <= 400000);

    // 6 m cells inside 0.2 m outer walls, 3 m high: 5 x 4 = 20 rooms.
    const AABB bounds = scene.worldBounds();
    const glm::vec3 extent = bounds.extent();
    CHECK(extent.y == Approx(3.0f));
    const double rooms = std::round((extent.x - 0.2) / 6.0) * std::round((extent.z - 0.2) / 6.0);
    CHECK(rooms >= 10.0);

    REQUIRE(scene.lights.size() >= 6);
    REQUIRE(scene.lights.size() <= 8);
    for (std::size_t i = 0; i < scene.lights.size(); ++i) {
        const Light& lamp = scene.lights[i];
        INFO(lamp.name);
        CHECK(lamp.name == "lamp" + std::to_string(i));
        CHECK(lamp.type == LightType::Point);
        CHECK(lamp.intensity >= 20.0f);
        CHECK(lamp.intensity <= 40.0f);
        CHECK(lamp.position.y > 2.0f);
        CHECK(lamp.position.y < bounds.upper.y);
        CHECK(lamp.position.x > bounds.lower.x);
        CHECK(lamp.position.x < bounds.upper.x);
        CHECK(lamp.position.z > bounds.lower.z);
        CHECK(lamp.position.z < bounds.upper.z);
    }

    int glossy = 0;
    for (const Material& m : scene.materials) glossy += (m.specular > 0.0f && m.roughness < 0.5f) ? 1 : 0;
    CHECK(glossy >= 1);

    // Same scene on every call (seeded layout).
    const Scene again = makeBuiltinScene("maze");
    REQUIRE(again.meshes.size() == scene.meshes.size());
    REQUIRE(again.instances.size() == scene.instances.size());
    bool same = true;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
        same = same && again.meshes[m].indices == scene.meshes[m].indices &&
               again.meshes[m].vertices.size() == scene.meshes[m].vertices.size();
        for (std::size_t v = 0; same && v < scene.meshes[m].vertices.size(); ++v)
            same = again.meshes[m].vertices[v].position == scene.meshes[m].vertices[v].position;
    }
    for (std::size_t i = 0; i < scene.instances.size(); ++i)
        same = same && again.instances[i].worldFromObject == scene.instances[i].worldFromObject;
    CHECK(same);
}

TEST_CASE("maze: heavily occluded, cameras look through doorways")
{
    const Scene scene = makeBuiltinScene("maze");
    const std::vector<Triangle> triangles = worldTriangles(scene);
    const AABB bounds = scene.worldBounds();

    // Lamps hang above the door height, so no lamp sees another.
    int visibleLampPairs = 0;
    for (std::size_t i = 0; i < scene.lights.size(); ++i)
        for (std::size_t j = i + 1; j < scene.lights.size(); ++j)
            visibleLampPairs += segmentBlocked(triangles, scene.lights[i].position, scene.lights[j].position) ? 0 : 1;
    CHECK(visibleLampPairs == 0);

    // Room centres at eye height: at most one pair in ten sees each other.
    std::vector<glm::vec3> centres;
    for (float x = bounds.lower.x + 0.1f + 3.0f; x < bounds.upper.x; x += 6.0f)
        for (float z = bounds.lower.z + 0.1f + 3.0f; z < bounds.upper.z; z += 6.0f) centres.emplace_back(x, 1.5f, z);
    REQUIRE(centres.size() >= 10);
    int pairs = 0, visiblePairs = 0;
    for (std::size_t i = 0; i < centres.size(); ++i)
        for (std::size_t j = i + 1; j < centres.size(); ++j) {
            ++pairs;
            visiblePairs += segmentBlocked(triangles, centres[i], centres[j]) ? 0 : 1;
        }
    INFO(visiblePairs << " of " << pairs << " room pairs see each other");
    CHECK(visiblePairs * 10 <= pairs);

    // "default" stands in a lit room; each camera's view ray passes a doorway into the next room
    // (the target is more than one room length away, so it lies beyond a wall).
    REQUIRE(scene.cameras.size() >= 2);
    const Camera& camera = scene.cameras[0];
    bool seesLamp = false;
    for (const Light& lamp : scene.lights)
        seesLamp = seesLamp || (glm::distance(lamp.position, camera.position) < 5.0f &&
                                !segmentBlocked(triangles, camera.position, lamp.position));
    CHECK(seesLamp);
    for (const Camera& c : scene.cameras) {
        INFO(c.name);
        CHECK(glm::distance(c.position, c.target) > 6.0f);
        CHECK_FALSE(segmentBlocked(triangles, c.position, c.target));
        CHECK(c.position.y > 1.0f);
        CHECK(c.position.y < 2.0f);
    }
    const Camera* unlit = scene.findCamera("unlit");
    REQUIRE(unlit != nullptr);
    // No lamp in the unlit camera's room (cells are 6 m, inside the 0.1 m outer wall halves).
    auto roomOf = [&](const glm::vec3& p) {
        return glm::floor((glm::vec2(p.x, p.z) - glm::vec2(bounds.lower.x, bounds.lower.z) - 0.1f) / 6.0f);
    };
    for (const Light& lamp : scene.lights) CHECK(roomOf(lamp.position) != roomOf(unlit->position));
}

TEST_CASE("street: sun, size, cameras, materials")
{
    const Scene scene = makeBuiltinScene("street");
    CHECK(scene.triangleCount() >= 10000);
    CHECK(scene.triangleCount() <= 200000);

    const Light* sun = scene.findLight("sun");
    REQUIRE(sun != nullptr);
    CHECK(scene.lights.size() == 1);
    CHECK(sun->type == LightType::Directional);
    const glm::vec3 irradiance = sun->radiantIntensity();
    for (int c = 0; c < 3; ++c) {
        CHECK(irradiance[c] >= 3.0f);
        CHECK(irradiance[c] <= 5.0f);
    }
    CHECK(irradiance.r > irradiance.b); // warm
    const glm::vec3 direction = glm::normalize(sun->direction);
    CHECK(std::asin(-direction.y) == Approx(40.0 * kPi / 180.0).margin(1e-3));
    CHECK(std::abs(direction.x) > std::abs(direction.z)); // across the street (which runs along z)

    const AABB bounds = scene.worldBounds();
    CHECK(bounds.upper.y >= 30.0f);
    CHECK(bounds.upper.y <= 40.0f);
    const Camera& eye = scene.cameras[0];
    CHECK(eye.position.y == Approx(1.7f));
    const glm::vec3 forward = glm::normalize(eye.target - eye.position);
    CHECK(std::abs(forward.z) > 2.0f * std::abs(forward.x)); // down the street
    const Camera* aerial = scene.findCamera("aerial");
    REQUIRE(aerial != nullptr);
    CHECK(aerial->position.y > bounds.upper.y);

    CHECK(glm::vec3(materialNamed(scene, "asphalt").baseColor) == glm::vec3(0.1f));
    int glossy = 0;
    for (const Material& m : scene.materials) {
        INFO(m.name);
        if (m.specular > 0.0f) {
            ++glossy;
            CHECK(m.roughness == Approx(0.25f));
        } else {
            CHECK(m.roughness == 1.0f);
        }
        CHECK(m.metallic == 0.0f);
        CHECK_FALSE(m.isEmissive());
    }
    CHECK(glossy >= 1);
}

TEST_CASE("street: the sun lights the -x side's facades and leaves the +x side in shadow")
{
    const Scene scene = makeBuiltinScene("street");
    const std::vector<Triangle> triangles = worldTriangles(scene);
    const glm::vec3 towardsSun = -glm::normalize(scene.findLight("sun")->direction);
    auto shadowedFraction = [&](float x, float y) {
        int samples = 0, shadowed = 0;
        for (float z = -70.0f; z <= 70.0f; z += 5.0f) {
            const glm::vec3 p(x, y, z);
            ++samples;
            shadowed += segmentBlocked(triangles, p, p + 300.0f * towardsSun) ? 1 : 0;
        }
        return static_cast<double>(shadowed) / samples;
    };
    // 1 m in front of the facades (x = -9 and 9) at 15 m, and the middle of the road.
    const double minusX = shadowedFraction(-8.0f, 15.0f), plusX = shadowedFraction(8.0f, 15.0f);
    const double road = shadowedFraction(0.0f, 0.01f);
    INFO("shadowed: -x facades " << minusX << ", +x facades " << plusX << ", road " << road);
    CHECK(minusX < 0.5);
    CHECK(plusX > 0.8);
    CHECK(road > 0.5);
    // The roofs are in the sun.
    const glm::vec3 above(0.0f, 45.0f, 0.0f);
    CHECK_FALSE(segmentBlocked(triangles, above, above + 300.0f * towardsSun));
}
