// The direct-emitter list: punctual lights map one to one; emissive triangles become cosine samples
// whose flux and irradiance match the area light.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>

#include "core/scene/builtin_scenes.h"
#include "core/scene/direct_lights.h"
#include "core/util/error.h"
#include "core/trace/ray_scene.h"
#include "core/scene/surface.h"

using namespace vplgi;

TEST_CASE("punctual lights become emitters with their intensity and profile", "[lights]")
{
    Scene scene = makeBuiltinScene("furnace");
    Light spot;
    spot.name = "spot";
    spot.type = LightType::Spot;
    spot.position = {0, 0.5f, 0};
    spot.direction = {0, -1, 0};
    spot.color = {1, 0.5f, 0.25f};
    spot.intensity = 8.0f;
    spot.innerConeAngle = 0.2f;
    spot.outerConeAngle = 0.4f;
    scene.lights.push_back(spot);
    DirectLightSet set = buildDirectLights(scene, DirectLightParams{});
    REQUIRE(set.points.size() == 2);
    CHECK(set.points[0].intensity.r == Approx(3.14159265f)); // furnace centre light
    CHECK(shared::emitterProfile(set.points[0], glm::vec3(0, 0, 1)) == 1.0f);
    const shared::PointEmitter& e = set.points[1];
    CHECK(e.intensity.g == Approx(4.0f));
    CHECK(shared::emitterProfile(e, glm::vec3(0, -1, 0)) == Approx(1.0f));          // inside the inner cone
    CHECK(shared::emitterProfile(e, glm::normalize(glm::vec3(1, -1, 0))) == 0.0f);   // 45 deg: outside
    float c = std::cos(0.3f);
    float t = (c - std::cos(0.4f)) / (std::cos(0.2f) - std::cos(0.4f));
    glm::vec3 mid(std::sin(0.3f), -std::cos(0.3f), 0.0f);
    CHECK(shared::emitterProfile(e, mid) == Approx(t * t).epsilon(1e-4));
}

TEST_CASE("cornell light samples carry the quad's flux and its irradiance", "[lights]")
{
    Scene scene = makeBuiltinScene("cornell");
    DirectLightParams params;
    params.emitterSamples = 64;
    DirectLightSet set = buildDirectLights(scene, params);
    REQUIRE(set.points.size() == 64);

    // The emissive triangles, brute force.
    double area = 0.0;
    glm::vec3 radiance(0.0f);
    std::vector<std::array<glm::vec3, 3>> triangles;
    for (const Instance& inst : scene.instances) {
        const Mesh& mesh = scene.meshes[inst.mesh];
        if (!scene.materials[mesh.material].isEmissive()) continue;
        radiance = scene.materials[mesh.material].emission;
        for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
            std::array<glm::vec3, 3> tri;
            for (int k = 0; k < 3; ++k)
                tri[k] = glm::vec3(inst.worldFromObject * glm::vec4(mesh.vertices[mesh.indices[t + k]].position, 1.0f));
            area += 0.5 * glm::length(glm::cross(tri[1] - tri[0], tri[2] - tri[0]));
            triangles.push_back(tri);
        }
    }
    REQUIRE(area > 0.0);
    // Flux: a cosine emitter of peak intensity I emits pi I; the quad emits pi Le A.
    double flux = 0.0;
    for (const auto& e : set.points) flux += 3.14159265358979 * e.intensity.r;
    CHECK(flux == Approx(3.14159265358979 * radiance.r * area).epsilon(1e-4));

    // Irradiance at floor points: samples against a dense midpoint quadrature of the triangles.
    for (glm::vec3 x : {glm::vec3(-0.278f, 0.0f, -0.28f), glm::vec3(-0.1f, 0.0f, -0.1f), glm::vec3(-0.45f, 0.2f, -0.45f)}) {
        const glm::vec3 n(0, 1, 0);
        double exact = 0.0;
        const int m = 200;
        for (const auto& tri : triangles) {
            glm::vec3 normal = glm::normalize(glm::cross(tri[1] - tri[0], tri[2] - tri[0]));
            double triArea = 0.5 * glm::length(glm::cross(tri[1] - tri[0], tri[2] - tri[0]));
            for (int i = 0; i < m; ++i)
                for (int j = 0; j < m - i; ++j) {
                    // Midpoints of a regular subdivision (upward sub-triangles' centroids, weighted).
                    float a = (i + 1.0f / 3.0f) / m, b = (j + 1.0f / 3.0f) / m;
                    glm::vec3 y = tri[0] + a * (tri[1] - tri[0]) + b * (tri[2] - tri[0]);
                    glm::vec3 d = y - x;
                    float r2 = glm::dot(d, d);
                    glm::vec3 w = d / std::sqrt(r2);
                    double g = std::max(0.0f, glm::dot(n, w)) * std::max(0.0f, glm::dot(normal, -w)) / r2;
                    exact += radiance.r * g * triArea / (m * (m + 1) / 2.0);
                }
        }
        double sampled = 0.0;
        for (const auto& e : set.points) {
            glm::vec3 d = glm::vec3(e.positionProfile) - x;
            float r2 = glm::dot(d, d);
            glm::vec3 w = d / std::sqrt(r2);
            sampled += e.intensity.r * shared::emitterProfile(e, -w) * std::max(0.0f, glm::dot(n, w)) / r2;
        }
        CHECK(sampled == Approx(exact).epsilon(0.01));
    }
}

TEST_CASE("emitter sample count must be positive", "[lights]")
{
    Scene scene = makeBuiltinScene("cornell");
    DirectLightParams params;
    params.emitterSamples = 0;
    CHECK_THROWS_AS(buildDirectLights(scene, params), Error);
}
