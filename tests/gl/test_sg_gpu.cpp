// glsl/shared/sg.h evaluated in GLSL by a compute probe (tests/gl/glsl/sg_probe.comp) against the
// same functions compiled as C++, for random inputs and the degenerate ones. This proves only that
// the GLSL and C++ builds of the header agree (llvmpipe's exp, log2, sqrt and division against
// libm's); that the maths is right is tests/cpu/test_sg.cpp's job.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "gl/api/objects.h"
#include "gl_test_context.h"
#include "glsl/shared/sg.h"

using namespace vplgi;
using namespace vplgi::shared;

namespace {

constexpr int kResultsPerCase = 7; // as in sg_probe.comp

struct Case {
    glm::vec4 positionRoughness, normal, view, diffuse, f0;
    VSGLight light;
    glm::vec4 toLightClamp, parameters;
};
static_assert(sizeof(Case) == 14 * 16, "Case must match std430 in sg_probe.comp");

VSGLShadingPoint shadingPoint(const Case& c)
{
    VSGLShadingPoint s;
    s.position = glm::vec3(c.positionRoughness);
    s.normal = glm::vec3(c.normal);
    s.view = glm::vec3(c.view);
    s.diffuse = glm::vec3(c.diffuse);
    s.f0 = glm::vec3(c.f0);
    s.roughness = c.positionRoughness.w;
    return s;
}

// What the probe writes for one case, computed by the C++ side of the shared header.
std::vector<glm::vec4> expectedResults(const Case& c)
{
    const VSGLShadingPoint s = shadingPoint(c);
    float cancelledSG = -1.0f, cancelledReduced = -1.0f;
    const glm::vec3 sg = vsglRadiance(s, c.light, glm::vec3(c.toLightClamp), 0.0f, cancelledSG);
    const glm::vec3 reduced = vsglRadiance(s, c.light, glm::vec3(c.toLightClamp), c.parameters.x, cancelledReduced);
    const SpecularLobe lobe = ggxReflectionLobe(s.normal, s.view, s.roughness);
    const glm::vec3 encoded = toksvigEncode(lobe.axis, lobe.sharpness);
    glm::vec3 axis;
    float sharpness;
    toksvigDecode(0.5f * encoded + glm::vec3(0.1f, 0.0f, 0.0f), axis, sharpness);
    return {
        glm::vec4(sg, cancelledSG),
        glm::vec4(reduced, cancelledReduced),
        glm::vec4(vplRadiance(s, c.light, glm::vec3(c.toLightClamp), c.toLightClamp.w),
                  vsglMipLevel(c.parameters.z, c.parameters.y, c.parameters.w, 9)),
        glm::vec4(lobe.axis, lobe.sharpness),
        glm::vec4(encoded, lobe.integral),
        glm::vec4(axis, sharpness),
        glm::vec4(evaluateBRDFCoefficients(glm::vec3(c.light.diffuse), glm::vec3(c.light.specular), c.light.diffuse.w,
                                           glm::vec3(c.light.normalValid), -s.view, glm::vec3(c.toLightClamp)),
                  0.0f),
    };
}

std::vector<Case> makeCases()
{
    std::mt19937 rng(96u);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto sphere = [&] {
        const float z = 2.0f * u(rng) - 1.0f, phi = 6.2831853f * u(rng);
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
    };
    auto above = [&](const glm::vec3& n) {
        glm::vec3 w = sphere();
        return glm::dot(w, n) < 0.0f ? -w : w;
    };
    std::vector<Case> cases;
    for (int i = 0; i < 2048; ++i) {
        Case c;
        const glm::vec3 n = sphere();
        const glm::vec3 position(4.0f * u(rng) - 2.0f, 4.0f * u(rng) - 2.0f, 4.0f * u(rng) - 2.0f);
        c.positionRoughness = glm::vec4(position, u(rng));
        c.normal = glm::vec4(n, 0.0f);
        c.view = glm::vec4(above(n), 0.0f);
        c.diffuse = glm::vec4(u(rng), u(rng), u(rng), 0.0f);
        c.f0 = i % 4 == 0 ? glm::vec4(0.0f) : glm::vec4(u(rng), u(rng), u(rng), 0.0f);
        // The light above the receiver, facing it more often than not, at 1 cm .. 3 m, r/d 1e-4 .. 3.
        const glm::vec3 towards = above(n);
        const float d = 0.01f + 3.0f * u(rng);
        const float ratio = std::pow(10.0f, -4.0f + 4.5f * u(rng));
        const glm::vec3 lightNormal = glm::normalize(-towards + 0.8f * sphere());
        const glm::vec3 toPrimary = above(lightNormal);
        const float lightRoughness = u(rng);
        const SpecularLobe lobe = ggxReflectionLobe(lightNormal, toPrimary, lightRoughness);
        c.light.positionRadius2 = glm::vec4(position + d * towards, ratio * ratio * d * d);
        c.light.normalValid = glm::vec4(lightNormal, 1.0f);
        c.light.geometric = glm::vec4(lightNormal, 0.0f);
        c.light.flux = glm::vec4(2.0f * u(rng), 2.0f * u(rng), 2.0f * u(rng), 0.0f);
        c.light.diffuse = glm::vec4(u(rng), u(rng), u(rng), lightRoughness);
        c.light.specular = glm::vec4(i % 3 == 0 ? glm::vec3(0.0f) : glm::vec3(u(rng), u(rng), u(rng)), lobe.integral);
        c.light.lobe = glm::vec4(lobe.axis, lobe.sharpness);
        c.toLightClamp = glm::vec4(toPrimary, i % 2 == 0 ? 0.0f : 4.0f * u(rng));
        c.parameters = glm::vec4(i % 5 == 0 ? 0.0f : std::pow(10.0f, -4.0f + 4.0f * u(rng)),
                                 std::pow(10.0f, -7.0f + 6.0f * u(rng)), 1024.0f, 4.0f);
        // Degenerate inputs every so often (test_sg.cpp has their values): r = 0, d = 0, empty slot,
        // zero normals, zero flux.
        switch (i % 37) {
        case 1:
            c.light.positionRadius2.w = 0.0f;
            break;
        case 2:
            c.light.positionRadius2 = glm::vec4(position, 0.01f);
            break;
        case 3:
            c.light.positionRadius2 = glm::vec4(position, 0.0f);
            break;
        case 4:
            c.light.normalValid.w = 0.0f;
            break;
        case 5:
            c.normal = glm::vec4(0.0f);
            break;
        case 6:
            c.light.normalValid = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
            c.light.geometric = glm::vec4(0.0f, 0.0f, 0.0f, 0.0f);
            break;
        case 7:
            c.light.flux = glm::vec4(0.0f);
            break;
        default:
            break;
        }
        cases.push_back(c);
    }
    return cases;
}

} // namespace

TEST_CASE("the SG / VSGL maths give the same values in GLSL and C++", "[gl][sg]")
{
    test::ensureGLContext();
    const std::vector<Case> cases = makeCases();
    const std::vector<glm::vec4> results = test::runComputeProbe(
        "sg probe", "sg_probe.comp", cases.data(), cases.size() * sizeof(Case), static_cast<int>(cases.size()), kResultsPerCase);

    // Per output row, the largest |GPU - CPU| relative to the row's largest |component| (rgb rows:
    // the brightest channel; other rows: 1 + max |component|, sharpnesses relative to themselves).
    double worst[kResultsPerCase] = {};
    int cancelledMismatches = 0, nonFinite = 0, lit = 0, cancelled = 0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const std::vector<glm::vec4> expected = expectedResults(cases[i]);
        const glm::vec4* got = &results[i * kResultsPerCase];
        for (int row = 0; row < kResultsPerCase; ++row)
            for (int k = 0; k < 4; ++k)
                if (!std::isfinite(got[row][k])) ++nonFinite;
        if (got[0].w != expected[0].w || got[1].w != expected[1].w) ++cancelledMismatches;
        if (expected[0].g > 0.0f) ++lit;
        if (expected[1].w == 1.0f) ++cancelled;
        for (int row = 0; row < kResultsPerCase; ++row) {
            const bool colour = row <= 2 || row == 6;
            const int components = colour ? 3 : 4;
            double scale = colour ? 0.0 : 1.0;
            for (int k = 0; k < components; ++k)
                scale = std::max(scale, (colour ? 0.0 : 1.0) + std::abs(expected[row][k]));
            if (!(scale > 0.0)) scale = 1.0;
            for (int k = 0; k < components; ++k)
                worst[row] = std::max(worst[row], std::abs(double(got[row][k]) - expected[row][k]) / scale);
        }
        // Mip level (row 2, w) is not colour: absolute.
        worst[2] = std::max(worst[2], std::abs(double(got[2].w) - expected[2].w));
    }
    std::printf("sg GLSL vs C++ (relative, per output): vsgl %.2g, vsgl reduced %.2g, vpl+mip %.2g, lobe %.2g, "
                "toksvig+integral %.2g, decoded %.2g, brdf %.2g (%d of %zu lit, %d cancelled)\n",
                worst[0], worst[1], worst[2], worst[3], worst[4], worst[5], worst[6], lit, cases.size(), cancelled);
    CHECK(nonFinite == 0);
    CHECK(cancelledMismatches == 0);
    CHECK(lit > 500);       // the lights reach the receivers ...
    CHECK(cancelled > 100); // ... and both branches of section 3.3 ran
    CHECK(lit < 2000);      // and the degenerate ones gave nothing
    // Measured on llvmpipe: 2.1e-5, 5.8e-5, 5.9e-5, 3.3e-6, 4.8e-5, 2.8e-7, 2.3e-5 (rows 0-6). The
    // largest come from narrow GGX lobes (roughness near 0: D's float error grows like 1e-8/alpha^2,
    // see test_brdf.cpp) and sharp SGs, where an ulp of difference in a cosine (llvmpipe's sqrt,
    // exp and division against libm's) is multiplied by the sharpness. Tolerances are 2.5-3x those;
    // a formula slip shows up as O(1).
    // On an H200 (test::twinTolerance): 2.5e-5, 9e-5, 9e-5, 1.5e-5, 2.6e-5, 5.7e-7, 7.8e-5.
    const double software[kResultsPerCase] = {6e-5, 1.5e-4, 1.5e-4, 1e-5, 1.5e-4, 1e-6, 6e-5};
    const double hardware[kResultsPerCase] = {6e-5, 2.5e-4, 2.5e-4, 4e-5, 1.5e-4, 1.5e-6, 2e-4};
    double tolerances[kResultsPerCase];
    for (int row = 0; row < kResultsPerCase; ++row)
        tolerances[row] = test::twinTolerance(software[row], hardware[row]);
    for (int row = 0; row < kResultsPerCase; ++row) {
        INFO("output row " << row);
        CHECK(worst[row] < tolerances[row]);
    }
}
