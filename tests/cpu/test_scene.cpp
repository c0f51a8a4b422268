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

TEST_CASE("surface area sums every instance's triangles in world space", "[scene]")
{
    // Closed form: the right triangle of legs 1 has area 1/2; an instance scaled by 2 and 3 in x and
    // y, 3; the translation changes nothing.
    Scene scene = oneTriangleScene();
    CHECK(instanceSurfaceArea(scene, scene.instances[0]) == Approx(0.5).epsilon(1e-12));
    scene.instances.push_back(Instance{0, glm::scale(glm::mat4(1.0f), glm::vec3(2, 3, 5))});
    CHECK(instanceSurfaceArea(scene, scene.instances[1]) == Approx(3.0).epsilon(1e-12));
    CHECK(sceneSurfaceArea(scene) == Approx(3.5).epsilon(1e-12));
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

TEST_CASE("generated normals weight each triangle by its area", "[scene]")
{
    // Two triangles meet at vertex 0: one in the xy plane of area 2 (facing +z), one in the xz
    // plane of area 0.5 (facing +y). The shared normal is (0, 0.5, 2) normalised.
    Mesh mesh;
    mesh.vertices.resize(5);
    mesh.vertices[0].position = {0, 0, 0};
    mesh.vertices[1].position = {2, 0, 0};
    mesh.vertices[2].position = {0, 2, 0};
    mesh.vertices[3].position = {0, 0, 1};
    mesh.vertices[4].position = {1, 0, 0};
    mesh.indices = {0, 1, 2, 0, 3, 4};
    generateNormals(mesh);
    CHECK(glm::length(mesh.vertices[0].normal - glm::normalize(glm::vec3(0, 0.5f, 2))) < 1e-6f);
    CHECK(glm::length(mesh.vertices[1].normal - glm::vec3(0, 0, 1)) < 1e-6f);
    CHECK(glm::length(mesh.vertices[3].normal - glm::vec3(0, 1, 0)) < 1e-6f);
}

TEST_CASE("generated tangents follow the normal texture's UV set and KHR_texture_transform", "[scene]")
{
    // The triangle (0,0,0) (1,0,0) (0,1,0) facing +z; TEXCOORD_0 u along +x, v along +y; TEXCOORD_1
    // u along +y, v along +x. Tangent: where the normal texture's u grows; w: +1 when n x t is
    // where its v grows.
    auto tangentFor = [](const TextureRef& normalTexture) {
        Scene scene = oneTriangleScene();
        Mesh& mesh = scene.meshes[0];
        const glm::vec2 uv0[3] = {{0, 0}, {1, 0}, {0, 1}};
        for (int i = 0; i < 3; ++i) {
            mesh.vertices[static_cast<std::size_t>(i)].texcoord = uv0[i];
            mesh.vertices[static_cast<std::size_t>(i)].texcoord1 = {uv0[i].y, uv0[i].x};
        }
        generateNormals(mesh);
        generateTangents(mesh, normalTexture);
        return mesh.vertices[0].tangent;
    };
    TextureRef plain;
    CHECK(glm::length(tangentFor(plain) - glm::vec4(1, 0, 0, 1)) < 1e-6f);
    TextureRef second;
    second.texCoord = 1; // u along +y, v along +x: n x t = -x, against v: mirrored
    CHECK(glm::length(tangentFor(second) - glm::vec4(0, 1, 0, -1)) < 1e-6f);
    TextureRef rotated;
    rotated.rotation = 1.5707963f; // u' = v (+y), v' = -u (-x): n x t = -x, with v'
    CHECK(glm::length(tangentFor(rotated) - glm::vec4(0, 1, 0, 1)) < 1e-5f);
    TextureRef flipped;
    flipped.scale = {-1.0f, 1.0f}; // u' = -u: t = -x, n x t = -y against v' = v (+y): mirrored
    CHECK(glm::length(tangentFor(flipped) - glm::vec4(-1, 0, 0, -1)) < 1e-6f);
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
