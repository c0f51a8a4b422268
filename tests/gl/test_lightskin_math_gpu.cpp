// glsl/shared/lightskin.h evaluated in GLSL by a compute probe (tests/gl/glsl/lightskin_probe.comp)
// against the same functions compiled as C++, for random inputs and degenerate ones. This proves
// only that the GLSL and C++ builds of the header agree (llvmpipe's pow, inversesqrt,
// sqrt and division against libm's); that the maths is right is tests/cpu/test_lightskin_math.cpp's job.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <vector>

#include "gl_test_context.h"
#include "glsl/shared/lightskin.h"
#include "measured.h"

using namespace vplgi;
using namespace vplgi::shared;

namespace {

constexpr int kResultsPerCase = 9; // as in lightskin_probe.comp

struct Case {
    glm::vec4 valPositionArea, valNormalExpectation, valFluxExponent, receiverPositionDepth, receiverNormalFactor,
        viewClamp, diffuseCosAxis, glossyCosSurface, interpolation, occluderPositionArea, occluderNormalRadius,
        roughnessOverlap;
    glm::uvec4 indices;
};
static_assert(sizeof(Case) == 13 * 16, "Case must match std430 in lightskin_probe.comp");

// What the probe writes for one case, computed by the C++ side of the shared header (the same
// expressions as the probe, line by line).
std::vector<glm::vec4> expectedResults(const Case& c)
{
    const glm::vec3 valPosition(c.valPositionArea);
    const float valArea = c.valPositionArea.w;
    const glm::vec3 valNormal(c.valNormalExpectation);
    const float expectation = c.valNormalExpectation.w;
    const glm::vec3 flux(c.valFluxExponent);
    const float k = c.valFluxExponent.w;
    const glm::vec3 x(c.receiverPositionDepth), n(c.receiverNormalFactor), view(c.viewClamp);

    const glm::vec3 diffuse =
        valDiffuseRadiance(flux, valPosition, valNormal, valArea, x, n, glm::vec3(c.diffuseCosAxis), expectation);
    const glm::vec3 glossy = valGlossyRadiance(flux, valPosition, valNormal, valArea, x, n, view,
                                               glm::vec3(c.glossyCosSurface), k, expectation);
    const float perspective = lightskinValArea(c.receiverPositionDepth.w, c.receiverNormalFactor.w, false);
    std::vector<glm::vec4> r(kResultsPerCase);
    r[0] = glm::vec4(diffuse, perspective);
    r[1] = glm::vec4(glossy, lightskinValArea(c.receiverPositionDepth.w, c.receiverNormalFactor.w, true));

    const glm::vec3 toVal = valPosition - x;
    const float distance2 = glm::dot(toVal, toVal);
    const glm::vec3 w = toVal * glm::inversesqrt(std::max(distance2, 1e-30f));
    const float cosCache = glm::dot(n, w);
    const glm::vec3 brdf = glm::vec3(c.diffuseCosAxis) * kInvPi;
    const glm::vec3 proxyFlux = proxyFluxFromRadiance(diffuse, distance2, brdf, cosCache);
    r[2] = glm::vec4(proxyFlux, lightskinValAreaTilted(perspective, c.diffuseCosAxis.w, c.glossyCosSurface.w));
    const float formFactor = diskFormFactor(valArea, -glm::dot(valNormal, w), cosCache, distance2);
    r[3] = glm::vec4(pointLightRadiance(proxyFlux, distance2, brdf, cosCache), formFactor);

    const float cosMirror = glm::dot(view, mirrorDirection(w, n));
    const glm::vec4 i4 = c.interpolation;
    r[4] = glm::vec4(proxyWeightDiffuse(formFactor, kProxyWeightEpsilon),
                     proxyWeightGlossy(formFactor, cosMirror, k, kProxyWeightEpsilon),
                     interpolationWeight(i4.x, i4.y, i4.z, i4.w),
                     valImportance(flux.y, valPosition, valNormal, x, n, c.viewClamp.w));

    const unsigned index = c.indices.x;
    const int size = static_cast<int>(c.indices.w);
    const glm::ivec2 pixel = haltonViewPixel(index, size, size / 2 + 1);
    r[5] = glm::vec4(halton(index, 2u), halton(index, 3u), static_cast<float>(pixel.x), static_cast<float>(pixel.y));

    const glm::mat3 frame = occlusionFrame(n);
    const glm::vec3 sphere = projectSphereToUnitDisk(valPosition - x, c.occluderNormalRadius.w, frame);
    const float radius = proxySphereRadius(c.roughnessOverlap.w, toVal, toVal * toVal + glm::vec3(c.glossyCosSurface));
    r[6] = glm::vec4(sphere, radius);
    const glm::vec3 disk = projectDiskToUnitDisk(glm::vec3(c.occluderPositionArea) - x,
                                                 glm::vec3(c.occluderNormalRadius), c.occluderPositionArea.w, frame);
    r[7] = glm::vec4(disk, squareOverlap(sphere, disk));

    const bool candidate = isOccluderCandidate(static_cast<int>(c.indices.y), x, n, static_cast<int>(c.indices.z),
                                               glm::vec3(c.occluderPositionArea), distance2);
    r[8] = glm::vec4(candidate ? 1.0f : 0.0f, occlusionFromOverlap(c.roughnessOverlap.z, sphere.z),
                     phongExponentFromRoughness(c.roughnessOverlap.x),
                     valSelectionExpectation(c.roughnessOverlap.y, expectation));
    return r;
}

std::vector<Case> makeCases()
{
    std::mt19937 rng(1103u);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto sphere = [&] {
        const float z = 2.0f * u(rng) - 1.0f, phi = 6.2831853f * u(rng);
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
    };
    auto above = [&](const glm::vec3& n) {
        const glm::vec3 w = sphere();
        return glm::dot(w, n) < 0.0f ? -w : w;
    };
    std::vector<Case> cases;
    for (int i = 0; i < 2048; ++i) {
        Case c;
        const glm::vec3 x(20.0f * u(rng) - 10.0f, 20.0f * u(rng) - 10.0f, 20.0f * u(rng) - 10.0f);
        const glm::vec3 n = sphere();
        const glm::vec3 towards = above(n);
        const float d = 0.05f + 8.0f * u(rng);
        const glm::vec3 valPosition = x + d * towards;
        const glm::vec3 valNormal = glm::normalize(-towards + 0.9f * sphere());
        c.valPositionArea = glm::vec4(valPosition, std::pow(10.0f, -4.0f + 4.0f * u(rng)));
        c.valNormalExpectation = glm::vec4(valNormal, std::pow(10.0f, -3.0f + 3.0f * u(rng)));
        c.valFluxExponent = glm::vec4(3.0f * u(rng), 3.0f * u(rng), 3.0f * u(rng), 200.0f * u(rng) * u(rng));
        c.receiverPositionDepth = glm::vec4(x, 0.1f + 100.0f * u(rng));
        c.receiverNormalFactor = glm::vec4(n, std::pow(10.0f, -7.0f + 5.0f * u(rng)));
        // The view near the mirror direction half of the time, so that cos^k is not always 0.
        const glm::vec3 mirror = mirrorDirection(towards, n);
        c.viewClamp = glm::vec4(i % 2 ? glm::normalize(mirror + 0.3f * sphere()) : above(n), 0.25f + 2.0f * u(rng));
        c.diffuseCosAxis = glm::vec4(u(rng), u(rng), i % 7 == 0 ? 0.0f : u(rng), 0.3f + 0.7f * u(rng));
        c.glossyCosSurface = glm::vec4(u(rng), u(rng), u(rng), 2.0f * u(rng) - 1.0f);
        const float maxDistance = 0.1f + 2.0f * u(rng);
        c.interpolation =
            glm::vec4(maxDistance * 1.1f * u(rng), maxDistance, i % 3 == 0 ? 2.0f : 1.0f, 2.0f * u(rng) - 1.0f);
        c.occluderPositionArea = glm::vec4(x + 10.0f * u(rng) * sphere(), 0.01f + 0.5f * u(rng));
        c.occluderNormalRadius = glm::vec4(sphere(), d * 1.2f * u(rng));
        c.roughnessOverlap = glm::vec4(0.02f + 0.98f * u(rng), 4096.0f, 0.5f * u(rng), 0.5f + 3.0f * u(rng));
        c.indices = glm::uvec4(1u + static_cast<unsigned>(4095.0f * u(rng)), static_cast<unsigned>(i % 5),
                               static_cast<unsigned>((i / 5) % 5), 1024u);
        // Degenerate inputs every so often (test_lightskin_math.cpp has their values): the VAL at the
        // receiver, P_VAL = 0, zero normals, zero area, max distance 0, zero weight sum.
        switch (i % 29) {
        case 1:
            c.valPositionArea = glm::vec4(x, 0.01f);
            break;
        case 2:
            c.valNormalExpectation.w = 0.0f;
            break;
        case 3:
            c.receiverNormalFactor = glm::vec4(0.0f, 0.0f, 0.0f, c.receiverNormalFactor.w);
            c.valNormalExpectation = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
            break;
        case 4:
            c.valPositionArea.w = 0.0f;
            c.occluderPositionArea = glm::vec4(x, 0.0f);
            break;
        case 5:
            c.interpolation = glm::vec4(0.0f, 0.0f, 1.0f, 0.5f);
            c.roughnessOverlap.w = 0.0f;
            break;
        default:
            break;
        }
        cases.push_back(c);
    }
    return cases;
}

} // namespace

TEST_CASE("the LightSkin maths give the same values in GLSL and C++", "[gl][lightskin][numbers]")
{
    test::ensureGLContext();
    const std::vector<Case> cases = makeCases();
    const std::vector<glm::vec4> results =
        test::runComputeProbe("lightskin probe", "lightskin_probe.comp", cases.data(), cases.size() * sizeof(Case),
                              static_cast<int>(cases.size()), kResultsPerCase);

    // Per output component, the largest |GPU - CPU| relative to |CPU| (rgb rows 0-3: relative to the
    // brightest channel; unit-disk coordinates, rows 6 and 7 x y, absolute: they are cosines).
    // A cosine near 0 is ill-conditioned: the ulp by which the GPU's and the CPU's unit direction
    // differ (~6e-8 absolute) becomes 6e-8/cos relative. So the worst is kept twice: over the cases
    // whose cosines (VAL, receiver, occluder disk, receiver towards the occluder) all exceed 0.05,
    // and over all cases.
    constexpr int kComponents = kResultsPerCase * 4;
    double worst[2][kComponents] = {};
    int nonFinite = 0, candidateMismatches = 0, pixelMismatches = 0, litDiffuse = 0, litGlossy = 0, candidates = 0;
    int wellConditioned = 0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const Case& c = cases[i];
        const std::vector<glm::vec4> expected = expectedResults(c);
        const glm::vec4* got = &results[i * kResultsPerCase];
        for (int row = 0; row < kResultsPerCase; ++row)
            for (int k = 0; k < 4; ++k)
                if (!std::isfinite(got[row][k])) ++nonFinite;
        if (expected[0].y > 0.0f) ++litDiffuse;
        if (expected[1].y > 0.0f) ++litGlossy;
        if (expected[8].x == 1.0f) ++candidates;
        if (got[8].x != expected[8].x) ++candidateMismatches;
        if (got[5].z != expected[5].z || got[5].w != expected[5].w) ++pixelMismatches;

        const glm::dvec3 x(c.receiverPositionDepth), n(c.receiverNormalFactor);
        const glm::dvec3 toVal = glm::dvec3(c.valPositionArea) - x, toOccluder = glm::dvec3(c.occluderPositionArea) - x;
        const glm::dvec3 w = glm::length(toVal) > 0.0 ? glm::normalize(toVal) : glm::dvec3(0.0);
        const glm::dvec3 o = glm::length(toOccluder) > 0.0 ? glm::normalize(toOccluder) : glm::dvec3(0.0);
        const double smallest =
            std::min({std::abs(glm::dot(glm::dvec3(c.valNormalExpectation), w)), std::abs(glm::dot(n, w)),
                      std::abs(glm::dot(glm::dvec3(c.occluderNormalRadius), o)), std::abs(glm::dot(n, o))});
        const bool conditioned = smallest > 0.05;
        if (conditioned) ++wellConditioned;
        for (int row = 0; row < kResultsPerCase; ++row) {
            const bool colour = row < 4;
            const double colourScale = std::max({double(std::abs(expected[row].x)), double(std::abs(expected[row].y)),
                                                 double(std::abs(expected[row].z)), 1e-30});
            for (int k = 0; k < 4; ++k) {
                if (row == 8 && k == 0) continue; // the candidate flag, counted above
                const bool absolute = (row == 6 || row == 7) && k < 2;
                const double scale = absolute          ? 1.0
                                     : colour && k < 3 ? colourScale
                                                       : std::max(double(std::abs(expected[row][k])), 1e-30);
                const double error = std::abs(double(got[row][k]) - expected[row][k]) / scale;
                for (int set = conditioned ? 0 : 1; set < 2; ++set)
                    worst[set][row * 4 + k] = std::max(worst[set][row * 4 + k], error);
            }
        }
    }
    // Colour rows as one number each (worst channel), then every scalar.
    auto rowWorst = [&](int set, int row) {
        return std::max({worst[set][row * 4], worst[set][row * 4 + 1], worst[set][row * 4 + 2]});
    };
    const char* names[kComponents] = {"diffuse",
                                      "",
                                      "",
                                      "area (perspective)",
                                      "glossy",
                                      "",
                                      "",
                                      "area (orthographic)",
                                      "proxy flux",
                                      "",
                                      "",
                                      "area (tilted)",
                                      "point light",
                                      "",
                                      "",
                                      "form factor",
                                      "weight d",
                                      "weight g",
                                      "interpolation",
                                      "importance",
                                      "halton 2",
                                      "halton 3",
                                      "pixel x",
                                      "pixel y",
                                      "sphere x",
                                      "sphere y",
                                      "sphere area",
                                      "sphere radius",
                                      "disk x",
                                      "disk y",
                                      "disk area",
                                      "overlap",
                                      "",
                                      "occlusion",
                                      "phong k",
                                      "P_VAL"};
    for (int set = 0; set < 2; ++set) {
        std::ostringstream line;
        line << "lightskin GLSL vs C++ (relative), " << (set == 0 ? "cosines > 0.05 (" : "all cases (")
             << (set == 0 ? wellConditioned : static_cast<int>(cases.size())) << "):";
        for (int row = 0; row < 4; ++row)
            line << " " << names[row * 4] << " " << rowWorst(set, row) << ",";
        for (int i = 0; i < kComponents; ++i)
            if (names[i][0] != '\0' && !(i < 16 && i % 4 != 3)) line << " " << names[i] << " " << worst[set][i] << ",";
        test::printMeasured(line.str());
    }
    MEASURED("lightskin probe coverage: " << litDiffuse << " diffuse and " << litGlossy << " glossy lit of "
                                          << cases.size() << ", " << candidates << " occluder candidates");
    CHECK(nonFinite == 0);
    CHECK(candidateMismatches == 0);
    CHECK(pixelMismatches == 0);
    CHECK(litDiffuse > 500);
    CHECK(litGlossy > 300);
    CHECK(candidates > 50);
    CHECK(wellConditioned > 500);
    // Components by kind: Phong lobes (glossy radiance, glossy weight: pow), the square overlap (a
    // difference of interval ends: relative error grows as the overlap shrinks) and the rest.
    auto isPhong = [](int i) { return (i >= 4 && i < 7) || i == 17; };
    const int kOverlap = 7 * 4 + 3;
    double restConditioned = 0.0, restAll = 0.0, phong = 0.0;
    for (int i = 0; i < kComponents; ++i) {
        if (isPhong(i)) {
            phong = std::max(phong, worst[1][i]);
        } else if (i != kOverlap) {
            restConditioned = std::max(restConditioned, worst[0][i]);
            restAll = std::max(restAll, worst[1][i]);
        }
    }
    // Measured on llvmpipe: 1.08e-6 (the rest, cosines > 0.05: a few float roundings), 5.2e-5 (the
    // rest, all cases: a receiver cosine of 1.4e-4 whose ~7e-9 absolute difference is 5e-5
    // relative), 5.2e-5 (Phong lobes: llvmpipe's pow is exp2(k log2 c), whose error grows with k up
    // to 200 here) and 8.3e-6 (overlap). Tolerances are 2.5-3x those; a formula slip shows up as O(1).
    // On an H200 (test::twinTolerance): 1.04e-4 for the rest with cosines > 0.05 (its approximate
    // transcendentals), the other two within their llvmpipe bounds.
    CHECK(restConditioned < test::twinTolerance(3e-6, 3e-4));
    CHECK(restAll < 1.5e-4);
    CHECK(phong < 1.5e-4);
    CHECK(worst[1][kOverlap] < 2.5e-5);
}
