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

TEST_CASE("emissive samples merge into at most rsm.areaSources cosine sources that keep their power", "[lights]")
{
    Scene scene = makeBuiltinScene("cornell");
    DirectLightParams params;
    params.emitterSamples = 64;
    const DirectLightSet set = buildDirectLights(scene, params);
    glm::dvec3 total(0.0);
    for (const shared::PointEmitter& e : set.points) total += glm::dvec3(e.intensity);
    for (int groups : {1, 2, 4, 64, 100}) {
        const std::vector<shared::PointEmitter> merged = groupCosineEmitters(set, groups);
        REQUIRE(!merged.empty());
        CHECK(static_cast<int>(merged.size()) <= std::min(groups, 64));
        glm::dvec3 sum(0.0);
        for (const shared::PointEmitter& g : merged) {
            sum += glm::dvec3(g.intensity);
            CHECK(static_cast<int>(g.positionProfile.w + 0.5f) == shared::kProfileCosine);
            // The Cornell light is one flat quad facing down: every group's normal is its normal.
            CHECK(g.axisCosOuter.y == Approx(-1.0f).margin(1e-6));
        }
        // Power pi I is kept (float sums of 64 terms).
        CHECK(sum.x == Approx(total.x).epsilon(1e-5));
        CHECK(sum.z == Approx(total.z).epsilon(1e-5));
        // Deterministic.
        const std::vector<shared::PointEmitter> again = groupCosineEmitters(set, groups);
        REQUIRE(again.size() == merged.size());
        for (std::size_t i = 0; i < merged.size(); ++i)
            CHECK(glm::vec3(again[i].positionProfile) == glm::vec3(merged[i].positionProfile));
    }
    // One group sits at the power-weighted centroid of the samples.
    const std::vector<shared::PointEmitter> one = groupCosineEmitters(set, 1);
    glm::dvec3 centroid(0.0);
    double weight = 0.0;
    for (const shared::PointEmitter& e : set.points) {
        const double w = 0.2126 * e.intensity.r + 0.7152 * e.intensity.g + 0.0722 * e.intensity.b;
        centroid += w * glm::dvec3(e.positionProfile);
        weight += w;
    }
    CHECK(glm::distance(glm::vec3(one[0].positionProfile), glm::vec3(centroid / weight)) < 1e-5f);
    CHECK(groupCosineEmitters(set, 0).empty());
    Scene dark = makeBuiltinScene("furnace"); // a point light only
    CHECK(groupCosineEmitters(buildDirectLights(dark, params), 4).empty());
}
