// Scene model: transforms, bounds, generated normals/tangents, validation, animation.
#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include "core/util/error.h"
#include "core/scene/scene.h"

using namespace vplgi;

namespace {

Scene oneTriangleScene()
{
    Scene scene;
    scene.name = "triangle";
    scene.materials.push_back(Material{});
    Mesh mesh;
    mesh.vertices.resize(3);
    mesh.vertices[0].position = {0, 0, 0};
    mesh.vertices[1].position = {1, 0, 0};
    mesh.vertices[2].position = {0, 1, 0};
    mesh.indices = {0, 1, 2};
    scene.meshes.push_back(mesh);
    scene.instances.push_back(Instance{0, glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0))});
    return scene;
}

} // namespace

TEST_CASE("world bounds follow instance transforms", "[scene]")
{
    Scene scene = oneTriangleScene();
    AABB b = scene.worldBounds();
    CHECK(b.lower.x == Approx(10.0f));
    CHECK(b.upper.x == Approx(11.0f));
    CHECK(b.upper.y == Approx(1.0f));
    CHECK(scene.triangleCount() == 1);
}

TEST_CASE("generated normals follow the winding and are unit length", "[scene]")
{
    Scene scene = oneTriangleScene();
    Mesh& mesh = scene.meshes[0];
    for (Vertex& v : mesh.vertices) v.normal = glm::vec3(0.0f);
    generateNormals(mesh);
    for (const Vertex& v : mesh.vertices) {
        CHECK(v.normal.z == Approx(1.0f)); // counter-clockwise in the xy plane faces +z
        CHECK(glm::length(v.normal) == Approx(1.0f));
    }
}

TEST_CASE("generated tangents point along +u and are orthogonal to the normal", "[scene]")
{
    Scene scene = oneTriangleScene();
    Mesh& mesh = scene.meshes[0];
    mesh.vertices[0].texcoord = {0, 0};
    mesh.vertices[1].texcoord = {1, 0};
    mesh.vertices[2].texcoord = {0, 1};
    generateNormals(mesh);
    generateTangents(mesh);
    for (const Vertex& v : mesh.vertices) {
        CHECK(v.tangent.x == Approx(1.0f));
        CHECK(std::abs(glm::dot(glm::vec3(v.tangent), v.normal)) < 1e-6f);
        CHECK(v.tangent.w == Approx(1.0f));
    }
    CHECK(mesh.hasTangents);
}

TEST_CASE("validation names the broken part", "[scene]")
{
    Scene scene = oneTriangleScene();
    REQUIRE_NOTHROW(scene.validate());
    scene.meshes[0].indices = {0, 1, 7};
    CHECK_THROWS_WITH(scene.validate(), Catch::Contains("vertex index out of range"));
    scene = oneTriangleScene();
    Light light;
    light.name = "bad";
    light.intensity = -1.0f;
    scene.lights.push_back(light);
    CHECK_THROWS_WITH(scene.validate(), Catch::Contains("light 0 (bad): intensity must be >= 0"));
    scene = oneTriangleScene();
    scene.meshes[0].material = 3;
    CHECK_THROWS_AS(scene.validate(), Error);
}

TEST_CASE("animations interpolate keys linearly and clamp outside", "[scene]")
{
    Scene scene = oneTriangleScene();
    Camera camera;
    camera.name = "cam";
    scene.cameras.push_back(camera);
    Light light;
    light.name = "sun";
    light.type = LightType::Directional;
    scene.lights.push_back(light);
    Animation move;
    move.targetKind = Animation::Target::Camera;
    move.targetName = "cam";
    move.keys = {{0.0f, {0, 0, 0}, {0, 0, -1}}, {2.0f, {4, 0, 0}, {4, 0, -1}}};
    applyAnimation(scene, move, 0.5f);
    CHECK(scene.cameras[0].position.x == Approx(1.0f));
    applyAnimation(scene, move, 10.0f);
    CHECK(scene.cameras[0].position.x == Approx(4.0f));
    Animation aim;
    aim.targetKind = Animation::Target::Light;
    aim.targetName = "sun";
    aim.keys = {{0.0f, {0, 10, 0}, {0, 0, 0}}};
    applyAnimation(scene, aim, 0.0f);
    CHECK(scene.lights[0].direction.y == Approx(-1.0f));
}

TEST_CASE("camera matrices map the target to the image centre", "[scene]")
{
    Camera camera;
    camera.position = {1, 2, 3};
    camera.target = {4, 2, -1};
    glm::vec4 clip = camera.clipFromView(16.0f / 9.0f) * camera.viewFromWorld() * glm::vec4(camera.target, 1.0f);
    CHECK(clip.x / clip.w == Approx(0.0f).margin(1e-5));
    CHECK(clip.y / clip.w == Approx(0.0f).margin(1e-5));
    CHECK(clip.w > 0.0f);
}
