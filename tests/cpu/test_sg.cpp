// The spherical-Gaussian maths of VSGL (glsl/shared/sg.h) against deterministic quadrature on the
// sphere (tests/common/sphere_quadrature.h), closed forms and the exact point-light formula (eq. 1),
// and the GGX -> SG fit table of docs/vsgl.md. Integrands of the references are written out here in
// double from the definitions (MATH.md 4), not taken from the code under test, except where a test
// says it checks the assembly of given lobes. Every tolerance is 2-3x the measured error, which the
// test prints ("measured: ..." lines; `ctest -L numbers --verbose`).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "glsl/shared/sg.h"
#include "measured.h"
#include "sphere_quadrature.h"

using namespace vplgi;
using namespace vplgi::shared;
using test::integrateSphereAbout;

namespace {

constexpr double kPiD = 3.14159265358979323846;

glm::dvec3 toDouble(const glm::vec3& v)
{
    return glm::dvec3(v);
}

// Unit vector at angle `angle` from `axis`, rotated towards the (fixed) tangent t of the axis.
glm::vec3 tiltedFrom(const glm::vec3& axis, float angle)
{
    const glm::mat3 frame = lightViewBasis(axis);
    return glm::normalize(std::cos(angle) * axis + std::sin(angle) * frame[0]);
}

float degrees(float d)
{
    return d * static_cast<float>(kPiD) / 180.0f;
}

// A SG written out in double (MATH 4.1), evaluated at a double direction. The float axis is
// renormalised in double: its norm is 1 only to ~6e-8, which a sharpness of 1e6 turns into 6%.
double sgReference(const SGLobe& g, const glm::dvec3& w)
{
    return g.amplitude * std::exp(g.sharpness * (glm::dot(w, glm::normalize(toDouble(g.axis))) - 1.0));
}

// An ASG written out in double (MATH 4.9).
double asgReference(const ASGLobe& g, const glm::dvec3& w)
{
    const double u = glm::dot(w, toDouble(g.x)), v = glm::dot(w, toDouble(g.y));
    return g.amplitude * std::max(glm::dot(w, toDouble(g.z)), 0.0) *
           std::exp(-double(g.sharpnessX) * u * u - double(g.sharpnessY) * v * v);
}

ASGLobe makeASG(const glm::vec3& z, float sharpnessX, float sharpnessY, float amplitude)
{
    const glm::mat3 frame = lightViewBasis(z);
    ASGLobe g;
    g.x = frame[0];
    g.y = frame[1];
    g.z = z;
    g.sharpnessX = sharpnessX;
    g.sharpnessY = sharpnessY;
    g.amplitude = amplitude;
    return g;
}

SGLobe makeSG(const glm::vec3& axis, float sharpness, float amplitude)
{
    SGLobe g;
    g.axis = axis;
    g.sharpness = sharpness;
    g.amplitude = amplitude;
    return g;
}

glm::vec3 randomUnit(std::mt19937& engine)
{
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float z = 2.0f * unit(engine) - 1.0f, phi = 2.0f * static_cast<float>(kPiD) * unit(engine);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
}

bool finite(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

} // namespace

TEST_CASE("SG integral matches quadrature and the closed form from eta = 0 to 1e6", "[sg][numbers]")
{
    const glm::dvec3 axis(0.0, 0.0, 1.0);
    double worstFloat = 0.0, worstQuadrature = 0.0;
    for (double eta : {0.0, 1e-4, 1e-3, 0.0499, 0.0501, 0.3, 1.0, 10.0, 100.0, 1e4, 1e6}) {
        const double closed = eta == 0.0 ? 4.0 * kPiD : 2.0 * kPiD * -std::expm1(-2.0 * eta) / eta;
        const double quadrature = integrateSphereAbout<double>(
            axis, [eta, &axis](const glm::dvec3& w) { return std::exp(eta * (glm::dot(w, axis) - 1.0)); }, 6000, 4);
        const double shared = sgIntegral(static_cast<float>(eta));
        INFO("eta " << eta << ": closed " << closed << ", quadrature " << quadrature << ", sgIntegral " << shared);
        worstQuadrature = std::max(worstQuadrature, std::abs(quadrature / closed - 1.0));
        worstFloat = std::max(worstFloat, std::abs(shared / closed - 1.0));
    }
    MEASURED("sgIntegral: worst relative error vs closed form " << worstFloat << " (float), quadrature vs closed form "
                                                                << worstQuadrature);
    // Measured 9.9e-8 (float rounding) and 9.1e-8 (the quadrature's own error).
    CHECK(worstFloat < 3e-7);
    CHECK(worstQuadrature < 3e-7);
}

TEST_CASE("SG product is the pointwise product, also for a huge sharpness next to a small one", "[sg][numbers]")
{
    std::mt19937 engine(43u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    struct Pair {
        SGLobe a, b;
    };
    std::vector<Pair> pairs;
    for (int k = 0; k < 200; ++k) {
        const float etaA = std::pow(10.0f, -3.0f + 7.0f * unit(engine)),
                    etaB = std::pow(10.0f, -3.0f + 7.0f * unit(engine));
        const glm::vec3 axisA = randomUnit(engine);
        const glm::vec3 axisB = k % 2 ? randomUnit(engine) : tiltedFrom(axisA, 0.2f * unit(engine));
        pairs.push_back({makeSG(axisA, etaA, 0.5f + unit(engine)), makeSG(axisB, etaB, 0.5f + unit(engine))});
    }
    // Opposite axes of equal sharpness (a constant), a zero sharpness, the cone of a tiny VSL.
    const glm::vec3 z(0.0f, 0.0f, 1.0f);
    pairs.push_back({makeSG(z, 7.0f, 1.0f), makeSG(-z, 7.0f, 1.0f)});
    pairs.push_back({makeSG(z, 0.0f, 2.0f), makeSG(tiltedFrom(z, 0.3f), 40.0f, 1.0f)});
    pairs.push_back({makeSG(tiltedFrom(z, degrees(1.0f)), 50.0f, 1.0f), makeSG(z, 1e9f, 1.0f)});
    pairs.push_back({makeSG(tiltedFrom(z, degrees(0.1f)), 2000.0f, 1.0f), makeSG(z, kConeMaxSharpness, 1.0f)});

    double worst = 0.0;
    for (const Pair& p : pairs) {
        const SGLobe product = sgProduct(p.a, p.b);
        REQUIRE(std::isfinite(product.amplitude));
        // Directions where the product is not negligible: its axis tilted by up to 3 standard
        // deviations (1/sqrt(eta)) in a few directions.
        const double spread = product.sharpness > 0.0f ? 3.0 / std::sqrt(double(product.sharpness)) : 1.0;
        for (int k = 0; k < 16; ++k) {
            const glm::vec3 w = glm::normalize(product.axis + float(spread * unit(engine)) * randomUnit(engine));
            // Unit vectors in double: a float norm error of 6e-8 times a sharpness of 1e12 would swamp
            // the comparison (the shared code never evaluates such a lobe pointwise).
            const glm::dvec3 wd = glm::normalize(toDouble(w));
            const glm::dvec3 axisA = glm::normalize(toDouble(p.a.axis)), axisB = glm::normalize(toDouble(p.b.axis));
            const glm::dvec3 axisP = glm::normalize(toDouble(product.axis));
            // Logarithms: the values span hundreds of orders of magnitude. Error per unit of the
            // exponents involved: the float axes (6e-8) times the sharpness set the scale.
            const double reference = std::log(double(p.a.amplitude) * double(p.b.amplitude)) +
                                     p.a.sharpness * (glm::dot(wd, axisA) - 1.0) +
                                     p.b.sharpness * (glm::dot(wd, axisB) - 1.0);
            const double got = std::log(double(product.amplitude)) + product.sharpness * (glm::dot(wd, axisP) - 1.0);
            if (!(product.amplitude > 0.0f)) continue; // underflow of a product below 1e-38: nothing to compare
            const double scale = 1.0 + std::abs(reference) + 1e-7 * (double(p.a.sharpness) + p.b.sharpness) * spread;
            worst = std::max(worst, std::abs(got - reference) / scale);
        }
    }
    MEASURED("sgProduct: worst |log error| / (1 + |log value| + 1e-7 (eta_a + eta_b) spread) " << worst);
    // Measured 3.1e-6 (float rounding of the axes). Not a tautology: float's spacing at 1e9 is 64, so
    // |v| - eta_a - eta_b computed directly could be off by up to ~64 in the logarithm of that pair.
    CHECK(worst < 1e-5);
}

TEST_CASE("SG inner product matches quadrature", "[sg][numbers]")
{
    struct Case {
        float etaA, etaB, angleDegrees;
    };
    const Case cases[] = {{1.0f, 1.0f, 90.0f},    {10.0f, 100.0f, 5.0f},  {300.0f, 300.0f, 2.0f}, {0.0f, 50.0f, 30.0f},
                          {1e-3f, 1e-3f, 180.0f}, {20.0f, 20.0f, 180.0f}, {1e4f, 10.0f, 1.0f},    {1e6f, 100.0f, 0.5f}};
    const glm::vec3 z(0.0f, 0.0f, 1.0f);
    double worst = 0.0;
    for (const Case& c : cases) {
        const SGLobe a = makeSG(z, c.etaA, 1.0f);
        const SGLobe b = makeSG(tiltedFrom(z, degrees(c.angleDegrees)), c.etaB, 1.0f);
        const SGLobe sharper = c.etaA >= c.etaB ? a : b;
        const double quadrature = integrateSphereAbout<double>(
            toDouble(sharper.axis), [&](const glm::dvec3& w) { return sgReference(a, w) * sgReference(b, w); }, 6000,
            256);
        const double shared = sgInnerProduct(a, b);
        const double error = std::abs(shared / quadrature - 1.0);
        INFO("eta " << c.etaA << ", " << c.etaB << " at " << c.angleDegrees << " deg: quadrature " << quadrature
                    << ", sgInnerProduct " << shared);
        worst = std::max(worst, error);
    }
    MEASURED("sgInnerProduct: worst relative error vs quadrature " << worst);
    CHECK(worst < 5e-6); // measured 1.9e-6 (float rounding)
}

TEST_CASE("ASG evaluates its definition and its product integral with an SG matches quadrature", "[sg][numbers]")
{
    const glm::vec3 z(0.0f, 0.0f, 1.0f);
    {
        // The definition along the ASG's own axes: cos(theta) exp(-lambda sin^2 theta) in the x-z plane.
        const ASGLobe g = makeASG(z, 30.0f, 5.0f, 2.0f);
        for (float theta : {0.0f, 0.1f, 0.4f, 1.2f}) {
            const glm::vec3 inX = std::cos(theta) * g.z + std::sin(theta) * g.x;
            const glm::vec3 inY = std::cos(theta) * g.z + std::sin(theta) * g.y;
            const double s2 = std::sin(theta) * std::sin(theta);
            CHECK(asgEvaluate(g, inX) == Approx(2.0 * std::cos(theta) * std::exp(-30.0 * s2)).epsilon(1e-5));
            CHECK(asgEvaluate(g, inY) == Approx(2.0 * std::cos(theta) * std::exp(-5.0 * s2)).epsilon(1e-5));
        }
        CHECK(asgEvaluate(g, -z) == 0.0f);
    }
    // (lambda, mu, nu, offset of the SG from the ASG axis, tolerance): MATH 4.9 measured 0.06-1.6% for
    // sharpness >= 10 and 3.6% at (2, 2, 2); tolerances 2-3x what this test measures.
    struct Case {
        float lambda, mu, nu, offsetDegrees;
        double tolerance;
    };
    const Case cases[] = {
        {10.0f, 40.0f, 10.0f, 3.0f, 1e-2},   // measured 4.3e-3
        {5.0f, 20.0f, 300.0f, 2.0f, 6e-3},   // measured 2.7e-3
        {200.0f, 800.0f, 10.0f, 1.0f, 3e-4}, // measured 1.3e-4
        {100.0f, 25.0f, 100.0f, 5.0f, 5e-3}, // measured 1.9e-3
        {2.0f, 2.0f, 2.0f, 10.0f, 0.2},      // measured 8.8e-2 (too broad for the large-sharpness form)
        {50.0f, 50.0f, 1e6f, 0.5f, 3e-6},    // measured 1.2e-6 (the cone of a tiny VSL: the ASG at p)
        {100.0f, 400.0f, 0.0f, 0.0f, 2e-7},  // measured 4.4e-8 (a constant SG: the ASG's integral pi/sqrt(lambda mu))
    };
    double worst = 0.0;
    for (const Case& c : cases) {
        const ASGLobe asg = makeASG(z, c.lambda, c.mu, 1.5f);
        // The SG tilted off the axis between x and y, so that both bandwidths matter.
        const glm::vec3 p = glm::normalize(std::cos(degrees(c.offsetDegrees)) * z +
                                           std::sin(degrees(c.offsetDegrees)) * glm::normalize(asg.x + 0.5f * asg.y));
        const SGLobe sg = makeSG(p, c.nu, 1.0f / sgIntegral(c.nu));
        const glm::vec3 axis = c.nu > 2.0f * std::max(c.lambda, c.mu) ? p : z;
        const double quadrature = integrateSphereAbout<double>(
            toDouble(axis), [&](const glm::dvec3& w) { return asgReference(asg, w) * sgReference(sg, w); }, 6000, 512);
        const double shared = asgSGProductIntegral(asg, sg);
        const double error = std::abs(shared / quadrature - 1.0);
        MEASURED("asgSGProductIntegral (lambda " << c.lambda << ", mu " << c.mu << ", nu " << c.nu << ", offset "
                                                 << c.offsetDegrees << " deg): relative error " << error);
        CHECK(error < c.tolerance);
        worst = std::max(worst, error);
    }
    CHECK(worst > 1e-3); // the form is approximate: an exact match would mean the test compares nothing
    // Zero sharpness everywhere: the form would be infinite; the cap gives the exact pi (the integral
    // of the clamped cosine times a constant).
    CHECK(asgSGProductIntegral(makeASG(z, 0.0f, 0.0f, 1.0f), makeSG(z, 0.0f, 1.0f)) == Approx(kPiD).epsilon(1e-6));
}

TEST_CASE("cone SG: cancellation-free solid angle, sharpness and the integral of 2 G_V", "[sg][numbers]")
{
    // Omega/(pi r^2) = 2/(s(s+d)) in float against double, where the naive 1 - d/s in float fails.
    double worstForm = 0.0;
    for (double ratio : {1e-5, 1e-4, 1e-3, 1e-2, 0.1, 1.0, 10.0, 1e3}) {
        const double d = 3.0, r2 = ratio * ratio * d * d, s = std::sqrt(d * d + r2);
        const double reference = 2.0 * kPiD * (r2 / (s * (s + d))) / (kPiD * r2); // exact algebra in double
        const double shared = coneSolidAngleOverArea(float(d), float(r2));
        worstForm = std::max(worstForm, std::abs(shared / reference - 1.0));
        const double sharpness = coneSharpness(float(d), float(r2));
        CHECK(sharpness == Approx(std::min(4.0 * kPiD / (2.0 * kPiD * r2 / (s * (s + d))), 1e12)).epsilon(1e-6));
        if (ratio == 1e-4) {
            const float sf = std::sqrt(float(d * d + r2));
            const double naive = 2.0 * (1.0 - double(float(d) / sf)) / float(r2);
            CHECK(std::abs(naive / reference - 1.0) > 0.5); // the naive form is useless here (MATH 4.5)
        }
    }
    MEASURED("cone: worst relative error of Omega/(pi r^2) in float " << worstForm);
    CHECK(worstForm < 3e-7);                          // measured 1.0e-7
    CHECK(coneSharpness(0.0f, 0.25f) == Approx(2.0)); // d = 0: a hemisphere, 4 pi / 2 pi
    CHECK(coneSharpness(1.0f, 0.0f) == kConeMaxSharpness);

    // int 2 G_V = Omega (1 - e^{-8 pi/Omega}) (MATH 4.5), by quadrature, for cones of 0.5 to 60 deg.
    double worstIntegral = 0.0;
    for (float halfAngle : {0.5f, 2.0f, 10.0f, 30.0f, 60.0f}) {
        const float d = 1.0f, r = std::tan(degrees(halfAngle)), r2 = r * r;
        const double omega = coneSolidAngle(d, r2);
        const double exactCone = 2.0 * kPiD * (1.0 - std::cos(double(degrees(halfAngle))));
        CHECK(omega == Approx(exactCone).epsilon(2e-6));
        const SGLobe cone = makeSG(glm::vec3(0.0f, 0.0f, 1.0f), coneSharpness(d, r2), 2.0f);
        const double quadrature = integrateSphereAbout<double>(
            glm::dvec3(0, 0, 1), [&](const glm::dvec3& w) { return sgReference(cone, w); }, 4000, 4);
        const double expected = omega * (1.0 - std::exp(-8.0 * kPiD / omega));
        worstIntegral = std::max(worstIntegral, std::abs(quadrature / expected - 1.0));
        if (halfAngle <= 10.0f) CHECK(std::abs(quadrature / omega - 1.0) < 1e-6); // preserved solid angle
    }
    MEASURED("cone: worst relative error of int 2 G_V vs Omega (1 - e^{-8 pi/Omega}) " << worstIntegral);
    CHECK(worstIntegral < 2e-7); // measured 5.7e-8 (float sharpness)
}

TEST_CASE("triple product ASG x SG x cone SG matches quadrature (MATH 4.10), with the diffuse special cases",
          "[sg][numbers]")
{
    const glm::vec3 z(0.0f, 0.0f, 1.0f);
    double worst = 0.0;
    int count = 0;
    for (glm::vec2 bandwidths : {glm::vec2(5.0f, 20.0f), glm::vec2(50.0f, 200.0f), glm::vec2(200.0f, 800.0f)}) {
        for (float etaLight : {0.0f, 10.0f, 300.0f}) {
            for (float coneDegrees : {2.0f, 5.0f, 20.0f}) {
                const ASGLobe asg = makeASG(z, bandwidths.x, bandwidths.y, 1.0f);
                const glm::vec3 coneAxis = glm::normalize(tiltedFrom(z, degrees(2.0f)) + 0.01f * asg.y);
                const float r = std::tan(degrees(coneDegrees));
                const SGLobe cone = sgNormalised(coneAxis, coneSharpness(1.0f, r * r));
                const SGLobe light =
                    sgNormalised(glm::normalize(tiltedFrom(z, degrees(3.0f)) - 0.02f * asg.x), etaLight);
                const double shared = asgSGProductIntegral(asg, sgProduct(light, cone));
                const glm::vec3 axis = cone.sharpness > 2.0f * bandwidths.y ? coneAxis : z;
                const double quadrature = integrateSphereAbout<double>(
                    toDouble(axis),
                    [&](const glm::dvec3& w) {
                        return asgReference(asg, w) * sgReference(light, w) * sgReference(cone, w);
                    },
                    4000, 512);
                const double error = std::abs(shared / quadrature - 1.0);
                INFO("ASG (" << bandwidths.x << ", " << bandwidths.y << "), light eta " << etaLight << ", cone "
                             << coneDegrees << " deg: quadrature " << quadrature << ", shared " << shared);
                CHECK(error < 0.03);
                worst = std::max(worst, error);
                ++count;
            }
        }
    }
    MEASURED("triple product ASG x SG x cone SG: worst relative error vs quadrature over " << count
                                                                                           << " cases: " << worst);
    // Measured worst 1.15e-2 (MATH 4.10 saw 3e-5 .. 1e-2 for these lobes); the CHECK in the loop
    // allows 3e-2.

    // Shading point diffuse: the ASG is a constant, T = int G_l G_V = sgInnerProduct (exact, MATH 4.4).
    const SGLobe cone = sgNormalised(z, coneSharpness(1.0f, 0.01f));
    const SGLobe light = sgNormalised(tiltedFrom(z, degrees(4.0f)), 120.0f);
    const double quadratureDiffuse = integrateSphereAbout<double>(
        toDouble(z), [&](const glm::dvec3& w) { return sgReference(light, w) * sgReference(cone, w); }, 4000, 256);
    const double diffuseError = std::abs(sgInnerProduct(light, cone) / quadratureDiffuse - 1.0);
    // Both diffuse: T = int G_V; the cone's 2 G_V integrates to Omega (1 - e^{-8 pi/Omega}).
    const double bothDiffuse = 2.0 * sgIntegral(coneSharpness(1.0f, 0.01f));
    const double omega = coneSolidAngle(1.0f, 0.01f);
    MEASURED("triple product, shading point diffuse: relative error "
             << diffuseError << "; both diffuse: int 2 G_V / Omega - 1 = " << bothDiffuse / omega - 1.0);
    CHECK(diffuseError < 1e-7);                        // measured 3.3e-8
    CHECK(std::abs(bothDiffuse / omega - 1.0) < 2e-7); // measured 6.0e-8 (e^{-8 pi/Omega} ~ 0 for this 5.7 deg cone)
}

namespace {

// A VSGL with a GGX specular lobe made as the RSM pass makes it (ggxReflectionLobe), lit from
// `incoming` (unit, towards the primary light).
VSGLight makeLight(const glm::vec3& position, float radius2, const glm::vec3& normal, const glm::vec3& flux,
                   const glm::vec3& diffuse, const glm::vec3& f0, float roughness, const glm::vec3& incoming)
{
    const SpecularLobe lobe = ggxReflectionLobe(normal, incoming, roughness);
    VSGLight l;
    l.positionRadius2 = glm::vec4(position, radius2);
    l.normalValid = glm::vec4(normal, 1.0f);
    l.geometric = glm::vec4(normal, 0.0f);
    l.flux = glm::vec4(flux, 0.0f);
    l.diffuse = glm::vec4(diffuse, roughness);
    l.specular = glm::vec4(f0, lobe.integral);
    l.lobe = glm::vec4(lobe.axis, lobe.sharpness);
    return l;
}

VSGLShadingPoint makePoint(const glm::vec3& position, const glm::vec3& normal, const glm::vec3& view,
                           const glm::vec3& diffuse, const glm::vec3& f0, float roughness)
{
    VSGLShadingPoint s;
    s.position = position;
    s.normal = normal;
    s.view = view;
    s.diffuse = diffuse;
    s.f0 = f0;
    s.roughness = roughness;
    return s;
}

// The SG integrand of eq. (2)-(3) built from the lobes vsglRadiance uses (the receiver's ASG and
// coefficients, the light's SG and coefficients), per colour channel at direction u. The light's
// diffuse lobe takes its cosine at the cone's axis w (pulled out of the integral); its specular lobe
// carries its own (ggxReflectionLobe).
struct LobeProduct {
    VSGLReceiver receiver;
    SGLobe light;
    glm::dvec3 lightDiffuse, lightSpecular;

    LobeProduct(const VSGLShadingPoint& s, const VSGLight& l, const glm::vec3& w) : receiver(vsglReceiver(s))
    {
        const glm::vec3 n(l.normalValid), axis(l.lobe);
        light = sgNormalised(-axis, l.lobe.w);
        lightDiffuse = glm::dvec3(glm::vec3(l.flux) * glm::vec3(l.diffuse)) / kPiD *
                       static_cast<double>(std::max(0.0f, -glm::dot(w, n)));
        const glm::vec3 f0(l.specular);
        lightSpecular = f0.x + f0.y + f0.z > 0.0f
                            ? glm::dvec3(glm::vec3(l.flux) *
                                         fresnelSchlick(f0, glm::clamp(glm::dot(n, axis), 0.0f, 1.0f)) * l.specular.w)
                            : glm::dvec3(0.0);
    }
    glm::dvec3 operator()(const glm::dvec3& w) const
    {
        const glm::dvec3 atReceiver =
            glm::dvec3(receiver.diffuse) + glm::dvec3(receiver.specular) * asgReference(receiver.lobe, w);
        const glm::dvec3 atLight = lightDiffuse + lightSpecular * sgReference(light, w);
        return atReceiver * atLight;
    }
};

double worstChannelError(const glm::dvec3& got, const glm::dvec3& expected)
{
    double worst = 0.0, scale = std::max({expected.r, expected.g, expected.b});
    for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(got[c] - expected[c]) / scale);
    return worst;
}

} // namespace

TEST_CASE("vsglRadiance is eq. (2) with the SG integrand of eq. (3): against quadrature of its lobes",
          "[sg][vsgl][numbers]")
{
    // Checks the assembly (coefficients, normalisations, the cone, 1/(pi r^2)) of the closed forms
    // tested one by one above; the integrand is the same lobes in double, with the exact cone SG.
    std::mt19937 engine(2015u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    double worst = 0.0;
    for (int k = 0; k < 24; ++k) {
        const float viewAngle = degrees(60.0f * unit(engine));
        const glm::vec3 view(std::sin(viewAngle), 0.0f, std::cos(viewAngle));
        const VSGLShadingPoint s = makePoint(glm::vec3(0.0f), n, view, glm::vec3(0.5f, 0.3f, 0.2f),
                                             glm::vec3(0.04f, 0.5f, 0.9f), 0.3f + 0.5f * unit(engine));
        // The light near the receiver's mirror direction (its lobe matters), facing it within 40 deg.
        const glm::vec3 mirror = glm::normalize(2.0f * glm::dot(n, view) * n - view);
        glm::vec3 towards = glm::normalize(mirror + 0.3f * randomUnit(engine));
        if (towards.z < 0.2f) towards = glm::normalize(towards + glm::vec3(0.0f, 0.0f, 0.4f));
        const float d = 1.0f + 2.0f * unit(engine);
        const glm::vec3 lightNormal = glm::normalize(-towards + 0.5f * randomUnit(engine) * unit(engine));
        const float halfAngle = degrees(3.0f + 12.0f * unit(engine));
        const float r = d * std::tan(halfAngle);
        // Lit so that its own lobe points back at the receiver (roughly): incoming = reflection of -towards.
        const glm::vec3 out = glm::normalize(-towards + 0.2f * randomUnit(engine));
        glm::vec3 incoming = glm::normalize(2.0f * glm::dot(lightNormal, out) * lightNormal - out);
        if (glm::dot(incoming, lightNormal) <= 0.05f) incoming = lightNormal;
        const VSGLight l =
            makeLight(d * towards, r * r, lightNormal, glm::vec3(2.0f, 1.0f, 0.5f), glm::vec3(0.6f, 0.5f, 0.4f),
                      glm::vec3(0.3f, 0.6f, 0.9f), 0.3f + 0.5f * unit(engine), incoming);
        float cancelled = -1.0f;
        const glm::dvec3 shared = glm::dvec3(vsglRadiance(s, l, incoming, 0.0f, cancelled));
        CHECK(cancelled == 0.0f);

        const glm::vec3 w = towards;
        const LobeProduct product(s, l, w);
        const double cosines = std::max(0.0f, glm::dot(w, n));
        const SGLobe cone = makeSG(w, coneSharpness(d, r * r), 2.0f);
        const glm::dvec3 integral = integrateSphereAbout<glm::dvec3>(
            toDouble(w), [&](const glm::dvec3& u) { return product(u) * sgReference(cone, u); }, 2000, 256);
        const glm::dvec3 expected = integral * cosines / (kPiD * double(r) * r);
        const double error = worstChannelError(shared, expected);
        INFO("case " << k << ": expected " << expected.r << " " << expected.g << " " << expected.b << ", got "
                     << shared.r << " " << shared.g << " " << shared.b);
        CHECK(error < 0.04);
        worst = std::max(worst, error);
    }
    MEASURED("vsglRadiance vs quadrature of its SG integrand: worst channel error / brightest channel " << worst);
    // Measured 1.4e-2 over the 24 cases (the ASG x SG product form, MATH 4.9); the loop allows 4e-2.
}

TEST_CASE("vsglRadiance of a diffuse light on a diffuse receiver is the closed form", "[sg][vsgl][numbers]")
{
    // rho_s/pi Phi rho_d/pi cos cos Omega/(pi r^2) (1 - e^{-8 pi/Omega}) (MATH 4.10, both diffuse);
    // with the bias reduction the factor in () is absent (MATH 5.4).
    std::mt19937 engine(7u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    double worst = 0.0, worstCancelled = 0.0;
    for (int k = 0; k < 400; ++k) {
        const VSGLShadingPoint s = makePoint(
            glm::vec3(unit(engine), unit(engine), 0.0f), n, glm::normalize(glm::vec3(unit(engine), 0.0f, 1.0f)),
            glm::vec3(unit(engine), unit(engine), unit(engine)), glm::vec3(0.0f), unit(engine));
        glm::vec3 towards = randomUnit(engine);
        towards.z = std::abs(towards.z) + 0.05f;
        towards = glm::normalize(towards);
        const float d = k % 50 == 0 ? 0.0f : std::pow(10.0f, -3.0f + 4.0f * unit(engine));
        const float ratio = std::pow(10.0f, -4.0f + 5.0f * unit(engine)); // r/d from 1e-4 to 10
        const float r2 = d > 0.0f ? ratio * ratio * d * d : 0.01f;
        const glm::vec3 lightNormal = glm::normalize(-towards + 0.6f * randomUnit(engine));
        const VSGLight l =
            makeLight(s.position + d * towards, r2, lightNormal, glm::vec3(1.0f, 2.0f, 3.0f),
                      glm::vec3(unit(engine), unit(engine), unit(engine)), glm::vec3(0.0f), 0.5f, lightNormal);
        const glm::vec3 w = d > 0.0f ? glm::normalize(glm::vec3(l.positionRadius2) - s.position) : n;
        const double cosines = std::max(0.0f, glm::dot(w, n)) * std::max(0.0f, -glm::dot(w, lightNormal));
        const double dd = glm::length(glm::dvec3(glm::vec3(l.positionRadius2)) - glm::dvec3(s.position));
        const double sd = std::sqrt(dd * dd + r2), omegaOverArea = 2.0 / (sd * (sd + dd));
        const double omega = kPiD * r2 * omegaOverArea;
        const glm::dvec3 exact = glm::dvec3(s.diffuse) / kPiD * glm::dvec3(glm::vec3(l.flux) * glm::vec3(l.diffuse)) /
                                 kPiD * cosines * omegaOverArea;
        float cancelled = -1.0f;
        const glm::dvec3 sg = glm::dvec3(vsglRadiance(s, l, lightNormal, 0.0f, cancelled));
        CHECK(cancelled == 0.0f);
        const glm::dvec3 reduced = glm::dvec3(vsglRadiance(s, l, lightNormal, 1e-3f, cancelled));
        if (cosines <= 0.0) { // facing away: nothing, and nothing to pull out
            CHECK((sg == glm::dvec3(0.0) && reduced == glm::dvec3(0.0)));
            continue;
        }
        CHECK(cancelled == 1.0f); // eta_rho = 0: always pulled out
        worst = std::max(worst, worstChannelError(sg, exact * (1.0 - std::exp(-8.0 * kPiD / omega))));
        worstCancelled = std::max(worstCancelled, worstChannelError(reduced, exact));
    }
    MEASURED("diffuse-diffuse VSGL vs closed form: worst relative error " << worst << " (SG), " << worstCancelled
                                                                          << " (bias reduction)");
    CHECK(worst < 1e-6);          // measured 4.4e-7: float rounding (d from 1e-3 to 10, r/d from 1e-4 to 10)
    CHECK(worstCancelled < 1e-6); // measured 4.4e-7
}

TEST_CASE("vplRadiance of a diffuse VPL whose shading normal is tilted off its triangle is the one-bounce path "
          "tracer's closed form",
          "[sg][vpl][numbers]")
{
    // A diffuse VPL on a triangle of normal n_g, shaded with a normal-mapped n_s, lit from toLight,
    // seen from a diffuse receiver s: the one-bounce path tracer's radiance at s is
    // rho_s/pi * Phi (cos_s(in) / cos_g(in)) * rho_d/pi * cos(s) cos_g(out) / d^2 (sg.h, vplRadiance:
    // the flux Phi crossed the triangle, whose irradiance takes the shading cosine; the texel's area
    // is seen from s under the geometric cosine). With n_s = n_g it is the usual Phi f f cos cos / d^2.
    std::mt19937 engine(11u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    double worst = 0.0;
    int lit = 0, dropped = 0;
    for (int k = 0; k < 400; ++k) {
        const VSGLShadingPoint s = makePoint(glm::vec3(unit(engine), unit(engine), 0.0f), n,
                                             glm::normalize(glm::vec3(unit(engine), 0.0f, 1.0f)),
                                             glm::vec3(unit(engine), unit(engine), unit(engine)), glm::vec3(0.0f), 1.0f);
        glm::vec3 towards = randomUnit(engine);
        towards.z = std::abs(towards.z) + 0.05f;
        const glm::vec3 position = s.position + (0.2f + 2.0f * unit(engine)) * glm::normalize(towards);
        const glm::vec3 geometric = glm::normalize(-towards + 0.6f * randomUnit(engine));
        const glm::vec3 shading = glm::normalize(geometric + 0.5f * randomUnit(engine)); // the normal map's tilt
        glm::vec3 toLight = glm::normalize(geometric + 0.8f * randomUnit(engine));
        if (k % 4 == 0) toLight = glm::normalize(-geometric + 0.3f * randomUnit(engine)); // lit from behind: dropped
        VSGLight l = makeLight(position, 0.0f, shading, glm::vec3(1.0f, 2.0f, 3.0f),
                               glm::vec3(unit(engine), unit(engine), unit(engine)), glm::vec3(0.0f), 1.0f, toLight);
        l.geometric = glm::vec4(geometric, 0.0f);
        const glm::dvec3 got = glm::dvec3(vplRadiance(s, l, toLight, 0.0f));
        const glm::dvec3 toVPL = glm::dvec3(position) - glm::dvec3(s.position);
        const double d2 = glm::dot(toVPL, toVPL);
        const glm::dvec3 w = toVPL / std::sqrt(d2);
        const double cosS = glm::dot(w, glm::dvec3(n)), cosOut = -glm::dot(w, glm::dvec3(geometric));
        const double cosShadingIn = glm::dot(glm::dvec3(shading), glm::dvec3(toLight));
        const double cosGeometricIn = glm::dot(glm::dvec3(geometric), glm::dvec3(toLight));
        const double cosShadingOut = -glm::dot(w, glm::dvec3(shading));
        // The glTF BRDF at the VPL needs both directions above its shading normal; the path tracer
        // drops an exit below the triangle and an entry below the shading hemisphere.
        if (cosS <= 0.0 || cosOut <= 0.0 || cosShadingIn <= 0.0 || cosShadingOut <= 0.0 || cosGeometricIn <= 1e-3) {
            CHECK(got == glm::dvec3(0.0));
            ++dropped;
            continue;
        }
        const glm::dvec3 exact = glm::dvec3(s.diffuse) / kPiD * glm::dvec3(glm::vec3(l.flux)) *
                                 (cosShadingIn / cosGeometricIn) * glm::dvec3(glm::vec3(l.diffuse)) / kPiD * cosS *
                                 cosOut / d2;
        worst = std::max(worst, worstChannelError(got, exact));
        ++lit;
    }
    MEASURED("vplRadiance with n_s != n_g vs closed form: worst relative error " << worst << " over " << lit
                                                                               << " lit cases (" << dropped << " dropped)");
    CHECK(lit > 100);
    CHECK(dropped > 20);
    CHECK(worst < 1.5e-6); // measured 4.8e-7: float rounding against double
}

TEST_CASE("bias reduction: the cancelled VSGL is eq. (1) as r -> 0, and only smooth-enough lobes cancel",
          "[sg][vsgl][numbers]")
{
    std::mt19937 engine(33u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    double worstDiffuseLight = 0.0, worstGlossyLight = 0.0;
    int cancelledCount = 0, awayFromPeak = 0;
    for (int k = 0; k < 200; ++k) {
        const float viewAngle = degrees(70.0f * unit(engine));
        const VSGLShadingPoint s =
            makePoint(glm::vec3(0.0f), n, glm::vec3(std::sin(viewAngle), 0.0f, std::cos(viewAngle)),
                      glm::vec3(0.4f, 0.3f, 0.2f), glm::vec3(0.04f, 0.3f, 0.9f), 0.2f + 0.6f * unit(engine));
        glm::vec3 towards = randomUnit(engine);
        towards.z = std::abs(towards.z) + 0.1f;
        towards = glm::normalize(towards);
        const float d = 0.5f + 2.0f * unit(engine), r = 1e-3f * d;
        const glm::vec3 lightNormal = glm::normalize(-towards + 0.5f * randomUnit(engine));
        // The primary light's direction at the VSGL: anywhere above its surface; for every other
        // glossy light so that its lobe aims at the receiver (the SG fit's peak), for the rest away
        // from it, where the SG lobe and GGX differ by a large factor (issue "VSGL made exact", part 3:
        // with the light's SG lobe in this branch, as before, the worst error away from the peak was
        // of order 1).
        const bool glossyLight = k % 2 == 1;
        glm::vec3 toPrimary = randomUnit(engine);
        if (glm::dot(toPrimary, lightNormal) < 0.0f) toPrimary = -toPrimary;
        if (glossyLight && k % 4 == 1 && glm::dot(-towards, lightNormal) > 0.05f)
            toPrimary = glm::normalize(2.0f * glm::dot(lightNormal, -towards) * lightNormal + towards);
        const glm::vec3 mirror = 2.0f * glm::dot(lightNormal, toPrimary) * lightNormal - toPrimary;
        if (glossyLight && glm::dot(mirror, -towards) < std::cos(degrees(20.0f))) ++awayFromPeak;
        const VSGLight l = makeLight(d * towards, r * r, lightNormal, glm::vec3(1.0f, 0.7f, 0.4f), glm::vec3(0.5f),
                                     glossyLight ? glm::vec3(0.9f, 0.8f, 0.6f) : glm::vec3(0.0f),
                                     0.5f + 0.3f * unit(engine), toPrimary);
        float cancelled = -1.0f;
        const glm::dvec3 reduced = glm::dvec3(vsglRadiance(s, l, toPrimary, 1e-3f, cancelled));
        if (cancelled != 1.0f) continue;
        ++cancelledCount;
        const glm::dvec3 point = glm::dvec3(vplRadiance(s, l, toPrimary, 0.0f));
        if (point == glm::dvec3(0.0)) {
            CHECK(reduced == glm::dvec3(0.0));
            continue;
        }
        const double error = worstChannelError(reduced, point);
        (glossyLight ? worstGlossyLight : worstDiffuseLight) =
            std::max(glossyLight ? worstGlossyLight : worstDiffuseLight, error);
    }
    MEASURED("bias reduction at r/d = 1e-3 vs eq. (1) (vplRadiance): worst relative error "
             << worstDiffuseLight << " (diffuse lights), " << worstGlossyLight
             << " (glossy lights, " << awayFromPeak << " of them > 20 deg off their lobe's peak); " << cancelledCount
             << " of 200 cancelled");
    CHECK(cancelledCount == 200);    // eta_V = 4e6 here: alpha eta_V = 4000 exceeds every lobe's sharpness
    CHECK(awayFromPeak >= 40);       // most glossy lights are seen off their peak
    CHECK(worstDiffuseLight < 5e-6); // measured 2.1e-6: float rounding and 2 d^2/(s(s+d)) - 1 = -7.5e-7
    // Both ends exact GGX, as eq. (1): float rounding only, at and away from the lobe's peak.
    CHECK(worstGlossyLight < 5e-6);

    // biasAlpha = 0 never cancels; a sharp receiver lobe next to a wide cone does not cancel.
    const VSGLShadingPoint sharp = makePoint(glm::vec3(0.0f), n, glm::normalize(glm::vec3(0.3f, 0.0f, 1.0f)),
                                             glm::vec3(0.2f), glm::vec3(0.9f), 0.1f);
    const glm::vec3 towards = glm::normalize(glm::vec3(-0.3f, 0.0f, 1.0f));
    const VSGLight wide =
        makeLight(towards, 0.1f, -towards, glm::vec3(1.0f), glm::vec3(0.5f), glm::vec3(0.0f), 0.5f, -towards);
    float cancelled = -1.0f;
    vsglRadiance(sharp, wide, -towards, 1e-3f, cancelled);
    CHECK(cancelled == 0.0f);
    vsglRadiance(sharp, wide, -towards, 1e6f, cancelled);
    CHECK(cancelled == 1.0f);
    const VSGLight tiny =
        makeLight(towards, 1e-12f, -towards, glm::vec3(1.0f), glm::vec3(0.5f), glm::vec3(0.0f), 0.5f, -towards);
    vsglRadiance(sharp, tiny, -towards, 0.0f, cancelled);
    CHECK(cancelled == 0.0f);
}

TEST_CASE(
    "as r -> 0 without bias reduction the VSGL tends to its lobes at w_i over d^2, and to eq. (1) for smooth lobes",
    "[sg][vsgl][numbers]")
{
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    const glm::vec3 view = glm::normalize(glm::vec3(0.5f, 0.0f, 1.0f));
    const glm::vec3 towards = glm::normalize(glm::vec3(-0.4f, 0.1f, 1.0f)); // near the mirror direction of view
    const float d = 1.5f;
    const glm::vec3 lightNormal = glm::normalize(-towards + glm::vec3(0.2f, 0.0f, 0.0f));
    const glm::vec3 out = -towards;
    const glm::vec3 toPrimary = glm::normalize(2.0f * glm::dot(lightNormal, out) * lightNormal - out); // lobe aims at s
    double previous = 1e30, limitError = 0.0, pointError = 0.0;
    for (float roughness : {0.5f, 0.7f}) {
        const VSGLShadingPoint s = makePoint(glm::vec3(0.0f), n, view, glm::vec3(0.5f), glm::vec3(0.5f), roughness);
        previous = 1e30;
        for (float ratio : {1e-1f, 1e-2f, 1e-3f, 1e-4f}) {
            const VSGLight l = makeLight(d * towards, ratio * ratio * d * d, lightNormal, glm::vec3(1.0f),
                                         glm::vec3(0.5f), glm::vec3(0.5f), roughness, toPrimary);
            float cancelled = -1.0f;
            const glm::dvec3 sg = glm::dvec3(vsglRadiance(s, l, toPrimary, 0.0f, cancelled));
            const LobeProduct product(s, l, towards);
            const double cosines = glm::dot(towards, n);
            const glm::dvec3 limit = product(toDouble(towards)) * cosines / (double(d) * d);
            const double error = worstChannelError(sg, limit);
            INFO("roughness " << roughness << ", r/d " << ratio << ": relative distance to the limit " << error);
            CHECK(error <= previous * 1.01 + 1e-6); // converges (float noise allowed at the end)
            previous = error;
            if (ratio == 1e-4f) {
                limitError = std::max(limitError, error);
                const glm::dvec3 point = glm::dvec3(vplRadiance(s, l, toPrimary, 0.0f));
                pointError = std::max(pointError, worstChannelError(sg, point));
            }
        }
    }
    MEASURED("r/d = 1e-4, no bias reduction: relative distance to the SG lobes at w_i / d^2 "
             << limitError << ", to eq. (1) with exact GGX (roughness 0.5 and 0.7 at both ends) " << pointError);
    CHECK(limitError < 4e-7); // measured 1.3e-7
    CHECK(pointError < 0.18); // measured 7.2e-2: the SG fits of GGX at both ends, pointwise
}

TEST_CASE("degenerate inputs give finite radiance: zero normals, zero flux, r = 0, d = 0, invalid lights", "[sg][vsgl]")
{
    const glm::vec3 n(0.0f, 0.0f, 1.0f), zero(0.0f);
    const VSGLShadingPoint s =
        makePoint(zero, n, glm::normalize(glm::vec3(0.2f, 0.0f, 1.0f)), glm::vec3(0.5f), glm::vec3(0.5f), 0.4f);
    const VSGLight base = makeLight(glm::vec3(0.0f, 0.0f, 1.0f), 0.01f, -n, glm::vec3(1.0f), glm::vec3(0.5f),
                                    glm::vec3(0.5f), 0.4f, glm::normalize(glm::vec3(0.1f, 0.2f, -1.0f)));
    auto both = [&](const VSGLShadingPoint& point, const VSGLight& light, glm::vec3& sg, glm::vec3& reduced,
                    glm::vec3& vpl) {
        float cancelled = 0.0f;
        const glm::vec3 toPrimary = glm::normalize(glm::vec3(0.1f, 0.2f, -1.0f));
        sg = vsglRadiance(point, light, toPrimary, 0.0f, cancelled);
        reduced = vsglRadiance(point, light, toPrimary, 1e-3f, cancelled);
        vpl = vplRadiance(point, light, toPrimary, 0.0f);
        return finite(sg) && finite(reduced) && finite(vpl);
    };
    glm::vec3 sg, reduced, vpl;
    REQUIRE(both(s, base, sg, reduced, vpl));
    CHECK(sg.g > 0.0f);
    CHECK(vpl.g > 0.0f);

    VSGLight l = base;
    l.normalValid.w = 0.0f; // empty slot
    REQUIRE(both(s, l, sg, reduced, vpl));
    CHECK((sg == zero && reduced == zero && vpl == zero));

    VSGLShadingPoint p = s;
    p.normal = zero;
    REQUIRE(both(p, base, sg, reduced, vpl));
    CHECK((sg == zero && reduced == zero && vpl == zero));

    p = s;
    p.view = zero;
    REQUIRE(both(p, base, sg, reduced, vpl));
    CHECK((sg == zero && reduced == zero && vpl == zero));

    l = base;
    l.normalValid = glm::vec4(zero, 1.0f);
    l.geometric = glm::vec4(zero, 0.0f);
    REQUIRE(both(s, l, sg, reduced, vpl));
    CHECK((sg == zero && reduced == zero && vpl == zero));

    l = base;
    l.flux = glm::vec4(0.0f);
    REQUIRE(both(s, l, sg, reduced, vpl));
    CHECK((sg == zero && reduced == zero && vpl == zero));

    l = base;
    l.lobe = glm::vec4(0.0f); // an empty lobe (a zero Toksvig vector decodes to sharpness 0)
    l.specular.w = 0.0f;
    REQUIRE(both(s, l, sg, reduced, vpl));

    // r = 0: finite, and the SG result is the limit of the previous test (eq. 1 with the fitted lobes).
    l = base;
    l.positionRadius2.w = 0.0f;
    REQUIRE(both(s, l, sg, reduced, vpl));
    CHECK(sg.g > 0.0f);
    l.positionRadius2.w = -1.0f; // negative variance from float cancellation upstream: read as 0
    glm::vec3 negative;
    REQUIRE(both(s, l, negative, reduced, vpl));
    CHECK(negative == sg);

    // d = 0, r > 0: w_i = n_s; a light in the receiver's plane (n_i = n_s) gives 0, one facing it
    // the closed form with cos = 1 and Omega = 2 pi (2 (1 - e^{-4}) / r^2 for the SG).
    l = base;
    l.positionRadius2 = glm::vec4(zero, 0.04f);
    l.normalValid = glm::vec4(n, 1.0f);
    l.geometric = glm::vec4(n, 0.0f);
    REQUIRE(both(s, l, sg, reduced, vpl));
    CHECK((sg == zero && reduced == zero && vpl == zero));
    l.normalValid = glm::vec4(-n, 1.0f);
    l.geometric = glm::vec4(-n, 0.0f);
    l.specular = glm::vec4(0.0f);
    VSGLShadingPoint matte = s;
    matte.f0 = zero;
    REQUIRE(both(matte, l, sg, reduced, vpl));
    CHECK(vpl == zero); // eq. (1) has no direction at d = 0
    const double expected = 0.5 / kPiD * 0.5 / kPiD * 2.0 / 0.04 * (1.0 - std::exp(-4.0));
    CHECK(sg.g == Approx(expected).epsilon(1e-6));

    // d = 0 and r = 0: nothing.
    l.positionRadius2 = glm::vec4(zero, 0.0f);
    REQUIRE(both(s, l, sg, reduced, vpl));
    CHECK((sg == zero && reduced == zero && vpl == zero));

    // The light-side lobe for a zero normal or light from below reflects nothing; no NaN.
    for (const glm::vec3& normal : {zero, -n}) {
        const SpecularLobe lobe = ggxReflectionLobe(normal, n, 0.5f);
        CHECK(lobe.integral == 0.0f);
        CHECK(std::isfinite(lobe.sharpness));
        CHECK(finite(lobe.axis));
    }
    // Grazing incidence stays finite; so does the receiver lobe at a grazing view.
    const SpecularLobe grazing = ggxReflectionLobe(n, glm::normalize(glm::vec3(1.0f, 0.0f, 1e-7f)), 0.0f);
    CHECK((std::isfinite(grazing.sharpness) && std::isfinite(grazing.integral)));
    p = s;
    p.view = glm::normalize(glm::vec3(1.0f, 0.0f, 1e-7f));
    p.roughness = 0.0f;
    REQUIRE(both(p, base, sg, reduced, vpl));
}

TEST_CASE("Toksvig encoding round trip, and an average of two lobes decodes to a wider lobe", "[sg][numbers]")
{
    const glm::vec3 axis = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
    double worst = 0.0;
    for (float eta : {0.0f, 0.5f, 1.0f, 10.0f, 100.0f, 1e3f, 1e4f, 1e5f}) {
        glm::vec3 decodedAxis;
        float decoded = -1.0f;
        toksvigDecode(toksvigEncode(axis, eta), decodedAxis, decoded);
        INFO("eta " << eta << " decodes to " << decoded);
        if (eta > 0.0f) CHECK(glm::length(decodedAxis - axis) < 1e-6f); // eta = 0 encodes no axis
        // Float: r = eta/(1+eta) is rounded by ~6e-8, so 1 - r = 1/(1+eta) by 6e-8 (1+eta) relative.
        const double error = std::abs(decoded - eta) / std::max(1.0, double(eta)) / std::max(1.0, double(eta));
        worst = std::max(worst, error);
    }
    MEASURED("Toksvig round trip: worst relative sharpness error / max(1, eta) " << worst);
    CHECK(worst < 3e-7); // measured 1.3e-7 (at eta = 1e5: 1.3% there)
    // A zero vector is the constant lobe; |v| >= 1 is held at eta ~ 1e6.
    glm::vec3 decodedAxis;
    float decoded = -1.0f;
    toksvigDecode(glm::vec3(0.0f), decodedAxis, decoded);
    CHECK((decoded == 0.0f && glm::length(decodedAxis) == Approx(1.0f)));
    toksvigDecode(glm::vec3(0.0f, 2.0f, 0.0f), decodedAxis, decoded);
    CHECK((std::isfinite(decoded) && decoded > 9e5f && decoded < 1.1e6f && decodedAxis == glm::vec3(0.0f, 1.0f, 0.0f)));
    // Mip-mapping two lobes of sharpness 100, 20 deg apart: the mean vector is r cos(10 deg) along the
    // bisector, so eta' = r' / (1 - r') (MATH 4.8), far below 100.
    const glm::vec3 a = tiltedFrom(glm::vec3(0.0f, 0.0f, 1.0f), degrees(10.0f));
    const glm::vec3 b = glm::vec3(-a.x, -a.y, a.z);
    toksvigDecode(0.5f * (toksvigEncode(a, 100.0f) + toksvigEncode(b, 100.0f)), decodedAxis, decoded);
    const double meanLength = 100.0 / 101.0 * std::cos(10.0 * kPiD / 180.0);
    CHECK(decoded == Approx(meanLength / (1.0 - meanLength)).epsilon(1e-4));
    CHECK(decoded < 50.0f);
    CHECK(glm::length(decodedAxis - glm::vec3(0.0f, 0.0f, 1.0f)) < 1e-6f);
}

TEST_CASE("VSGL mip level h = 1/2 log2(k / (N P_j)) (MATH 5.2), clamped", "[sg]")
{
    const float uniform = 1.0f / (256.0f * 256.0f);
    CHECK(vsglMipLevel(1024.0f, uniform, 4.0f, 9) == 4.0f); // the paper's N, k and 256^2 RSM: 16 x 16 texels
    CHECK(vsglMipLevel(1024.0f, 4.0f * uniform, 4.0f, 9) == Approx(3.0f));
    CHECK(vsglMipLevel(1024.0f, 0.25f * uniform, 4.0f, 9) == Approx(5.0f));
    CHECK(vsglMipLevel(1024.0f, 2.0f * uniform, 4.0f, 9) == Approx(3.5f));
    CHECK(vsglMipLevel(1024.0f, 1.0f, 4.0f, 9) == 0.0f);   // a certain texel: no filtering
    CHECK(vsglMipLevel(1024.0f, 1e-12f, 4.0f, 9) == 8.0f); // held at the top level (one texel)
    CHECK(vsglMipLevel(1024.0f, 0.0f, 4.0f, 9) == 8.0f);
    CHECK(vsglMipLevel(0.0f, uniform, 4.0f, 9) == 8.0f);
    CHECK(vsglMipLevel(1024.0f, uniform, 0.0f, 9) == 0.0f);
    // The expected total footprint of N draws covers the RSM k times: sum_j P_j N (k / (N P_j)) = k
    // texels^2 per texel, i.e. 4^h texels per draw: for uniform P, N 4^h = k W H.
    CHECK(1024.0f * std::pow(4.0f, vsglMipLevel(1024.0f, uniform, 4.0f, 9)) == Approx(4.0f * 65536.0f));
}

namespace {

// GGX written out in double (brdf.h's model, F = 1): the NDF and the height-correlated Smith term.
double ggxD(double NoH, double alpha)
{
    const double a2 = alpha * alpha, d = NoH * NoH * (a2 - 1.0) + 1.0;
    return a2 / (kPiD * d * d);
}

double ggxV(double NoV, double NoL, double alpha)
{
    const double a2 = alpha * alpha;
    return 0.5 / (NoL * std::sqrt(NoV * NoV * (1.0 - a2) + a2) + NoV * std::sqrt(NoL * NoL * (1.0 - a2) + a2));
}

// Relative errors of an approximation against the exact function: of the integral, and the L2
// norm of the difference over the L2 norm of the exact function (both over the sphere).
struct FitError {
    double integral = 0.0, l2 = 0.0;
};

struct FitSums {
    double exact = 0.0, exact2 = 0.0, approx = 0.0, difference2 = 0.0;
    FitError error() const { return {approx / exact - 1.0, std::sqrt(difference2 / exact2)}; }
};

} // namespace

TEST_CASE("GGX to SG fit: NDF and specular-lobe errors per roughness and view", "[sg][ggx][numbers]")
{
    // Two NDF sharpness mappings in use (MATH 4.6): A = 2/alpha^2, B = 2/alpha^2 - 2. The NDF SG is
    // D(h) ~= 1/(pi alpha^2) G(h; n, eta); its integral error is that of int D (n.h) dh = 1.
    // The specular lobe f_spec(v, w) cos(theta_w) (F = 1) against its SG warp (the light side,
    // ggxWarpedSGLobe) and its ASG warp (the shading point, ggxWarpedASGLobe), times the exact cosine.
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    auto mappingA = [](float alpha) { return 2.0f / (alpha * alpha); };
    auto mappingB = [](float alpha) { return 2.0f / (alpha * alpha) - 2.0f; };
    double scoreA = 0.0, scoreB = 0.0, worstNDFB = 0.0, worstSGB = 0.0, worstASGB = 0.0, worstASGIntegralB = 0.0;
    int chosenMatchesB = 0;
    MEASURED("GGX NDF as SG | roughness | A: integral err | A: L2 | B: integral err | B: L2");
    for (int step = 1; step <= 9; ++step) {
        const float roughness = 0.1f * step;
        const float alpha = std::max(roughness * roughness, kMinAlpha);
        if (ggxNDFSharpness(alpha) == mappingB(alpha)) ++chosenMatchesB;
        const float etas[2] = {mappingA(alpha), mappingB(alpha)};
        FitSums ndf[2];
        for (int m = 0; m < 2; ++m) {
            // One pass for the four sums: exact, exact^2, approximation, difference^2 (all over n.h > 0).
            const glm::dvec4 sums = integrateSphereAbout<glm::dvec4>(
                glm::dvec3(0, 0, 1),
                [&](const glm::dvec3& h) {
                    if (h.z <= 0.0) return glm::dvec4(0.0);
                    const double exact = ggxD(h.z, alpha);
                    const double approx = std::exp(etas[m] * (h.z - 1.0)) / (kPiD * alpha * alpha);
                    return glm::dvec4(exact * h.z, exact * exact, approx * h.z, (approx - exact) * (approx - exact));
                },
                3000, 4);
            ndf[m] = FitSums{sums.x, sums.y, sums.z, sums.w};
        }
        const FitError a = ndf[0].error(), b = ndf[1].error();
        MEASURED("GGX NDF as SG | " << roughness << " | " << a.integral << " | " << a.l2 << " | " << b.integral << " | "
                                    << b.l2);
        scoreA += std::abs(a.integral) + a.l2;
        scoreB += std::abs(b.integral) + b.l2;
        worstNDFB = std::max({worstNDFB, std::abs(b.integral), b.l2});
    }
    MEASURED("GGX lobe f cos | roughness | view deg | SG warp A: integral err, L2 | SG warp B: integral err, L2 | "
             "ASG warp A: integral err, L2 | ASG warp B: integral err, L2");
    for (int step = 1; step <= 9; ++step) {
        const float roughness = 0.1f * step;
        const float alpha = std::max(roughness * roughness, kMinAlpha);
        for (float viewDegrees : {0.0f, 30.0f, 60.0f}) {
            const glm::vec3 view(std::sin(degrees(viewDegrees)), 0.0f, std::cos(degrees(viewDegrees)));
            const glm::dvec3 v = toDouble(view);
            SpecularLobe sgLobes[2];
            ASGLobe asgLobes[2];
            SGLobe normalised[2];
            for (int m = 0; m < 2; ++m) {
                const float eta = m == 0 ? mappingA(alpha) : mappingB(alpha);
                sgLobes[m] = ggxWarpedSGLobe(n, view, alpha, eta);
                asgLobes[m] = ggxWarpedASGLobe(n, view, alpha, eta);
                normalised[m] = sgNormalised(sgLobes[m].axis, sgLobes[m].sharpness);
            }
            auto exactLobe = [&](const glm::dvec3& w) {
                if (w.z <= 0.0) return 0.0;
                const glm::dvec3 h = glm::normalize(v + w);
                return ggxD(h.z, alpha) * ggxV(v.z, w.z, alpha) * w.z;
            };
            auto approximation = [&](int k, const glm::dvec3& w) { // k: 0, 1 SG warp A, B; 2, 3 ASG warp A, B
                if (w.z <= 0.0) return 0.0;
                return (k < 2 ? sgLobes[k].integral * sgReference(normalised[k], w)
                              : asgReference(asgLobes[k - 2], w)) *
                       w.z;
            };
            const glm::dvec3 mirror = toDouble(sgLobes[1].axis);
            FitSums sums[4];
            for (int k = 0; k < 4; ++k) {
                const glm::dvec4 q = integrateSphereAbout<glm::dvec4>(
                    mirror,
                    [&](const glm::dvec3& w) {
                        const double exact = exactLobe(w), approx = approximation(k, w);
                        return glm::dvec4(exact, exact * exact, approx, (approx - exact) * (approx - exact));
                    },
                    2000, 256);
                sums[k] = FitSums{q.x, q.y, q.z, q.w};
            }
            FitError e[4];
            for (int k = 0; k < 4; ++k)
                e[k] = sums[k].error();
            MEASURED("GGX lobe f cos | " << roughness << " | " << viewDegrees << " | " << e[0].integral << ", "
                                         << e[0].l2 << " | " << e[1].integral << ", " << e[1].l2 << " | "
                                         << e[2].integral << ", " << e[2].l2 << " | " << e[3].integral << ", "
                                         << e[3].l2);
            scoreA += std::abs(e[0].integral) + e[0].l2 + std::abs(e[2].integral) + e[2].l2;
            scoreB += std::abs(e[1].integral) + e[1].l2 + std::abs(e[3].integral) + e[3].l2;
            worstSGB = std::max({worstSGB, std::abs(e[1].integral), e[1].l2});
            worstASGB = std::max(worstASGB, e[3].l2);
            worstASGIntegralB = std::max(worstASGIntegralB, std::abs(e[3].integral));
        }
    }
    MEASURED("GGX to SG fit: summed |integral error| + L2 over all rows: A (2/alpha^2) "
             << scoreA << ", B (2/alpha^2 - 2) " << scoreB << "; worst of B: NDF " << worstNDFB << ", SG warp "
             << worstSGB << ", ASG warp L2 " << worstASGB << ", ASG warp integral " << worstASGIntegralB);
    CHECK(chosenMatchesB == 9); // ggxNDFSharpness is mapping B ...
    CHECK(scoreB < scoreA);     // ... because it measures better
    // Measured worst of mapping B over the table: 0.28 (NDF L2; the Gaussian has no GGX tail), 0.47
    // (SG warp L2 at 60 deg), 0.52 (ASG warp L2) and 0.43 (ASG warp integral at roughness 0.9: the
    // ASG's clamped cosine about its axis cuts a broad lobe); bounds about 2x.
    CHECK(worstNDFB < 0.6);
    CHECK(worstSGB < 1.0);
    CHECK(worstASGB < 1.1);
    CHECK(worstASGIntegralB < 0.9);
}
