// The LightSkin + BRSM maths (glsl/shared/lightskin.h) against closed forms, quadrature, brute force
// and Monte Carlo. References are written out here in double from the definitions (MATH.md 9), not
// taken from the code under test. Every tolerance is 2-3x the measured error, which the test prints
// ("measured: ..." lines; `ctest -L numbers --verbose`, or run
// `build/tests/vplgi_tests_cpu "[lightskin]"`).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "core/util/importance_table.h"
#include "glsl/shared/lightskin.h"
#include "glsl/shared/lightskin_gpu.h"
#include "glsl/shared/tonemap.h"
#include "measured.h"
#include "sphere_quadrature.h"

using namespace vplgi;
using namespace vplgi::shared;

namespace {

constexpr double kPiD = 3.14159265358979323846;

double radians(double degrees)
{
    return degrees * kPiD / 180.0;
}

glm::vec3 randomUnit(std::mt19937& engine)
{
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const float z = 2.0f * unit(engine) - 1.0f, phi = 2.0f * static_cast<float>(kPiD) * unit(engine);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
}

// A unit vector in the hemisphere about n.
glm::vec3 randomAbove(std::mt19937& engine, const glm::vec3& n)
{
    const glm::vec3 w = randomUnit(engine);
    return glm::dot(w, n) < 0.0f ? -w : w;
}

double relativeError(double got, double expected)
{
    return std::abs(got - expected) / std::abs(expected);
}

// The largest relative error over the channels of an rgb value, relative to its brightest channel.
double relativeError(const glm::dvec3& got, const glm::dvec3& expected)
{
    const double scale = std::max({std::abs(expected.x), std::abs(expected.y), std::abs(expected.z)});
    const glm::dvec3 d = glm::abs(got - expected);
    return std::max({d.x, d.y, d.z}) / scale;
}

// Area of the planar quadrilateral a b c d (in order): half the length of the cross product of its
// diagonals.
double quadArea(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d)
{
    return 0.5 * glm::length(glm::cross(c - a, d - b));
}

// One VAL as the estimators see it.
struct Val {
    glm::vec3 position, normal, flux;
    float area = 0.0f;
};

// Eq. (3)'s term for one VAL at x, written out in double from MATH 9.2 (not from the header).
glm::dvec3 diffuseTermReference(const Val& v, const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& rho)
{
    const glm::dvec3 toVal = glm::dvec3(v.position) - x;
    const double d2 = glm::dot(toVal, toVal);
    const glm::dvec3 w = toVal / std::sqrt(d2);
    const double cosL = std::max(-glm::dot(glm::dvec3(v.normal), w), 0.0);
    const double cosX = std::max(glm::dot(n, w), 0.0);
    return glm::dvec3(v.flux) * rho / kPiD * cosL * cosX / (double(v.area) + kPiD * d2);
}

// Eq. (4)'s term, written out in double.
glm::dvec3 glossyTermReference(const Val& v, const glm::dvec3& x, const glm::dvec3& n, const glm::dvec3& view,
                               const glm::dvec3& rho, double k)
{
    const glm::dvec3 toVal = glm::dvec3(v.position) - x;
    const double d2 = glm::dot(toVal, toVal);
    const glm::dvec3 w = toVal / std::sqrt(d2);
    const double cosL = std::max(-glm::dot(glm::dvec3(v.normal), w), 0.0);
    const double cosX = std::max(glm::dot(n, w), 0.0);
    const glm::dvec3 mirror = 2.0 * glm::dot(n, w) * n - w;
    const double cosE = std::max(glm::dot(view, mirror), 0.0);
    return glm::dvec3(v.flux) * rho * ((k + 2.0) / (2.0 * kPiD) * std::pow(cosE, k)) * cosL * cosX /
           (double(v.area) + kPiD * d2);
}

// A receiver with VALs on a 6 x 6 m patch 1-4 m above it, facing down more or less, with areas of a
// 1024^2 RSM's texels and fluxes of a few watts per channel.
struct ValScene {
    glm::vec3 receiverPosition{0.0f, 0.0f, 0.0f};
    glm::vec3 receiverNormal{0.0f, 0.0f, 1.0f};
    glm::vec3 view{0.0f, 0.0f, 1.0f};
    glm::vec3 diffuse{0.7f, 0.5f, 0.3f};
    glm::vec3 glossy{0.9f, 0.8f, 0.6f};
    float phongExponent = 12.0f;
    std::vector<Val> vals;
};

ValScene makeValScene(int count, std::uint32_t seed)
{
    std::mt19937 engine(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    ValScene s;
    s.view = glm::normalize(glm::vec3(0.3f, -0.2f, 1.0f));
    for (int i = 0; i < count; ++i) {
        Val v;
        v.position = glm::vec3(6.0f * unit(engine) - 3.0f, 6.0f * unit(engine) - 3.0f, 1.0f + 3.0f * unit(engine));
        v.normal = glm::normalize(glm::vec3(0.0f, 0.0f, -1.0f) + 0.7f * randomUnit(engine));
        v.flux = glm::vec3(0.5f + 3.0f * unit(engine), 0.5f + 3.0f * unit(engine), 0.5f + 3.0f * unit(engine));
        v.area = 0.001f + 0.05f * unit(engine);
        s.vals.push_back(v);
    }
    return s;
}

glm::dvec3 diffuseTerm(const ValScene& s, const Val& v, float selectionExpectation)
{
    return glm::dvec3(valDiffuseRadiance(v.flux, v.position, v.normal, v.area, s.receiverPosition, s.receiverNormal,
                                         s.diffuse, selectionExpectation));
}

glm::dvec3 glossyTerm(const ValScene& s, const Val& v, float selectionExpectation)
{
    return glm::dvec3(valGlossyRadiance(v.flux, v.position, v.normal, v.area, s.receiverPosition, s.receiverNormal,
                                        s.view, s.glossy, s.phongExponent, selectionExpectation));
}

} // namespace

// --- Eq. (1) ---------------------------------------------------------------------------------------

TEST_CASE("LightSkin eq. (1): the VAL area is the texel's footprint on a plane across the light axis",
          "[lightskin][numbers]")
{
    // A perspective light (not square, to keep P00 and P11 apart) and an orthographic one, both
    // RSMs not square either. texelFactor as RSMView computes it (gl/passes/rsm_pass.cpp).
    const int width = 256, height = 128;
    const glm::dmat4 perspective = glm::perspective(radians(70.0), 1.4, 0.05, 200.0);
    const glm::dmat4 orthographic = glm::ortho(-15.0, 15.0, -10.0, 10.0, 0.1, 300.0);
    double worstPerspective = 0.0, worstOrthographic = 0.0, worstTiltedPerspective = 0.0, worstTiltedOrthographic = 0.0;
    double paperOnTilted = 0.0; // eq. (1) alone on the tilted plane
    for (int kind = 0; kind < 2; ++kind) {
        const bool ortho = kind == 1;
        const glm::dmat4 clipFromView = ortho ? orthographic : perspective;
        const glm::dmat4 viewFromClip = glm::inverse(clipFromView);
        const float texelFactor =
            static_cast<float>(4.0 / (clipFromView[0][0] * clipFromView[1][1] * double(width) * double(height)));
        // The ray through NDC (x, y): origin and direction in view space (exact inverse, in double).
        auto ray = [&](double x, double y, glm::dvec3& origin, glm::dvec3& direction) {
            const glm::dvec4 nearPoint = viewFromClip * glm::dvec4(x, y, -1.0, 1.0);
            const glm::dvec4 farPoint = viewFromClip * glm::dvec4(x, y, 1.0, 1.0);
            origin = glm::dvec3(nearPoint) / nearPoint.w;
            direction = glm::normalize(glm::dvec3(farPoint) / farPoint.w - origin);
        };
        for (const glm::ivec2 texel :
             {glm::ivec2(0, 0), glm::ivec2(128, 64), glm::ivec2(255, 127), glm::ivec2(17, 101), glm::ivec2(200, 3)}) {
            const double x0 = 2.0 * texel.x / width - 1.0, x1 = 2.0 * (texel.x + 1) / width - 1.0;
            const double y0 = 2.0 * texel.y / height - 1.0, y1 = 2.0 * (texel.y + 1) / height - 1.0;
            for (double depth : {0.5, 3.0, 40.0}) {
                // Plane z = -depth (across the axis), and the same plane point with a normal tilted by
                // 50 degrees towards x and y (the real, tilted surface of MATH 9.1).
                glm::dvec3 centreOrigin, centreDirection;
                ray(0.5 * (x0 + x1), 0.5 * (y0 + y1), centreOrigin, centreDirection);
                const glm::dvec3 planePoint =
                    centreOrigin + centreDirection * ((-depth - centreOrigin.z) / centreDirection.z);
                for (int tilted = 0; tilted < 2; ++tilted) {
                    const glm::dvec3 planeNormal =
                        tilted
                            ? glm::normalize(glm::dvec3(std::sin(radians(50.0)) * glm::normalize(glm::dvec2(1.0, 0.6)),
                                                        std::cos(radians(50.0))))
                            : glm::dvec3(0.0, 0.0, 1.0);
                    glm::dvec3 corners[4];
                    const glm::dvec2 ndc[4] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
                    for (int c = 0; c < 4; ++c) {
                        glm::dvec3 origin, direction;
                        ray(ndc[c].x, ndc[c].y, origin, direction);
                        const double t = glm::dot(planePoint - origin, planeNormal) / glm::dot(direction, planeNormal);
                        corners[c] = origin + t * direction;
                    }
                    const double exact = quadArea(corners[0], corners[1], corners[2], corners[3]);
                    const float area = lightskinValArea(static_cast<float>(depth), texelFactor, ortho);
                    if (!tilted) {
                        double& worst = ortho ? worstOrthographic : worstPerspective;
                        worst = std::max(worst, relativeError(area, exact));
                    } else {
                        // Angles at the texel centre: to the light axis (-z) and to the surface normal.
                        const float cosAxis = static_cast<float>(-centreDirection.z);
                        const float cosSurface = static_cast<float>(std::abs(glm::dot(centreDirection, planeNormal)));
                        const float tiltedArea = lightskinValAreaTilted(area, cosAxis, cosSurface);
                        INFO("tilted, " << (ortho ? "orthographic" : "perspective") << " texel " << texel.x << ","
                                        << texel.y << " depth " << depth);
                        double& worst = ortho ? worstTiltedOrthographic : worstTiltedPerspective;
                        worst = std::max(worst, relativeError(tiltedArea, exact));
                        paperOnTilted = std::max(paperOnTilted, relativeError(area, exact));
                    }
                }
            }
        }
    }
    MEASURED("eq. (1) vs the exact texel footprint (relative): perspective "
             << worstPerspective << ", orthographic " << worstOrthographic << "; tilted 50 deg: perspective "
             << worstTiltedPerspective << ", orthographic " << worstTiltedOrthographic << " (eq. 1 alone there: up to "
             << paperOnTilted << ")");
    // Measured 6.1e-8 and 0 across the axis (float rounding: eq. 1 is exact there, MATH 9.1). On the
    // tilted plane, A cos(alpha)/cos(theta_s) at the texel centre is exact only for an infinitesimal
    // texel: 3.0e-4 (perspective: the texel's rays diverge across the tilted plane) and 3.3e-8
    // (orthographic: parallel rays, exact but for rounding).
    CHECK(worstPerspective < 2e-7);
    CHECK(worstOrthographic < 2e-7);
    CHECK(worstTiltedPerspective < 8e-4);
    CHECK(worstTiltedOrthographic < 1e-7);
    // The paper's A_disk alone is far off on the tilted plane (measured 0.73; MATH 9.1: 36-75% at
    // 50 deg), which is why the tilted form is offered.
    CHECK(paperOnTilted > 0.3);
}

// --- Disk form factor (MATH 9.2) -------------------------------------------------------------------

TEST_CASE("LightSkin disk form factor: exact on axis, measured off axis against quadrature", "[lightskin][numbers]")
{
    // On axis, a disk of radius a at distance d facing the receiver: a^2 / (d^2 + a^2).
    double worstOnAxis = 0.0;
    for (double ratio : {0.01, 0.1, 0.5, 1.0, 3.0}) {
        const double a = 0.4 * ratio, d = 0.4;
        const float f = diskFormFactor(static_cast<float>(kPiD * a * a), 1.0f, 1.0f, static_cast<float>(d * d));
        worstOnAxis = std::max(worstOnAxis, relativeError(f, a * a / (d * d + a * a)));
    }
    // Off axis: F = int_disk cos+ cos+ / (pi r^2) dA by the midpoint rule in (r^2, phi) on the disk
    // (equal-area cells; deterministic, so no Monte Carlo noise: 400 x 800 cells resolve it to ~1e-6).
    // The disk's centre is at distance d along +z; the receiver's normal tilts by thetaX towards x,
    // the disk's normal by thetaL away from -z towards y.
    MEASURED("disk form factor | a/d | theta_l deg | theta_x deg | quadrature | A cos cos/(A + pi d^2) | rel. error");
    double worstSmall = 0.0, worstLarge = 0.0;
    const double angles[5][2] = {{0.0, 0.0}, {40.0, 30.0}, {60.0, 0.0}, {0.0, 60.0}, {70.0, 70.0}};
    for (double ratio : {0.05, 0.1, 0.3, 0.5, 1.0}) {
        for (const auto& angle : angles) {
            const double d = 2.0, a = ratio * d;
            const glm::dvec3 centre(0.0, 0.0, d);
            const glm::dvec3 nx(std::sin(radians(angle[1])), 0.0, std::cos(radians(angle[1])));
            const glm::dvec3 nl(0.0, std::sin(radians(angle[0])), -std::cos(radians(angle[0])));
            // Tangents of the disk.
            const glm::dvec3 t = glm::normalize(glm::cross(nl, glm::dvec3(1.0, 0.0, 0.0)));
            const glm::dvec3 b = glm::cross(nl, t);
            const int rings = 400, sectors = 800;
            double sum = 0.0;
            for (int i = 0; i < rings; ++i) {
                const double r = a * std::sqrt((i + 0.5) / rings);
                for (int j = 0; j < sectors; ++j) {
                    const double phi = 2.0 * kPiD * (j + 0.5) / sectors;
                    const glm::dvec3 y = centre + r * (std::cos(phi) * t + std::sin(phi) * b);
                    const double dist2 = glm::dot(y, y);
                    const glm::dvec3 w = y / std::sqrt(dist2);
                    sum += std::max(glm::dot(nx, w), 0.0) * std::max(-glm::dot(nl, w), 0.0) / (kPiD * dist2);
                }
            }
            const double reference = sum * kPiD * a * a / (rings * sectors);
            const float approx =
                diskFormFactor(static_cast<float>(kPiD * a * a), static_cast<float>(std::cos(radians(angle[0]))),
                               static_cast<float>(std::cos(radians(angle[1]))), static_cast<float>(d * d));
            const double error = approx / reference - 1.0;
            MEASURED("disk form factor | " << ratio << " | " << angle[0] << " | " << angle[1] << " | " << reference
                                           << " | " << approx << " | " << error);
            double& worst = ratio <= 0.1 ? worstSmall : worstLarge;
            worst = std::max(worst, std::abs(error));
        }
    }
    MEASURED("disk form factor: on axis worst relative error " << worstOnAxis << "; off axis worst " << worstSmall
                                                               << " (a/d <= 0.1), " << worstLarge << " (a/d 0.3-1)");
    // Measured: 2.6e-8 on axis (float rounding of the exact closed form); off axis 0.0175 up to
    // a/d = 0.1 and 0.76 up to a/d = 1, always an underestimate here. The centre's cosines stand for
    // the whole disk: a disk facing the receiver stays exact however the receiver tilts (cos theta_x
    // is linear across it and averages to the centre's), a tilted disk does not (worst at 70/70
    // degrees, a/d = 1). The bound on the large disks is loose because an underestimate cannot
    // exceed 1; it catches a formula slip, not drift.
    CHECK(worstOnAxis < 1e-7);
    CHECK(worstSmall < 0.04);
    CHECK(worstLarge < 0.9);
}

// --- One VAL's radiance and the selected-subset estimator (eq. 3, 4, 14, 15; MATH 9.2, 9.9) ---------

TEST_CASE("LightSkin eq. (3) and (4) per VAL match the written-out formulas and the VPL limit", "[lightskin]")
{
    const ValScene s = makeValScene(200, 7u);
    const glm::dvec3 x(s.receiverPosition), n(s.receiverNormal), view(s.view);
    double worstDiffuse = 0.0, worstGlossy = 0.0;
    int lit = 0, glossyLit = 0;
    for (const Val& v : s.vals) {
        const glm::dvec3 diffuseRef = diffuseTermReference(v, x, n, glm::dvec3(s.diffuse));
        const glm::dvec3 glossyRef = glossyTermReference(v, x, n, view, glm::dvec3(s.glossy), s.phongExponent);
        const glm::dvec3 diffuse = diffuseTerm(s, v, 1.0f), glossy = glossyTerm(s, v, 1.0f);
        if (diffuseRef.x > 0.0) {
            ++lit;
            worstDiffuse = std::max(worstDiffuse, relativeError(diffuse, diffuseRef));
        } else {
            CHECK(diffuse == glm::dvec3(0.0));
        }
        if (glossyRef.x > 1e-6 * diffuseRef.x) {
            ++glossyLit;
            worstGlossy = std::max(worstGlossy, relativeError(glossy, glossyRef));
        }
        // A = 0: the VPL of a diffuse emitter, intensity Phi cos(theta_l)/pi, on a Lambertian receiver.
        Val point = v;
        point.area = 0.0f;
        const glm::dvec3 toVal = glm::dvec3(v.position) - x;
        const double d2 = glm::dot(toVal, toVal);
        const glm::dvec3 w = toVal / std::sqrt(d2);
        const glm::dvec3 vpl = glm::dvec3(v.flux) * std::max(-glm::dot(glm::dvec3(v.normal), w), 0.0) / kPiD *
                               glm::dvec3(s.diffuse) / kPiD * std::max(glm::dot(n, w), 0.0) / d2;
        if (vpl.x > 0.0) CHECK(relativeError(diffuseTerm(s, point, 1.0f), vpl) < 1e-5);
    }
    INFO("worst relative error: diffuse " << worstDiffuse << ", glossy " << worstGlossy);
    CHECK(lit > 100);
    CHECK(glossyLit > 30);
    // float against double: measured 1.4e-6 (diffuse) and 2.4e-6 (glossy: cos^12 multiplies the
    // cosine's rounding by 12).
    CHECK(worstDiffuse < 4e-6);
    CHECK(worstGlossy < 6e-6);

    // Degenerate inputs: P_VAL = 0, the VAL at the receiver, zero normals: 0, finite.
    const Val& v = s.vals[0];
    CHECK(diffuseTerm(s, v, 0.0f) == glm::dvec3(0.0));
    CHECK(glossyTerm(s, v, 0.0f) == glm::dvec3(0.0));
    CHECK(valDiffuseRadiance(v.flux, s.receiverPosition, v.normal, v.area, s.receiverPosition, s.receiverNormal,
                             s.diffuse, 1.0f) == glm::vec3(0.0f));
    CHECK(valGlossyRadiance(v.flux, v.position, glm::vec3(0.0f), 0.0f, s.receiverPosition, s.receiverNormal, s.view,
                            s.glossy, s.phongExponent, 1.0f) == glm::vec3(0.0f));
}

TEST_CASE("LightSkin glossy BRDF: (k+2)/(2 pi) cos^k normalises at normal incidence", "[lightskin]")
{
    // int phongBRDF(1, cos theta_e, k) cos(theta) dw over the hemisphere = 1 for light from the normal
    // (the mirror direction is the normal itself), MATH 9.2.
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    for (float k : {0.0f, 1.0f, 10.0f, 100.0f, 1000.0f}) {
        const double integral = test::integrateSphereAbout<double>(
            glm::dvec3(n),
            [&](const glm::dvec3& w) {
                if (w.z <= 0.0) return 0.0;
                return double(phongBRDF(glm::vec3(1.0f), static_cast<float>(w.z), k).x) * w.z;
            },
            2000, 8);
        INFO("k = " << k);
        // Measured within 1.3e-6 of 1 (float evaluation of pow at 2000 x 8 nodes).
        CHECK(integral == Approx(1.0).epsilon(5e-6));
    }
}

TEST_CASE("LightSkin eq. (14)/(15) equal eq. (3)/(4) when N draws each have probability 1/N", "[lightskin][numbers]")
{
    // Every VAL drawn once, per-draw probability 1/N: P_VAL = N (1/N) = 1 (MATH 9.9), so the
    // selected-subset sum is the full sum term by term.
    const ValScene s = makeValScene(50, 11u);
    const int n = static_cast<int>(s.vals.size());
    const float p = 1.0f / static_cast<float>(n);
    glm::dvec3 fullDiffuse(0.0), fullGlossy(0.0), subsetDiffuse(0.0), subsetGlossy(0.0), perDrawDiffuse(0.0);
    for (const Val& v : s.vals) {
        fullDiffuse += diffuseTerm(s, v, 1.0f);
        fullGlossy += glossyTerm(s, v, 1.0f);
        subsetDiffuse += diffuseTerm(s, v, valSelectionExpectation(static_cast<float>(n), p));
        subsetGlossy += glossyTerm(s, v, valSelectionExpectation(static_cast<float>(n), p));
        perDrawDiffuse += diffuseTerm(s, v, p); // the other reading: P_VAL = p
    }
    const double diffuseError = relativeError(subsetDiffuse, fullDiffuse);
    const double glossyError = relativeError(subsetGlossy, fullGlossy);
    MEASURED("eq. (14) vs eq. (3), all " << n << " VALs drawn once with p = 1/N: relative difference " << diffuseError
                                         << " (diffuse), " << glossyError << " (glossy)");
    REQUIRE(fullDiffuse.x > 0.0);
    REQUIRE(fullGlossy.x > 0.0);
    // Measured 0 and 0 (50 (1/50) rounds to exactly 1 in float; other N are 1 to within an ulp).
    CHECK(diffuseError < 2e-7);
    CHECK(glossyError < 2e-7);
    // Dividing by the per-draw p alone over-counts by N (MATH 9.9), which this test would catch.
    CHECK(perDrawDiffuse.x / fullDiffuse.x == Approx(n).epsilon(1e-5));
}

TEST_CASE("LightSkin eq. (14)/(15) under a non-uniform importance: the mean over selections is eq. (3)/(4)",
          "[lightskin][numbers]")
{
    // 50 VALs in a 10 x 5 importance map, importance from eq. (10) for a few view samples around the
    // receiver (non-uniform, and not proportional to the terms), plus a floor so that no VAL that
    // contributes has zero probability (eq. 14 is unbiased only then). N_sVAL = 16 draws per
    // selection, drawn by the CPU twin of the GPU sampler (core/util/importance_table.h).
    const ValScene s = makeValScene(50, 23u);
    const int width = 10, height = 5, drawCount = 16;
    const glm::vec3 viewSamples[3][2] = {{{0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}},
                                         {{2.5f, 0.5f, 0.0f}, {0.0f, 0.0f, 1.0f}},
                                         {{-1.0f, 2.0f, 0.5f}, glm::normalize(glm::vec3(0.3f, -0.4f, 1.0f))}};
    std::vector<float> importance;
    for (const Val& v : s.vals) {
        float sum = 0.0f;
        for (const auto& vs : viewSamples)
            sum += valImportance(luminanceRec709(v.flux), v.position, v.normal, vs[0], vs[1], kImportanceClampDistance);
        importance.push_back(sum / 3.0f + 0.02f);
    }
    const auto [lowest, highest] = std::minmax_element(importance.begin(), importance.end());
    const ImportanceTable table = buildImportanceTable(importance, width, height);

    glm::dvec3 exactDiffuse(0.0), exactGlossy(0.0);
    for (const Val& v : s.vals) {
        exactDiffuse += diffuseTerm(s, v, 1.0f);
        exactGlossy += glossyTerm(s, v, 1.0f);
    }
    const int selections = 20000;
    glm::dvec3 sumDiffuse(0.0), sumDiffuse2(0.0), sumGlossy(0.0), sumGlossy2(0.0);
    for (int k = 0; k < selections; ++k) {
        glm::dvec3 diffuse(0.0), glossy(0.0);
        for (const ImportanceSample& draw :
             sampleImportanceTable(table, drawCount, static_cast<std::uint32_t>(k + 1))) {
            const Val& v = s.vals[static_cast<std::size_t>(draw.y * width + draw.x)];
            const float expectation = valSelectionExpectation(static_cast<float>(drawCount), draw.probability);
            diffuse += diffuseTerm(s, v, expectation);
            glossy += glossyTerm(s, v, expectation);
        }
        sumDiffuse += diffuse;
        sumDiffuse2 += diffuse * diffuse;
        sumGlossy += glossy;
        sumGlossy2 += glossy * glossy;
    }
    const double m = selections;
    const glm::dvec3 meanDiffuse = sumDiffuse / m, meanGlossy = sumGlossy / m;
    // Standard errors of the means from the sample variances.
    const glm::dvec3 errorDiffuse = glm::sqrt((sumDiffuse2 / m - meanDiffuse * meanDiffuse) / (m - 1.0));
    const glm::dvec3 errorGlossy = glm::sqrt((sumGlossy2 / m - meanGlossy * meanGlossy) / (m - 1.0));
    const glm::dvec3 zDiffuse = glm::abs(meanDiffuse - exactDiffuse) / errorDiffuse;
    const glm::dvec3 zGlossy = glm::abs(meanGlossy - exactGlossy) / errorGlossy;
    MEASURED("eq. (14)/(15) Monte Carlo, "
             << selections << " selections of " << drawCount << " draws from 50 VALs "
             << "(importance " << *lowest << ".." << *highest << "): diffuse mean " << meanDiffuse.y << " vs eq. (3) "
             << exactDiffuse.y << " (standard error " << errorDiffuse.y << ", |z| " << zDiffuse.x << ", " << zDiffuse.y
             << ", " << zDiffuse.z << "); glossy mean " << meanGlossy.y << " vs eq. (4) " << exactGlossy.y
             << " (standard error " << errorGlossy.y << ", |z| " << zGlossy.x << ", " << zGlossy.y << ", " << zGlossy.z
             << ")");
    CHECK(*highest > 5.0f * *lowest); // the importance is far from uniform
    // The estimate varies from selection to selection (a test with zero variance could not fail)...
    CHECK(errorDiffuse.y > 1e-4 * exactDiffuse.y);
    CHECK(errorGlossy.y > 1e-4 * exactGlossy.y);
    // ... and its mean is eq. (3)/(4) within 4 standard errors per channel (two-sided; a 4-sigma miss
    // has probability 6e-5 per channel for an unbiased estimator; the seeds are fixed, so the
    // outcome is deterministic).
    for (int c = 0; c < 3; ++c) {
        CHECK(zDiffuse[c] < 4.0);
        CHECK(zGlossy[c] < 4.0);
    }
    // The per-draw p alone (no N_sVAL) would be N_sVAL = 16 times too bright: thousands of standard errors.
    CHECK(std::abs(drawCount * meanDiffuse.y - exactDiffuse.y) > 100.0 * errorDiffuse.y);
}

// --- Proxy lights (eq. 6, 7) -----------------------------------------------------------------------

TEST_CASE("LightSkin eq. (7): the isotropic point light Phi_p/(4 pi) at x_p reproduces the cache's radiance",
          "[lightskin][numbers]")
{
    std::mt19937 engine(5u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    double worst = 0.0;
    int checked = 0;
    for (int i = 0; i < 500; ++i) {
        const glm::vec3 c(10.0f * unit(engine), 10.0f * unit(engine), 10.0f * unit(engine));
        const glm::vec3 n = randomUnit(engine);
        const glm::vec3 xp = c + (0.2f + 5.0f * unit(engine)) * randomAbove(engine, n);
        const glm::vec3 radiance(3.0f * unit(engine), 3.0f * unit(engine), 3.0f * unit(engine));
        const glm::vec3 toProxy = xp - c;
        const float d2 = glm::dot(toProxy, toProxy);
        const glm::vec3 wi = toProxy / std::sqrt(d2);
        const float cosCache = glm::dot(n, wi);
        // Diffuse (rho_d/pi) for even i, the glossy Phong BRDF towards a view for odd i.
        glm::vec3 brdf;
        if (i % 2 == 0) {
            brdf = glm::vec3(unit(engine), unit(engine), unit(engine)) * kInvPi;
        } else {
            const glm::vec3 mirror = mirrorDirection(wi, n);
            const glm::vec3 view = glm::normalize(mirror + 0.4f * randomUnit(engine));
            brdf = phongBRDF(glm::vec3(unit(engine), unit(engine), unit(engine)), glm::dot(view, mirror), 20.0f);
        }
        const glm::vec3 flux = proxyFluxFromRadiance(radiance, d2, brdf, cosCache);
        // The point light written out: intensity Phi/(4 pi), radiance f I cos / d^2.
        for (int k = 0; k < 3; ++k) {
            if (!(brdf[k] > 1e-3f) || !(cosCache > 1e-3f)) continue;
            const double back = double(brdf[k]) * double(flux[k]) / (4.0 * kPiD) * double(cosCache) / double(d2);
            worst = std::max(worst, std::abs(back - radiance[k]) / radiance[k]);
            ++checked;
        }
        const glm::vec3 shaded = pointLightRadiance(flux, d2, brdf, cosCache);
        for (int k = 0; k < 3; ++k)
            if (brdf[k] > 1e-3f && cosCache > 1e-3f) CHECK(std::abs(shaded[k] - radiance[k]) <= 1e-5f * radiance[k]);
    }
    MEASURED("eq. (7) round trip through the isotropic point light: worst relative error " << worst << " over "
                                                                                           << checked << " channels");
    CHECK(checked > 1000);
    // Measured 2.0e-7 (float rounding of 4 pi d^2 / cos and back).
    CHECK(worst < 6e-7);

    // Guards (MATH 9.4): a zero BRDF channel or a cosine at or below 0 gives no flux, per channel.
    const glm::vec3 l(1.0f, 2.0f, 3.0f);
    CHECK(proxyFluxFromRadiance(l, 4.0f, glm::vec3(0.1f, 0.0f, 0.2f), 0.5f).y == 0.0f);
    CHECK(proxyFluxFromRadiance(l, 4.0f, glm::vec3(0.1f, 0.0f, 0.2f), 0.5f).x > 0.0f);
    CHECK(proxyFluxFromRadiance(l, 4.0f, glm::vec3(0.1f), 0.0f) == glm::vec3(0.0f));
    CHECK(proxyFluxFromRadiance(l, 4.0f, glm::vec3(0.1f), -0.3f) == glm::vec3(0.0f));
    CHECK(proxyFluxFromRadiance(l, 4.0f, glm::vec3(1e-9f), 0.5f) == glm::vec3(0.0f));
}

TEST_CASE("LightSkin eq. (5)/(6)/(13): proxy weights and the weighted position", "[lightskin]")
{
    // Eq. (6) as printed: epsilon + F, epsilon + cos^k F.
    CHECK(proxyWeightDiffuse(0.25f, kProxyWeightEpsilon) == 0.25f + kProxyWeightEpsilon);
    CHECK(proxyWeightGlossy(0.25f, 0.5f, 3.0f, 0.0f) == Approx(0.25 * 0.125).epsilon(1e-6));
    CHECK(proxyWeightGlossy(0.25f, -0.5f, 3.0f, 1e-6f) == 1e-6f);
    // With every form factor 0 the weights are epsilon and eq. (5) is still defined (the plain mean).
    CHECK(proxyWeightDiffuse(0.0f, kProxyWeightEpsilon) > 0.0f);
    // Eq. (13) = eq. (5) in expectation: with P_VAL = 1 for every VAL (each drawn once), the
    // weighted mean of the subset is the full eq. (5) mean exactly.
    const ValScene s = makeValScene(50, 31u);
    glm::dvec3 full(0.0), subset(0.0);
    double fullWeight = 0.0, subsetWeight = 0.0;
    for (const Val& v : s.vals) {
        const glm::vec3 toVal = v.position - s.receiverPosition;
        const float d2 = glm::dot(toVal, toVal);
        const glm::vec3 w = toVal / std::sqrt(d2);
        const float f = diskFormFactor(v.area, -glm::dot(v.normal, w), glm::dot(s.receiverNormal, w), d2);
        const float weight = proxyWeightDiffuse(f, kProxyWeightEpsilon);
        full += double(weight) * glm::dvec3(v.position);
        fullWeight += weight;
        const float expectation = valSelectionExpectation(50.0f, 1.0f / 50.0f);
        subset += double(weight / expectation) * glm::dvec3(v.position);
        subsetWeight += weight / expectation;
    }
    CHECK(glm::length(full / fullWeight - subset / subsetWeight) < 1e-6);
}

// --- Interpolation (eq. 8, 9) -----------------------------------------------------------------------

TEST_CASE("LightSkin eq. (8)/(9): weights over 16 caches sum to one and the farthest cache gets 0",
          "[lightskin][numbers]")
{
    std::mt19937 engine(17u);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    double worstSum = 0.0, worstConstant = 0.0;
    for (int trial = 0; trial < 200; ++trial) {
        const glm::vec3 x(unit(engine), unit(engine), unit(engine));
        const glm::vec3 n = randomUnit(engine);
        const float exponent = trial % 3 == 0 ? 2.0f : kInterpolationExponent;
        glm::vec3 caches[16], normals[16];
        float distances[16];
        float maxDistance = 0.0f;
        int farthest = 0;
        for (int i = 0; i < 16; ++i) {
            caches[i] = x + 0.8f * unit(engine) * randomUnit(engine);
            normals[i] = glm::normalize(n + 0.5f * randomUnit(engine));
            distances[i] = glm::length(caches[i] - x);
            if (distances[i] > maxDistance) {
                maxDistance = distances[i];
                farthest = i;
            }
        }
        float weights[16], sum = 0.0f;
        for (int i = 0; i < 16; ++i) {
            weights[i] = interpolationWeight(distances[i], maxDistance, exponent, glm::dot(n, normals[i]));
            sum += weights[i];
        }
        CHECK(weights[farthest] == 0.0f);
        REQUIRE(sum > 0.0f);
        // Eq. (9): normalised weights sum to one, and a constant proxy (same flux, same position at
        // every cache) is reproduced.
        double normalisedSum = 0.0, interpolated = 0.0;
        for (int i = 0; i < 16; ++i) {
            const float normalised = weights[i] / sum;
            CHECK(normalised >= 0.0f);
            CHECK(normalised <= 1.0f);
            normalisedSum += normalised;
            interpolated += double(normalised * 3.7f);
        }
        worstSum = std::max(worstSum, std::abs(normalisedSum - 1.0));
        worstConstant = std::max(worstConstant, std::abs(interpolated / 3.7 - 1.0));
    }
    MEASURED("eq. (9): normalised weights over 16 caches sum to one within "
             << worstSum << ", a constant proxy is reproduced within " << worstConstant);
    // Measured 1.5e-7 and 1.8e-7: float rounding of 16 divisions and sums.
    CHECK(worstSum < 5e-7);
    CHECK(worstConstant < 5e-7);

    // The shape of eq. (8) (MATH 9.5's reading: (1 - d/d_max)^p cos+): linear for p = 1.
    CHECK(interpolationWeight(0.5f, 2.0f, 1.0f, 1.0f) == Approx(0.75f));
    CHECK(interpolationWeight(0.5f, 2.0f, 2.0f, 0.5f) == Approx(0.5625f * 0.5f));
    CHECK(interpolationWeight(0.0f, 2.0f, 1.0f, -0.2f) == 0.0f);
    CHECK(interpolationWeight(3.0f, 2.0f, 1.0f, 1.0f) == 0.0f); // beyond d_max (defensive)
    CHECK(interpolationWeight(0.0f, 0.0f, 1.0f, 0.8f) == Approx(0.8f));
}

// --- Importance (eq. 10, 11) ------------------------------------------------------------------------

TEST_CASE("LightSkin eq. (10)/(11): one view sample's importance and the distance clamp", "[lightskin]")
{
    const glm::vec3 valPosition(1.0f, 2.0f, 3.0f), valNormal(0.0f, 0.0f, 1.0f);
    const float flux = 2.0f;
    // A view sample at offset l from the VAL, normal facing back at it with angle: written out.
    auto reference = [&](const glm::vec3& l, const glm::vec3& n, double clamp) {
        const double d2 = glm::dot(glm::dvec3(l), glm::dvec3(l));
        const glm::dvec3 d = glm::dvec3(l) / std::sqrt(d2);
        return flux * std::max(glm::dot(glm::dvec3(valNormal), d), 0.0) * std::max(-glm::dot(glm::dvec3(n), d), 0.0) /
               std::max(clamp * clamp, d2);
    };
    const glm::vec3 facing = glm::normalize(glm::vec3(-0.2f, 0.1f, -1.0f));
    for (const glm::vec3 l : {glm::vec3(0.1f, 0.2f, 0.5f), glm::vec3(0.5f, -0.3f, 0.6f), glm::vec3(1.5f, 1.0f, 2.0f),
                              glm::vec3(-4.0f, 0.5f, 7.0f)}) {
        for (float clamp : {kImportanceClampDistance, 0.25f, 3.0f}) {
            INFO("l = " << l.x << "," << l.y << "," << l.z << ", clamp " << clamp);
            const float got = valImportance(flux, valPosition, valNormal, valPosition + l, facing, clamp);
            CHECK(got == Approx(reference(l, facing, clamp)).epsilon(2e-6));
        }
    }
    // Eq. (11) with clamp 1: inside the unit ball, D = 1 (no growth as the distance falls).
    const float nearer = valImportance(flux, valPosition, valNormal, valPosition + glm::vec3(0.0f, 0.0f, 0.2f),
                                       glm::vec3(0.0f, 0.0f, -1.0f), 1.0f);
    CHECK(nearer == Approx(flux));
    const float farther = valImportance(flux, valPosition, valNormal, valPosition + glm::vec3(0.0f, 0.0f, 2.0f),
                                        glm::vec3(0.0f, 0.0f, -1.0f), 1.0f);
    CHECK(farther == Approx(flux / 4.0f));
    // l points from the VAL to the view sample (MATH 9.6): a sample behind the VAL, or facing away, gets 0.
    CHECK(valImportance(flux, valPosition, valNormal, valPosition - glm::vec3(0.0f, 0.0f, 2.0f),
                        glm::vec3(0.0f, 0.0f, 1.0f), 1.0f) == 0.0f);
    CHECK(valImportance(flux, valPosition, valNormal, valPosition + glm::vec3(0.0f, 0.0f, 2.0f),
                        glm::vec3(0.0f, 0.0f, 1.0f), 1.0f) == 0.0f);
    CHECK(valImportance(flux, valPosition, valNormal, valPosition, facing, 1.0f) == 0.0f);
}

// --- Halton (MATH 9.8) ----------------------------------------------------------------------------------

TEST_CASE("LightSkin Halton view samples: the radical inverses of MATH 9.8", "[lightskin]")
{
    const float base2[8] = {0.5f, 0.25f, 0.75f, 0.125f, 0.625f, 0.375f, 0.875f, 0.0625f};
    for (unsigned i = 1; i <= 8; ++i)
        CHECK(halton(i, 2u) == base2[i - 1]); // exact: powers of two
    const double base3[8] = {1.0 / 3, 2.0 / 3, 1.0 / 9, 4.0 / 9, 7.0 / 9, 2.0 / 9, 5.0 / 9, 8.0 / 9};
    for (unsigned i = 1; i <= 8; ++i)
        CHECK(halton(i, 3u) == Approx(base3[i - 1]).epsilon(1e-6));
    CHECK(halton(0u, 2u) == 0.0f);
    CHECK(halton(5u, 1u) == 0.0f); // no endless loop on a bad base
    CHECK(halton(5u, 0u) == 0.0f);
    CHECK(halton(511u, 2u) == Approx(511.0 / 512.0).epsilon(1e-7)); // 111111111 -> 0.111111111
    // The paper's Fig. 2 view buffer, 1024 x 768: sample 1 is its centre column, a third of the way up.
    CHECK(haltonViewPixel(1u, 1024, 768) == glm::ivec2(512, 256));
    CHECK(haltonViewPixel(2u, 1024, 768) == glm::ivec2(256, 512));
    // 512 samples land on 512 different pixels, all inside the buffer.
    std::vector<int> seen;
    for (unsigned i = 1; i <= 512; ++i) {
        const glm::ivec2 p = haltonViewPixel(i, 1024, 768);
        CHECK(p.x >= 0);
        CHECK(p.x < 1024);
        CHECK(p.y >= 0);
        CHECK(p.y < 768);
        seen.push_back(p.y * 1024 + p.x);
    }
    std::sort(seen.begin(), seen.end());
    CHECK(std::unique(seen.begin(), seen.end()) == seen.end());
}

// --- Occlusion (section 3; MATH 9.3, 9.10) ---------------------------------------------------------------

namespace {

struct Cache {
    glm::vec3 position, normal;
    float area = 0.0f;
};

// The occlusion of the proxy light (sphere at proxyPosition, proxyRadius) seen from caches[cacheIndex]
// by all the other caches, through the header's functions, in the order a GPU pass loops.
float occlusionOf(const std::vector<Cache>& caches, int cacheIndex, const glm::vec3& proxyPosition, float proxyRadius,
                  int* candidates)
{
    const Cache& c = caches[static_cast<std::size_t>(cacheIndex)];
    const glm::mat3 frame = occlusionFrame(c.normal);
    const glm::vec3 toProxy = proxyPosition - c.position;
    const glm::vec3 proxy = projectSphereToUnitDisk(toProxy, proxyRadius, frame);
    float overlap = 0.0f;
    *candidates = 0;
    for (int j = 0; j < static_cast<int>(caches.size()); ++j) {
        const Cache& o = caches[static_cast<std::size_t>(j)];
        if (!isOccluderCandidate(cacheIndex, c.position, c.normal, j, o.position, glm::dot(toProxy, toProxy))) continue;
        ++*candidates;
        overlap += squareOverlap(proxy, projectDiskToUnitDisk(o.position - c.position, o.normal, o.area, frame));
    }
    return occlusionFromOverlap(overlap, proxy.z);
}

} // namespace

TEST_CASE("LightSkin proxy sphere: radius 2 sigma_max, the disk's own radius for VALs uniform on a disk",
          "[lightskin][numbers]")
{
    // VALs uniform on a disk of radius R (midpoint rings of equal area), far from the origin, moments
    // of the offsets from a cache 3 m away (as the pass accumulates them). Along a world axis e the
    // variance is R^2/4 (1 - (n.e)^2), n the disk's normal, so 2 sigma_max = R sqrt(1 - min_e (n.e)^2):
    // exactly R for a disk that contains an axis (the full-width reading gives the disk's own radius).
    const float radius = 1.5f;
    const glm::vec3 centre(1000.0f, 20.0f, -700.0f), cache = centre + glm::vec3(0.0f, -3.0f, 0.5f);
    auto sphereRadius = [&](const glm::vec3& normal) {
        const glm::mat3 frame = lightViewBasis(normal);
        float weightSum = 0.0f;
        glm::vec3 offsetSum(0.0f), squaredSum(0.0f);
        for (int i = 0; i < 64; ++i)
            for (int j = 0; j < 64; ++j) {
                const float r = radius * std::sqrt((i + 0.5f) / 64.0f);
                const float phi = 2.0f * static_cast<float>(kPiD) * (j + 0.5f) / 64.0f;
                const glm::vec3 offset = centre + r * std::cos(phi) * frame[0] + r * std::sin(phi) * frame[1] - cache;
                weightSum += 1.0f;
                offsetSum += offset;
                squaredSum += offset * offset;
            }
        return proxySphereRadius(weightSum, offsetSum, squaredSum);
    };
    const glm::vec3 tiltedNormal = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    const float acrossZ = sphereRadius(glm::vec3(0.0f, 0.0f, 1.0f));
    const float tilted = sphereRadius(tiltedNormal);
    const glm::vec3 n2 = tiltedNormal * tiltedNormal;
    const double tiltedExpected = radius * std::sqrt(1.0 - std::min({n2.x, n2.y, n2.z}));
    MEASURED("proxy sphere radius for VALs uniform on a disk of radius "
             << radius << ": " << acrossZ << " (disk across z), " << tilted << " (tilted disk; expected "
             << tiltedExpected << ")");
    // Measured 1.5 and 1.47321 against 1.5 and 1.47321 (the midpoint rings' second moment is
    // R^2/4 (1 - 1/(2 64^2)), 3e-5 low in the radius; float sums of 4096 squares taken ~1e3 m from
    // the origin would lose far more than that without the offsets, which are 3 m).
    CHECK(acrossZ == Approx(radius).epsilon(1e-3));
    CHECK(tilted == Approx(tiltedExpected).epsilon(1e-3));
    // The half-width reading (sigma_max) would give R/2.
    CHECK(acrossZ > 0.9f * radius);
    CHECK(proxySphereRadius(0.0f, glm::vec3(1.0f), glm::vec3(1.0f)) == 0.0f);
    // One VAL (twice the weight at one point): no extent.
    CHECK(proxySphereRadius(2.0f, glm::vec3(2.0f, 4.0f, 6.0f), glm::vec3(2.0f, 8.0f, 18.0f)) == 0.0f);
}

TEST_CASE("LightSkin projections on the unit disk: areas pi F, centres at the directions' tangent coordinates",
          "[lightskin]")
{
    const glm::mat3 frame = occlusionFrame(glm::vec3(0.0f, 0.0f, 1.0f));
    // A sphere straight above: area pi (r/d)^2 at the centre.
    const glm::vec3 above = projectSphereToUnitDisk(glm::vec3(0.0f, 0.0f, 4.0f), 1.0f, frame);
    CHECK(above.x == Approx(0.0f).margin(1e-7));
    CHECK(above.y == Approx(0.0f).margin(1e-7));
    CHECK(above.z == Approx(kPiD / 16.0).epsilon(1e-6));
    // At 60 degrees from the normal: (r/d)^2 cos(60), centre at distance sin(60) from the disk's centre.
    const glm::vec3 tilted =
        projectSphereToUnitDisk(4.0f * glm::vec3(std::sin(radians(60.0)), 0.0f, std::cos(radians(60.0))), 1.0f, frame);
    CHECK(tilted.z == Approx(kPiD / 32.0).epsilon(1e-6));
    CHECK(std::hypot(tilted.x, tilted.y) == Approx(std::sin(radians(60.0))).epsilon(1e-6));
    // Below the horizon: nothing; around the cache: everything.
    CHECK(projectSphereToUnitDisk(glm::vec3(0.0f, 0.0f, -4.0f), 1.0f, frame).z == 0.0f);
    CHECK(projectSphereToUnitDisk(glm::vec3(0.0f, 0.0f, 0.5f), 1.0f, frame).z == Approx(kPiD));
    // A disk straight above, facing the cache either way: pi a^2/(d^2 + a^2) (MATH 9.10).
    const float a = 0.5f, d = 2.0f;
    for (float facing : {-1.0f, 1.0f}) {
        const glm::vec3 disk = projectDiskToUnitDisk(glm::vec3(0.0f, 0.0f, d), glm::vec3(0.0f, 0.0f, facing),
                                                     static_cast<float>(kPiD) * a * a, frame);
        CHECK(disk.z == Approx(kPiD * a * a / (d * d + a * a)).epsilon(1e-6));
    }
    // Squares: equal squares overlapping by half along x; disjoint ones; one inside the other.
    CHECK(squareOverlap(glm::vec3(0.0f, 0.0f, 0.04f), glm::vec3(0.1f, 0.0f, 0.04f)) == Approx(0.02f));
    CHECK(squareOverlap(glm::vec3(0.0f, 0.0f, 0.04f), glm::vec3(0.3f, 0.0f, 0.04f)) == 0.0f);
    CHECK(squareOverlap(glm::vec3(0.0f, 0.0f, 0.01f), glm::vec3(0.02f, -0.01f, 1.0f)) == Approx(0.01f));
}

TEST_CASE("LightSkin occlusion cells: five fifths of the unit disk, a cell's square and depth from its moments",
          "[lightskin]")
{
    // A 1000 x 1000 midpoint grid over [-1, 1]^2: the share of the disk's points in each cell is its
    // share of the disk's area, i.e. of the cosine-weighted hemisphere (Nusselt).
    const glm::mat3 frame = occlusionFrame(glm::normalize(glm::vec3(0.2f, 1.0f, -0.4f)));
    int counts[kOcclusionCells] = {};
    int inside = 0;
    const int n = 1000;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const float u = -1.0f + (2.0f * static_cast<float>(i) + 1.0f) / n;
            const float v = -1.0f + (2.0f * static_cast<float>(j) + 1.0f) / n;
            if (u * u + v * v >= 1.0f) continue;
            const glm::vec3 w = u * frame[0] + v * frame[1] + std::sqrt(1.0f - u * u - v * v) * frame[2];
            ++counts[occlusionCell(w, frame)];
            ++inside;
        }
    // The grid's boundary error is about the perimeter times a cell, 2 pi / 1000 of pi: 2e-3.
    for (int count : counts) CHECK(static_cast<double>(count) / inside == Approx(0.2).margin(2e-3));
    // Directions in each quadrant's middle, and the centre.
    CHECK(occlusionCell(frame[2], frame) == 0);
    CHECK(occlusionCell(glm::normalize(frame[0] + frame[2]), frame) == 1);
    CHECK(occlusionCell(glm::normalize(frame[1] + frame[2]), frame) == 2);
    CHECK(occlusionCell(glm::normalize(-frame[0] + frame[2]), frame) == 3);
    CHECK(occlusionCell(glm::normalize(-frame[1] + frame[2]), frame) == 4);

    // Square: VALs uniform on a disk of radius 0.3 about (0.1, -0.2) on the unit disk (midpoint
    // rings): the mean, and the area of that disk, pi 0.09 (2 sigma = R per axis).
    float weight = 0.0f;
    glm::vec2 sum(0.0f), squares(0.0f);
    for (int i = 0; i < 64; ++i)
        for (int j = 0; j < 64; ++j) {
            const float r = 0.3f * std::sqrt((i + 0.5f) / 64.0f);
            const float phi = 2.0f * static_cast<float>(kPiD) * (j + 0.5f) / 64.0f;
            const glm::vec2 p = glm::vec2(0.1f, -0.2f) + r * glm::vec2(std::cos(phi), std::sin(phi));
            weight += 1.0f;
            sum += p;
            squares += p * p;
        }
    const glm::vec3 square = occlusionCellSquare(weight, sum, squares);
    CHECK(square.x == Approx(0.1f).margin(1e-5));
    CHECK(square.y == Approx(-0.2f).margin(1e-5));
    CHECK(square.z == Approx(kPiD * 0.09).epsilon(1e-3));
    CHECK(occlusionCellSquare(0.0f, sum, squares) == glm::vec3(0.0f));
    // Spread over the whole disk and beyond: at most pi.
    CHECK(occlusionCellSquare(1.0f, glm::vec2(0.0f), glm::vec2(4.0f)).z == Approx(kPiD));
    // Depth: distances 4 and 6 are mean 5, sigma 1; one VAL at 5: sigma held at 0.005; none: 0.
    CHECK(occlusionCellDepth(2.0f, 10.0f, 16.0f + 36.0f).x == Approx(5.0f));
    CHECK(occlusionCellDepth(2.0f, 10.0f, 16.0f + 36.0f).y == Approx(1.0f));
    CHECK(occlusionCellDepth(1.0f, 5.0f, 25.0f).y == Approx(0.005f));
    CHECK(occlusionCellDepth(0.0f, 0.0f, 0.0f) == glm::vec2(0.0f));
    // Behind: half at the mean, the normal CDF within 0.01 a sigma away (0.159), a step without spread.
    CHECK(occlusionBehind(5.0f, glm::vec2(5.0f, 1.0f)) == Approx(0.5f));
    CHECK(occlusionBehind(6.0f, glm::vec2(5.0f, 1.0f)) == Approx(0.1587f).margin(0.01));
    CHECK(occlusionBehind(4.0f, glm::vec2(5.0f, 1.0f)) == Approx(0.8413f).margin(0.01));
    CHECK(occlusionBehind(4.9f, glm::vec2(5.0f, 0.0f)) == 1.0f);
    CHECK(occlusionBehind(5.1f, glm::vec2(5.0f, 0.0f)) == 0.0f);
}

TEST_CASE("LightSkin occlusion: a wall between a VAL cluster and the cache blocks it, half a wall half of it",
          "[lightskin][numbers]")
{
    // The receiving cache at the origin facing up; the VALs uniform on a disk of radius 1 at height
    // 10, facing down; the proxy light's sphere from their moments (2 sigma). The wall: caches on a
    // 0.25 m grid at height 5 over [-4, 4]^2 (cell centres, so that half the
    // wall ends at x = 0 under the proxy's centre) (their Voronoi areas 0.0625 m^2), facing the cache.
    // Decoys that must not count: caches behind the proxy light (height 12), below the cache's
    // horizon (height -1), and the cache itself.
    float weightSum = 0.0f;
    glm::vec3 offsetSum(0.0f), squaredSum(0.0f);
    for (int i = 0; i < 32; ++i)
        for (int j = 0; j < 32; ++j) {
            const float r = std::sqrt((i + 0.5f) / 32.0f), phi = 2.0f * static_cast<float>(kPiD) * (j + 0.5f) / 32.0f;
            const glm::vec3 offset(r * std::cos(phi), r * std::sin(phi), 10.0f);
            weightSum += 1.0f;
            offsetSum += offset;
            squaredSum += offset * offset;
        }
    const glm::vec3 proxyPosition = offsetSum / weightSum;
    const float proxyRadius = proxySphereRadius(weightSum, offsetSum, squaredSum);

    auto makeCaches = [](bool wall, bool halfWall) {
        std::vector<Cache> caches;
        caches.push_back({glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), 0.0625f}); // the receiver
        for (int i = -16; i < 16; ++i)
            for (int j = -16; j < 16; ++j) {
                const glm::vec3 p(0.25f * (i + 0.5f), 0.25f * (j + 0.5f), 0.0f);
                if (wall && (!halfWall || i < 0))
                    caches.push_back({p + glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(0.0f, 0.0f, -1.0f), 0.0625f});
                caches.push_back({p + glm::vec3(0.0f, 0.0f, 12.0f), glm::vec3(0.0f, 0.0f, -1.0f), 0.0625f});
                caches.push_back({p + glm::vec3(0.0f, 0.0f, -1.0f), glm::vec3(0.0f, 0.0f, 1.0f), 0.0625f});
            }
        return caches;
    };
    int fullCandidates = 0, halfCandidates = 0, noCandidates = 0;
    const float full = occlusionOf(makeCaches(true, false), 0, proxyPosition, proxyRadius, &fullCandidates);
    const float half = occlusionOf(makeCaches(true, true), 0, proxyPosition, proxyRadius, &halfCandidates);
    const float none = occlusionOf(makeCaches(false, false), 0, proxyPosition, proxyRadius, &noCandidates);
    MEASURED("double-projection occlusion (proxy sphere radius "
             << proxyRadius << " at 10 m): full wall " << full << " (" << fullCandidates << " occluders), half wall "
             << half << " (" << halfCandidates << "), no wall " << none << " (" << noCandidates << ")");
    CHECK(fullCandidates == 32 * 32); // only the wall: no decoy, not the cache itself
    CHECK(halfCandidates == 16 * 32);
    CHECK(noCandidates == 0);
    // Measured: 0.9979 (the wall's squares tile the proxy's square but for the slight shrinking of
    // the disks' form factors off axis), 0.4989, 0.
    CHECK(full > 0.9f);
    CHECK(half > 0.4f);
    CHECK(half < 0.6f);
    CHECK(none == 0.0f);
}

// --- GGX -> Phong ------------------------------------------------------------------------------------------

namespace {

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

struct LobeFit {
    double integral = 0.0; // int Phong cos / int GGX cos - 1
    double shape = 0.0;    // L2 of the difference after scaling Phong to GGX's integral, relative to GGX's L2 norm
};

// The exact GGX specular lobe D V (F = 1) times cos(theta_i) over incident directions w, against the
// paper's normalised Phong lobe (k+2)/(2 pi) cos^k(theta_e) cos(theta_i), theta_e between the view and
// the mirror of w. Quadrature about the mirror direction of the view.
LobeFit fitPhong(double alpha, double viewDegrees, double k)
{
    const glm::dvec3 v(std::sin(radians(viewDegrees)), 0.0, std::cos(radians(viewDegrees)));
    const glm::dvec3 mirror(-v.x, -v.y, v.z);
    auto exact = [&](const glm::dvec3& w) {
        const glm::dvec3 h = glm::normalize(v + w);
        return ggxD(h.z, alpha) * ggxV(v.z, w.z, alpha) * w.z;
    };
    auto phong = [&](const glm::dvec3& w) {
        const double cosE = glm::dot(v, glm::dvec3(-w.x, -w.y, w.z));
        return cosE > 0.0 ? (k + 2.0) / (2.0 * kPiD) * std::pow(cosE, k) * w.z : 0.0;
    };
    const int thetaNodes = 800, phiNodes = 64;
    const glm::dvec3 sums = test::integrateSphereAbout<glm::dvec3>(
        mirror,
        [&](const glm::dvec3& w) {
            if (w.z <= 0.0) return glm::dvec3(0.0);
            const double e = exact(w), p = phong(w);
            return glm::dvec3(e, e * e, p);
        },
        thetaNodes, phiNodes);
    const double scale = sums.x / sums.z;
    const double difference2 = test::integrateSphereAbout<double>(
        mirror,
        [&](const glm::dvec3& w) {
            if (w.z <= 0.0) return 0.0;
            const double d = scale * phong(w) - exact(w);
            return d * d;
        },
        thetaNodes, phiNodes);
    return {sums.z / sums.x - 1.0, std::sqrt(difference2 / sums.y)};
}

} // namespace

TEST_CASE("GGX to Phong: the exponent mapping by measured lobe error per roughness", "[lightskin][ggx][numbers]")
{
    // Candidates, with n = 2/alpha^2 - 2 (sg.h's NDF sharpness): k = n/4 (the mirror direction moves
    // twice as fast as the half vector), k = n/(4 cos theta_v) (the spherical warp's stretch, MATH 4.7,
    // made isotropic) and k = n (the NDF's own exponent). The integral error does not depend on k
    // (the Phong lobe is normalised, GGX with F = 1 loses energy to shadowing), so the choice is by
    // the shape error: the L2 of the difference after matching integrals.
    const double alphas[] = {0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1.0};
    double shapeSum[3] = {0.0, 0.0, 0.0};
    double worstShapeChosen = 0.0;
    int chosenMatches = 0;
    MEASURED("GGX vs Phong | alpha | view deg | integral err | shape L2: k = n/4 | n/(4 cos) | n");
    for (double alpha : alphas) {
        const double n = 2.0 / (alpha * alpha) - 2.0;
        if (std::abs(phongExponentFromRoughness(static_cast<float>(alpha)) - n / 4.0) <= 1e-5 * (1.0 + n))
            ++chosenMatches;
        for (double viewDegrees : {0.0, 30.0, 60.0}) {
            const double candidates[3] = {n / 4.0, n / (4.0 * std::cos(radians(viewDegrees))), n};
            LobeFit fits[3];
            for (int c = 0; c < 3; ++c) {
                fits[c] = fitPhong(alpha, viewDegrees, candidates[c]);
                shapeSum[c] += fits[c].shape;
            }
            worstShapeChosen = std::max(worstShapeChosen, fits[0].shape);
            MEASURED("GGX vs Phong | " << alpha << " | " << viewDegrees << " | " << fits[0].integral << " | "
                                       << fits[0].shape << " | " << fits[1].shape << " | " << fits[2].shape);
        }
    }
    MEASURED("GGX vs Phong: summed shape L2 over the 21 rows: n/4 " << shapeSum[0] << ", n/(4 cos theta_v) "
                                                                    << shapeSum[1] << ", n " << shapeSum[2]);
    CHECK(chosenMatches == 7);
    CHECK(phongExponentFromRoughness(0.0f) == phongExponentFromRoughness(kMinAlpha)); // finite for a mirror
    CHECK(std::isfinite(phongExponentFromRoughness(0.0f))); // phongExponentFromRoughness is n/4 ...
    CHECK(shapeSum[0] < shapeSum[1]);                       // ... because it measures best
    CHECK(shapeSum[0] < shapeSum[2]);
    // Measured worst shape error of n/4: 0.68 (alpha = 1, view 60: GGX's lobe leans towards grazing,
    // which a lobe symmetric about the mirror direction cannot follow); bound about 1.5x.
    CHECK(worstShapeChosen < 1.0);
}
