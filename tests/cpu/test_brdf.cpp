// The shared material (glsl/shared/brdf.h) checked on its own, independently of the path tracer's
// sampler: the GGX NDF's normalisation, the height-correlated Smith term against the textbook
// Lambda form written out here, the white-furnace directional albedo (<= 1, and 1 for the Lambert
// lobe alone), and reciprocity. Integrals are deterministic quadratures, never Monte Carlo, so every
// tolerance sits a small factor above a measured, repeatable error.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "glsl/shared/brdf.h"
#include "brdf_quadrature.h"
#include "measured.h"

using namespace vplgi;
using test::integrateAboutNormal;
using test::polarDirection;

namespace {

constexpr double kPi = 3.14159265358979323846;
const glm::vec3 kNormal(0.0f, 0.0f, 1.0f);

} // namespace

TEST_CASE("GGX NDF is normalised: the integral of D(h) (n.h) over the hemisphere is 1", "[brdf][numbers]")
{
    // The quadrature alone (the same nodes with D in double precision) is within 2e-11 of 1 for every
    // alpha here. What is left is the float evaluation of distributionGGX: near the pole cos(theta)
    // moves in float steps of 6e-8 while 1 - cos^2(theta) spans only ~alpha^2 across the lobe, so the
    // error grows like 1e-8 / alpha^2 (a limitation of the shared float code, not of this test).
    // Tolerances: 2-3x each measured |integral - 1|, floored at 1e-7.
    struct Case {
        float alpha;
        double tolerance;
    };
    const Case cases[] = {
        {shared::kMinAlpha, 4e-3}, // measured 1.77e-3
        {0.0025f, 3e-3},           // measured 1.31e-3 (roughness 0.05)
        {0.01f, 6e-4},             // measured 2.31e-4
        {0.04f, 5e-5},             // measured 1.79e-5
        {0.1f, 3e-6},              // measured 9.5e-7
        {0.25f, 1e-7},             // measured 2.9e-8
        {0.5f, 1e-7},              // measured 2.8e-8
        {0.75f, 1e-7},             // measured 2.7e-8
        {1.0f, 1e-7},              // measured 4.0e-8
    };
    for (const Case& c : cases) {
        const float alpha = c.alpha;
        const double integral = integrateAboutNormal<double>(
            [alpha](double theta, double) {
                const float cosine = static_cast<float>(std::cos(theta));
                return static_cast<double>(shared::distributionGGX(cosine, alpha)) * cosine;
            },
            200000, 1, false);
        MEASURED("GGX NDF normalisation at alpha " << alpha << ": int D (n.h) dw - 1 = " << integral - 1.0);
        CHECK(std::abs(integral - 1.0) < c.tolerance);
    }
}

TEST_CASE("height-correlated Smith term matches the textbook Lambda form (Heitz 2014)", "[brdf][numbers]")
{
    // Heitz 2014, eq. 99 and 72: Lambda(w) = (-1 + sqrt(1 + alpha^2 tan^2 theta)) / 2 for GGX,
    // G2(wo, wi) = 1 / (1 + Lambda(wo) + Lambda(wi)); visibilitySmithGGX is G2 / (4 NoV NoL).
    auto lambda = [](double cosine, double alpha) {
        const double tan2 = (1.0 - cosine * cosine) / (cosine * cosine);
        return 0.5 * (-1.0 + std::sqrt(1.0 + alpha * alpha * tan2));
    };
    std::mt19937 engine(2014u);
    std::uniform_real_distribution<double> cosines(0.01, 1.0);
    double worst = 0.0;
    for (double alpha : {0.002, 0.01, 0.1, 0.3, 0.6, 1.0}) {
        for (int k = 0; k < 2000; ++k) {
            const double noV = cosines(engine), noL = cosines(engine);
            const double g2 = 1.0 / (1.0 + lambda(noV, alpha) + lambda(noL, alpha));
            const double textbook = g2 / (4.0 * noV * noL);
            const double shared = shared::visibilitySmithGGX(static_cast<float>(noV), static_cast<float>(noL),
                                                             static_cast<float>(alpha));
            worst = std::max(worst, std::abs(shared / textbook - 1.0));
        }
    }
    MEASURED("Smith G2 (height-correlated) vs textbook Lambda form: worst relative difference " << worst);
    // Measured: 2.1e-7 worst relative difference over 12000 pairs (float rounding of the inputs and
    // the evaluation).
    CHECK(worst < 5e-7);
    // Not a tautology: the uncorrelated product G1(wo) G1(wi) differs by far more at grazing angles.
    const double separable = 1.0 / ((1.0 + lambda(0.1, 0.5)) * (1.0 + lambda(0.1, 0.5))) / (4.0 * 0.01);
    CHECK(std::abs(shared::visibilitySmithGGX(0.1f, 0.1f, 0.5f) / separable - 1.0) > 0.1);
}

TEST_CASE("white furnace: directional albedo <= 1 for every roughness, Lambert alone is its albedo",
          "[brdf][numbers]")
{
    // F0 = 1 (metallic white): Fresnel is exactly 1, so the albedo is what masking-shadowing leaves,
    // which single-scattering GGX loses energy to (more at high roughness) but can never exceed 1.
    // Sanity of the quadrature: at roughness 1 (alpha = 1, D = 1/pi, V = 1/(2 (NoL + NoV))) and normal
    // view the albedo is 1 - ln 2 in closed form.
    const shared::SurfaceMaterial white{glm::vec3(1.0f), 1.0f, 0.0f, 1.0f};
    {
        shared::SurfaceMaterial roughest = white;
        roughest.roughness = 1.0f;
        const double albedo = test::directionalAlbedo(roughest, 0.0).g;
        MEASURED("white furnace, roughness 1, normal view: albedo - (1 - ln 2) = " << albedo - (1.0 - std::log(2.0)));
        CHECK(std::abs(albedo - (1.0 - std::log(2.0))) < 7e-7); // measured 2.7e-7
    }
    // Allowed excess over 1 per roughness. From roughness 0.2 up the albedo stays below 1 by far more
    // than the quadrature error, 1e-5 is a margin for that. Below, the float evaluation of D (see the
    // NDF test) lets the albedo at normal view exceed 1: measured +1.35e-2 at roughness 0.05 (alpha
    // 0.0025) and +5.4e-4 at 0.1 (alpha 0.01); the tolerances are 2-3x those.
    auto allowedExcess = [](float roughness) { return roughness <= 0.05f ? 3e-2 : roughness <= 0.1f ? 1.5e-3 : 1e-5; };
    double highest = 0.0, highestRough = 0.0, lowestSmooth = 2.0;
    for (float roughness : {0.05f, 0.1f, 0.2f, 0.35f, 0.5f, 0.75f, 1.0f}) {
        for (float thetaO : {0.0f, 0.5f, 1.0f, 1.3f, 1.5f}) {
            shared::SurfaceMaterial material = white;
            material.roughness = roughness;
            const double albedo = test::directionalAlbedo(material, thetaO).g;
            INFO("roughness " << roughness << ", theta_o " << thetaO << ": albedo " << albedo);
            highest = std::max(highest, albedo);
            if (roughness >= 0.2f) highestRough = std::max(highestRough, albedo);
            CHECK(albedo <= 1.0 + allowedExcess(roughness));
            CHECK(albedo > 0.3); // lowest: 1 - ln 2 = 0.307 at roughness 1, normal view
            if (roughness <= 0.1f && thetaO <= 1.0f) lowestSmooth = std::min(lowestSmooth, albedo);
        }
    }
    // A nearly smooth mirror with F = 1 reflects nearly everything: measured lowest 0.99884
    // (roughness 0.05, theta_o = 1); what is missing is the little masking a narrow lobe still has.
    CHECK(lowestSmooth > 0.997);
    MEASURED("white furnace (F0 = 1): highest directional albedo " << highest << " (float D at roughness 0.05), "
             << highestRough << " from roughness 0.2 up; lowest at roughness <= 0.1, theta_o <= 1: " << lowestSmooth);

    // The Lambert lobe alone (metallic 0, specular 0: no microfacet term) reflects exactly its albedo.
    const shared::SurfaceMaterial lambert{glm::vec3(0.7f, 0.5f, 0.3f), 0.0f, 0.6f, 0.0f};
    const glm::vec3 wo = glm::normalize(glm::vec3(0.4f, 0.2f, 0.8f));
    double worstLambert = 0.0;
    for (int c = 0; c < 3; ++c) {
        const double albedo = integrateAboutNormal<double>(
            [&](double theta, double phi) {
                const glm::vec3 wi = polarDirection(theta, phi);
                return static_cast<double>(shared::evaluateBRDF(lambert, kNormal, wo, wi)[c]) * wi.z;
            },
            4000, 64, false);
        worstLambert = std::max(worstLambert, std::abs(albedo / lambert.baseColor[c] - 1.0));
    }
    MEASURED("Lambert lobe: worst relative difference of its directional albedo from baseColor " << worstLambert);
    // Measured: 1.96e-7 (the quadrature's own error on cos(theta) plus float rounding of 1/pi).
    CHECK(worstLambert < 5e-7);
}

TEST_CASE("the shared BRDF is reciprocal: f(wo, wi) = f(wi, wo)", "[brdf][numbers]")
{
    std::mt19937 engine(7u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    auto randomDirection = [&] { // uniform on the sphere; half of them below the horizon
        const float z = 2.0f * unit(engine) - 1.0f;
        const float phi = 2.0f * static_cast<float>(kPi) * unit(engine);
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
    };
    double worst = 0.0;
    int nonZero = 0;
    for (int k = 0; k < 20000; ++k) {
        const shared::SurfaceMaterial material{glm::vec3(unit(engine), unit(engine), unit(engine)), unit(engine),
                                               std::max(0.05f, unit(engine)), unit(engine)};
        const glm::vec3 a = randomDirection(), b = randomDirection();
        const glm::vec3 ab = shared::evaluateBRDF(material, kNormal, a, b);
        const glm::vec3 ba = shared::evaluateBRDF(material, kNormal, b, a);
        for (int c = 0; c < 3; ++c) {
            if (ab[c] == 0.0f && ba[c] == 0.0f) continue;
            ++nonZero;
            worst = std::max(worst, static_cast<double>(std::abs(ab[c] - ba[c]) / std::max(ab[c], ba[c])));
        }
    }
    MEASURED("reciprocity: worst relative |f(wo, wi) - f(wi, wo)| " << worst << " over " << nonZero << " values");
    CHECK(nonZero > 10000); // about a quarter of the pairs have both directions above the horizon
    // Measured: 2.6e-6 (float rounding: the Fresnel term evaluates v.h, the reversed call l.h, and
    // the Smith term adds its two halves in the other order).
    CHECK(worst < 7e-6);
}
