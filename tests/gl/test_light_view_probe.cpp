// The shared light-view maths (glsl/shared/light_view.h) evaluated in GLSL by a compute probe
// (tests/gl/glsl/light_view_probe.comp) against the same functions compiled as C++.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "gl/api/objects.h"
#include "gl_test_context.h"
#include "glsl/shared/light_view.h"

using namespace vplgi;
using namespace vplgi::shared;

namespace {

constexpr int kResultsPerCase = 8; // as in light_view_probe.comp

struct Case {
    glm::vec4 positionNear, normalFar, direction, uvTexel;
};

// What the probe writes for one case, computed by the C++ side of the shared header.
std::vector<glm::vec4> expectedResults(const Case& c)
{
    const glm::vec3 p(c.positionNear), n(c.normalFar), w(c.direction);
    const float zNear = c.positionNear.w, zFar = c.normalFar.w;
    const glm::vec3 q = p + c.direction.w * w;
    const int cubeFace = lightViewCubeFace(w);
    const glm::mat3 cube = lightViewHemisphereBasis(n);
    const glm::vec3 dc = glm::transpose(cube) * w;
    const int hemisphereFace = lightViewHemisphereFace(dc);
    const glm::mat3 frame = lightViewBasis(n);
    const glm::vec3 local = glm::transpose(frame) * (q - p);
    const int resolution = static_cast<int>(c.uvTexel.w);
    const int texel = static_cast<int>(c.uvTexel.z);
    const glm::vec2 uv(c.uvTexel);
    return {
        glm::vec4(static_cast<float>(cubeFace), static_cast<float>(hemisphereFace),
                  lightViewHemisphereFaceUV(dc, hemisphereFace)),
        lightViewCubeFaceClipFromWorld(p, cubeFace, zNear, zFar) * glm::vec4(q, 1.0f),
        lightViewHemisphereFaceClipFromWorld(p, cube, hemisphereFace, zNear, zFar) * glm::vec4(q, 1.0f),
        glm::vec4(paraboloidMapFromPoint(local, zNear, zFar),
                  paraboloidTexelSolidAngle(glm::ivec2(texel % resolution, texel / resolution), resolution)),
        glm::vec4(paraboloidDirectionFromMap(uv), paraboloidSolidAngleDensity(uv)),
        lightViewDirectionalFit(-w, p - glm::vec3(zFar), p + glm::vec3(zNear, zFar, 2.0f * zNear)) * glm::vec4(q, 1.0f),
        glm::vec4(cube * glm::vec3(1.0f, 2.0f, 3.0f), 0.0f),
        glm::vec4(frame * glm::vec3(1.0f, 2.0f, 3.0f), 0.0f),
    };
}

} // namespace

TEST_CASE("the light-view maths give the same values in GLSL and C++", "[gl][lightview]")
{
    test::ensureGLContext();
    std::mt19937 rng(19);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto sphere = [&] {
        const float z = 2.0f * u(rng) - 1.0f, phi = 6.2831853f * u(rng);
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
    };
    std::vector<Case> cases;
    for (int i = 0; i < 1024; ++i) {
        // Axis normals (both branches of lightViewBasis) every few cases, random ones otherwise.
        glm::vec3 n = i % 8 == 0 ? glm::vec3(0, 0, 1) : i % 8 == 1 ? glm::vec3(0, 0, -1) : sphere();
        glm::vec3 w = sphere();
        if (glm::dot(w, n) < 0.0f) w = -w;
        const int resolution = i % 3 == 0 ? 16 : (i % 3 == 1 ? 64 : 128);
        glm::vec2 uv;
        do
            uv = glm::vec2(u(rng), u(rng));
        while (glm::length(2.0f * uv - 1.0f) > 1.0f);
        Case c;
        c.positionNear =
            glm::vec4(10.0f * u(rng) - 5.0f, 10.0f * u(rng) - 5.0f, 10.0f * u(rng) - 5.0f, 0.01f + 0.09f * u(rng));
        c.normalFar = glm::vec4(n, 10.0f + 40.0f * u(rng));
        c.direction = glm::vec4(w, 0.1f + 4.9f * u(rng));
        c.uvTexel = glm::vec4(uv, std::floor(u(rng) * resolution * resolution), resolution);
        cases.push_back(c);
    }
    const std::vector<glm::vec4> results =
        test::runComputeProbe("light view probe", "light_view_probe.comp", cases.data(), cases.size() * sizeof(Case),
                              static_cast<int>(cases.size()), kResultsPerCase);

    // Per output row, the largest |GPU - CPU| relative to the row's magnitude (1 + max |component|).
    double worst[kResultsPerCase] = {};
    int faceMismatches = 0, solidAngles = 0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const std::vector<glm::vec4> expected = expectedResults(cases[i]);
        const glm::vec4* got = &results[i * kResultsPerCase];
        // Face choices are exact integers; a mismatch would only be possible at a tie to rounding.
        if (got[0].x != expected[0].x || got[0].y != expected[0].y) {
            ++faceMismatches;
            continue;
        }
        if (expected[3].w > 0.0f) ++solidAngles;
        for (int row = 0; row < kResultsPerCase; ++row) {
            double scale = 1.0;
            for (int k = 0; k < 4; ++k)
                scale = std::max(scale, 1.0 + std::abs(expected[row][k]));
            for (int k = 0; k < 4; ++k)
                worst[row] =
                    std::max(worst[row], std::abs(static_cast<double>(got[row][k]) - expected[row][k]) / scale);
        }
    }
    std::printf("light view GLSL vs C++ (relative, per output): face uv %.2g, cube clip %.2g, hemisphere clip %.2g, "
                "paraboloid map+texel %.2g, inverse+density %.2g, directional clip %.2g, bases %.2g %.2g\n",
                worst[0], worst[1], worst[2], worst[3], worst[4], worst[5], worst[6], worst[7]);
    CHECK(faceMismatches == 0);
    CHECK(solidAngles > 100); // texels in the disk were exercised, not only empty ones
    // Measured on llvmpipe: at most 7.9e-7 (hemisphere clip coordinates; float rounding in another
    // order, and llvmpipe's atan, sqrt and division differ from libm by an ulp or so); 2.5e-6 is
    // about 3x that and far below what a formula slip would give.
    for (int row = 0; row < kResultsPerCase; ++row) {
        INFO("output row " << row);
        CHECK(worst[row] < 2.5e-6);
    }
}
