// Embree scene against analytic geometry.
#include <catch2/catch.hpp>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "core/scene/builtin_scenes.h"
#include "core/trace/ray_scene.h"
#include "core/scene/surface.h"

using namespace vplgi;

namespace {

// A unit quad in the z = 0 plane, [0,1]^2, facing +z, placed by `transform`.
Scene quadScene(const glm::mat4& transform)
{
    Scene scene;
    scene.name = "quad";
    Material m;
    m.baseColor = glm::vec4(0.5f, 0.25f, 1.0f, 1.0f);
    scene.materials.push_back(m);
    Mesh mesh;
    for (glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)}) {
        Vertex v;
        v.position = p;
        v.normal = {0, 0, 1};
        v.texcoord = glm::vec2(p);
        mesh.vertices.push_back(v);
    }
    mesh.indices = {0, 1, 2, 0, 2, 3};
    scene.meshes.push_back(mesh);
    scene.instances.push_back(Instance{0, transform});
    return scene;
}

} // namespace

TEST_CASE("rays hit a transformed quad at the analytic distance", "[embree]")
{
    Scene scene = quadScene(glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -2)));
    RayScene rays(scene);
    Ray ray;
    ray.origin = {0.25f, 0.75f, 3.0f};
    ray.direction = {0, 0, -1};
    Hit hit = rays.intersect(ray);
    REQUIRE(hit.valid());
    CHECK(hit.t == Approx(5.0f));
    SurfacePoint s = surfaceAt(scene, hit, -ray.direction);
    CHECK(s.position.x == Approx(0.25f));
    CHECK(s.position.y == Approx(0.75f));
    CHECK(s.position.z == Approx(-2.0f));
    CHECK(s.normal.z == Approx(1.0f));
    CHECK(s.texcoord.x == Approx(0.25f));
    CHECK(s.material.baseColor.g == Approx(0.25f));

    ray.origin = {1.5f, 0.5f, 3.0f}; // beside the quad
    CHECK_FALSE(rays.intersect(ray).valid());
    CHECK_FALSE(rays.occluded(ray));
    ray.origin = {0.5f, 0.5f, 3.0f};
    CHECK(rays.occluded(ray));
    ray.tMax = 4.9f; // stops short of the quad
    CHECK_FALSE(rays.occluded(ray));
    CHECK_FALSE(rays.visible({0.5f, 0.5f, -1.0f}, {0.5f, 0.5f, -3.0f}));
    CHECK(rays.visible({0.5f, 0.5f, -1.0f}, {0.5f, 0.5f, -1.9f}));
}

TEST_CASE("rays from the furnace centre hit the sphere at radius R", "[embree]")
{
    FurnaceParams params;
    params.radius = 2.0f;
    Scene scene = makeFurnace(params);
    RayScene rays(scene);
    // The tessellation lies inside the sphere by at most R (1 - cos(pi / segments)) over a flat facet.
    const float tolerance = params.radius * (1.0f - std::cos(3.14159265f / params.rings)) * 2.0f + 1e-5f;
    for (int i = 0; i < 50; ++i) {
        float theta = 0.1f + 2.9f * i / 50.0f, phi = 0.37f * i;
        Ray ray;
        ray.direction = {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
        Hit hit = rays.intersect(ray);
        REQUIRE(hit.valid());
        CHECK(hit.t == Approx(params.radius).margin(tolerance));
        SurfacePoint s = surfaceAt(scene, hit, -ray.direction);
        CHECK(glm::dot(s.normal, -ray.direction) > 0.999f); // inward normal
    }
}
