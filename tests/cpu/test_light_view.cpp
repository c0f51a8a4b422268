// The shared light-view maths (glsl/shared/light_view.h) on the CPU: bit-equality with glm where
// ShadowPass relies on it, GL's cube-map layout (spec Table 8.19), SMCIR's hemisphere cube (every
// hemisphere direction on exactly one face, the VPL as centre of projection, MATH.md 6.3's face
// corners), paraboloid round trips and solid angles (they sum to 2 pi), the directional fit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "glsl/shared/light_view.h"
#include "measured.h"

using namespace vplgi;
using namespace vplgi::shared;

namespace {

constexpr double kPi = 3.14159265358979323846;

bool bitIdentical(const glm::mat4& a, const glm::mat4& b)
{
    return std::memcmp(&a, &b, sizeof(glm::mat4)) == 0;
}

// Uniform floats in [0, 1) from mt19937's raw output (std:: distributions differ between
// libraries): `Uniform u(seed); u()`.
struct Uniform {
    std::mt19937 engine;
    explicit Uniform(std::uint32_t seed) : engine(seed) {}
    float operator()() { return static_cast<float>(engine() >> 8u) * 0x1p-24f; }
};

glm::vec3 randomDirection(Uniform& u)
{
    const float z = 2.0f * u() - 1.0f;
    const float phi = 2.0f * static_cast<float>(kPi) * u();
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
}

// n points of a Fibonacci spiral on the unit sphere (zMin = -1) or the upper hemisphere (zMin = 0),
// z from zMin to 1 in equal steps (both ends included: the hemisphere's rim and pole are in it).
std::vector<glm::vec3> fibonacciDirections(int n, double zMin)
{
    const double golden = kPi * (3.0 - std::sqrt(5.0));
    std::vector<glm::vec3> directions;
    for (int i = 0; i < n; ++i) {
        const double z = zMin + (1.0 - zMin) * i / (n - 1);
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        directions.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), z);
    }
    return directions;
}

glm::vec3 ndcOf(const glm::vec4& clip)
{
    return glm::vec3(clip) / clip.w;
}

// Normals to test the hemisphere cube and paraboloid with: the axes both ways (lightViewBasis's
// branch on n.z, and n = (0,0,-1) itself), and random ones.
std::vector<glm::vec3> testNormals()
{
    std::vector<glm::vec3> normals = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {0, -1, 0}};
    Uniform u(11);
    for (int i = 0; i < 6; ++i)
        normals.push_back(randomDirection(u));
    return normals;
}

} // namespace

TEST_CASE("light view: look-at and projections are bit for bit glm's", "[lightview]")
{
    // ShadowPass built its matrices with glm; the shared versions must give the same bits so that
    // its images do not change (the shadow depths are compared with <=).
    Uniform u(3);
    for (int i = 0; i < 200; ++i) {
        const glm::vec3 eye = 10.0f * glm::vec3(u(), u(), u()) - 5.0f;
        const glm::vec3 center = eye + randomDirection(u) * (0.1f + 3.0f * u());
        const glm::vec3 up = randomDirection(u);
        CHECK(bitIdentical(lightViewLookAt(eye, center, up), glm::lookAt(eye, center, up)));
        const float zNear = 1e-3f + u(), zFar = zNear + 100.0f * u() + 1e-2f;
        const float l = -u() - 0.1f, r = u() + 0.1f, b = -u() - 0.1f, t = u() + 0.1f;
        CHECK(bitIdentical(lightViewFrustum(l, r, b, t, zNear, zFar), glm::frustum(l, r, b, t, zNear, zFar)));
        CHECK(bitIdentical(lightViewOrtho(l, r, b, t, zNear, zFar), glm::ortho(l, r, b, t, zNear, zFar)));
        // tan(radians(90) / 2) rounds to exactly 1 in float, so glm's 90 degree frustum has 1s.
        CHECK(bitIdentical(lightViewCubeFaceClipFromView(zNear, zFar),
                           glm::perspective(glm::radians(90.0f), 1.0f, zNear, zFar)));
        for (int face = 0; face < kLightViewCubeFaceCount; ++face)
            CHECK(bitIdentical(lightViewCubeFaceViewFromWorld(eye, face),
                               glm::lookAt(eye, eye + lightViewCubeFaceDirection(face), lightViewCubeFaceUp(face))));
    }
}

TEST_CASE("light view: cube faces cover the sphere in GL's cube-map layout", "[lightview]")
{
    // OpenGL 4.5 Table 8.19: the major axis picks the face; (sc, tc, ma) per face give the texture
    // coordinates s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2, which must be the face view's NDC
    // (x, y) mapped to [0, 1] for a layered render into a cube map to be sampled back correctly.
    auto table = [](int face, glm::vec3 r) {
        switch (face) {
        case 0:
            return glm::vec3(-r.z, -r.y, r.x);
        case 1:
            return glm::vec3(r.z, -r.y, r.x);
        case 2:
            return glm::vec3(r.x, r.z, r.y);
        case 3:
            return glm::vec3(r.x, -r.z, r.y);
        case 4:
            return glm::vec3(r.x, -r.y, r.z);
        default:
            return glm::vec3(-r.x, -r.y, r.z);
        }
    };
    const glm::vec3 position(0.3f, -1.2f, 2.5f);
    const float zNear = 0.01f, zFar = 20.0f;
    int perFace[6] = {};
    float worst = 0.0f;
    for (const glm::vec3& d : fibonacciDirections(20000, -1.0)) {
        const int face = lightViewCubeFace(d);
        REQUIRE(face >= 0);
        REQUIRE(face < 6);
        ++perFace[face];
        // The face GL samples is the major axis of d, with its sign.
        const glm::vec3 a = glm::abs(d);
        const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
        CHECK(face == 2 * axis + (d[axis] < 0.0f ? 1 : 0));
        for (float distance : {0.05f, 1.0f, 15.0f}) {
            const glm::vec4 clip =
                lightViewCubeFaceClipFromWorld(position, face, zNear, zFar) * glm::vec4(position + distance * d, 1.0f);
            REQUIRE(clip.w > 0.0f);
            const glm::vec3 ndc = ndcOf(clip);
            const glm::vec3 sct = table(face, d);
            const glm::vec2 expected = glm::vec2(sct) / std::abs(sct.z);
            worst = std::max({worst, std::abs(ndc.x - expected.x), std::abs(ndc.y - expected.y)});
            CHECK(std::abs(ndc.x) <= 1.0f + 1e-6f);
            CHECK(std::abs(ndc.y) <= 1.0f + 1e-6f);
            CHECK(std::abs(ndc.z) < 1.0f);
        }
    }
    // Measured 5.3e-6: float rounding of the points p + 0.05 d near a light 2.8 m from the origin
    // (2.4e-7 m, 5e-6 of the direction); 1.5e-5 is about 3x that.
    std::printf("cube faces: largest |NDC - Table 8.19| = %.3g\n", worst);
    CHECK(worst < 1.5e-5f);
    for (int face = 0; face < 6; ++face)
        CHECK(perFace[face] > 3000); // about 20000/6 each
}

TEST_CASE("light view: every hemisphere direction lands on exactly one of the three faces", "[lightview]")
{
    // SMCIR Sec. 4 / MATH.md 6.3. For directions strictly inside one face the other two frusta do
    // not contain them. A direction whose two largest cube-frame components are equal lies on the
    // edge the two faces share: it is on the border of both (NDC coordinate exactly +1 up to
    // rounding), and lightViewHemisphereFace gives it to the lower index; n itself is the corner
    // of all three. Those ties are tested explicitly below; in the Fibonacci set a direction counts
    // as a tie when the components differ by less than the rounding of the projection (kTie).
    const float kInside = 1e-6f; // NDC slack for float rounding (measured below: 3.6e-7)
    const float kTie = 4e-6f;    // component difference within which two faces both hold it
    const float zNear = 0.01f, zFar = 50.0f;
    const glm::vec3 position(1.5f, 0.25f, -2.0f);
    int ties = 0, checked = 0;
    float worstOutside = 0.0f, minAxialRatio = 1.0f;
    for (const glm::vec3& n : testNormals()) {
        INFO("n = " << n.x << ", " << n.y << ", " << n.z);
        const glm::mat3 frame = lightViewBasis(n);
        const glm::mat3 cube = lightViewHemisphereBasis(n);
        // The cube frame is a rotation taking (1,1,1)/sqrt(3) to n.
        CHECK(glm::length(cube * glm::vec3(0.57735026918963f) - n) < 1e-6f);
        CHECK(glm::determinant(cube) == Approx(1.0f).margin(1e-6));
        CHECK(glm::length(glm::transpose(cube) * cube[0] - glm::vec3(1, 0, 0)) < 1e-6f);
        glm::mat4 clipFromWorld[3];
        for (int face = 0; face < 3; ++face)
            clipFromWorld[face] = lightViewHemisphereFaceClipFromWorld(position, cube, face, zNear, zFar);
        for (const glm::vec3& local : fibonacciDirections(20000, 0.0)) {
            const glm::vec3 w = frame * local;
            const glm::vec3 dc = glm::transpose(cube) * w;
            const int owner = lightViewHemisphereFace(dc);
            int inside = 0;
            bool ownerInside = false, othersAreTies = true;
            for (int face = 0; face < 3; ++face) {
                const glm::vec4 clip = clipFromWorld[face] * glm::vec4(position + 2.0f * w, 1.0f);
                const glm::vec3 ndc = ndcOf(clip);
                const bool in = clip.w > 0.0f && std::abs(ndc.x) <= 1.0f + kInside && std::abs(ndc.y) <= 1.0f + kInside;
                if (face == owner) {
                    ownerInside = in;
                    worstOutside = std::max({worstOutside, std::abs(ndc.x) - 1.0f, std::abs(ndc.y) - 1.0f});
                    CHECK(std::abs(ndc.z) < 1.0f);
                    // Depth along the face axis is at least distance / sqrt(6) (the header's note on zNear).
                    minAxialRatio = std::min(minAxialRatio, clip.w / 2.0f);
                    // The face's texture coordinates agree with its matrix.
                    const glm::vec2 uv = lightViewHemisphereFaceUV(dc, face);
                    CHECK(glm::length(uv - (glm::vec2(ndc) * 0.5f + 0.5f)) < 2e-6f);
                }
                if (in) {
                    ++inside;
                    if (face != owner && dc[owner] - dc[face] >= kTie) othersAreTies = false;
                }
            }
            CHECK(ownerInside);
            CHECK(othersAreTies);
            if (inside != 1) ++ties;
            ++checked;
        }

        // Explicit ties: n (all three faces, at their NDC corner (1, 1)) and directions on the
        // three shared edges, at NDC coordinate 1 on both faces.
        const glm::vec3 edges[] = {
            {1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 0.3f}, {-1.5f, 1.0f, 1.0f}, {1.0f, -0.7f, 1.0f}, {1.0f, 1.0f, -1.9f}};
        for (const glm::vec3& edge : edges) {
            const glm::vec3 dc = glm::normalize(edge);
            const glm::vec3 w = cube * dc;
            REQUIRE(glm::dot(w, n) >= 0.0f);
            const float top = std::max({dc.x, dc.y, dc.z});
            CHECK(lightViewHemisphereFace(dc) == (dc.x == top ? 0 : (dc.y == top ? 1 : 2)));
            for (int face = 0; face < 3; ++face) {
                const glm::vec4 clip = clipFromWorld[face] * glm::vec4(position + 2.0f * w, 1.0f);
                const glm::vec3 ndc = ndcOf(clip);
                const float border = std::max(ndc.x, ndc.y);
                if (dc[face] == top) {
                    // On the face's border (NDC coordinate 1 towards the other tied face), inside otherwise.
                    CHECK(clip.w > 0.0f);
                    CHECK(border == Approx(1.0f).margin(kInside));
                    CHECK(std::min(ndc.x, ndc.y) >= -1.0f - kInside);
                } else {
                    // Clearly outside: behind the face's eye plane or well past its border.
                    CHECK((clip.w <= 0.0f || border > 1.1f));
                }
            }
        }
    }
    std::printf("hemisphere cube: %d directions, %d on a shared edge, owner face at most %.3g outside its "
                "NDC square, smallest axial depth / distance %.6f (1/sqrt6 = 0.408248)\n",
                checked, ties, worstOutside, minAxialRatio);
    CHECK(worstOutside < kInside);
    CHECK(minAxialRatio >= 0.408248f * (1.0f - 1e-5f));
    CHECK(minAxialRatio < 0.42f); // the rim directions between two axes come close to the bound
}

TEST_CASE("light view: hemisphere faces project from the VPL (Kooima), corners to NDC +-1", "[lightview]")
{
    const float zNear = 0.01f, zFar = 100.0f;
    const glm::vec3 position(-0.5f, 2.0f, 0.75f);
    Uniform u(5);
    float worstRay = 0.0f, worstInverse = 0.0f;
    for (const glm::vec3& n : testNormals()) {
        INFO("n = " << n.x << ", " << n.y << ", " << n.z);
        const glm::mat3 cube = lightViewHemisphereBasis(n);
        for (int face = 0; face < 3; ++face) {
            INFO("face " << face);
            const glm::mat4 clipFromWorld = lightViewHemisphereFaceClipFromWorld(position, cube, face, zNear, zFar);
            // The VPL is the centre of projection: clip x, y and w vanish there.
            const glm::vec4 centre = clipFromWorld * glm::vec4(position, 1.0f);
            CHECK(std::abs(centre.x) < 1e-5f);
            CHECK(std::abs(centre.y) < 1e-5f);
            CHECK(std::abs(centre.w) < 1e-5f);
            // MATH.md 6.3: the cube [-h, h]^3 with the eye at (h/3)(1,1,1); face +x has corners
            // (h, +-h, +-h), its right axis is z and its up axis y; the other faces cyclically.
            const float h = 0.2f + u();
            for (int corner = 0; corner < 4; ++corner) {
                const float right = corner & 1 ? h : -h;
                const float up = corner & 2 ? h : -h;
                glm::vec3 c(0.0f);
                c[face] = h;
                c[(face + 2) % 3] = right;
                c[(face + 1) % 3] = up;
                const glm::vec3 world = position + cube * (c - glm::vec3(h / 3.0f));
                const glm::vec3 ndc = ndcOf(clipFromWorld * glm::vec4(world, 1.0f));
                CHECK(ndc.x == Approx(right > 0.0f ? 1.0f : -1.0f).margin(1e-5));
                CHECK(ndc.y == Approx(up > 0.0f ? 1.0f : -1.0f).margin(1e-5));
            }
            // Points along one view ray land on one pixel, with depth growing with distance, and
            // the ray comes back from the NDC point through the inverse matrix.
            const glm::mat4 worldFromClip = glm::inverse(clipFromWorld);
            for (int k = 0; k < 20; ++k) {
                glm::vec3 dc(0.0f);
                dc[face] = 1.0f;
                dc[(face + 2) % 3] = 3.0f * u() - 2.0f; // ratios in [-2, 1]: on the face
                dc[(face + 1) % 3] = 3.0f * u() - 2.0f;
                const glm::vec3 w = cube * glm::normalize(dc);
                const glm::vec3 first = ndcOf(clipFromWorld * glm::vec4(position + 0.05f * w, 1.0f));
                float previousDepth = -2.0f;
                for (float distance : {0.05f, 0.5f, 5.0f, 50.0f}) {
                    const glm::vec3 ndc = ndcOf(clipFromWorld * glm::vec4(position + distance * w, 1.0f));
                    worstRay = std::max(worstRay, glm::length(glm::vec2(ndc) - glm::vec2(first)));
                    CHECK(ndc.z > previousDepth);
                    previousDepth = ndc.z;
                }
                const glm::vec4 back = worldFromClip * glm::vec4(first.x, first.y, 0.5f, 1.0f);
                const glm::vec3 ray = glm::normalize(glm::vec3(back) / back.w - position);
                worstInverse = std::max(worstInverse, glm::length(ray - w));
            }
        }
    }
    std::printf("hemisphere faces: one ray, one pixel to %.3g in NDC; NDC -> inverse matrix -> ray to %.3g\n", worstRay,
                worstInverse);
    // Measured 1.7e-5 and 1.4e-5, both from rounding world positions: a point 5 cm from a VPL 2 m
    // from the origin carries 2.4e-7 m of rounding, 5e-6 of its direction, which the face's
    // projection magnifies up to 6x off axis (and the inverse reads a point at depth ~ zNear).
    // Tolerances about 3x.
    CHECK(worstRay < 5e-5f);
    CHECK(worstInverse < 4e-5f);
}

TEST_CASE("light view: paraboloid map round trips", "[lightview][paraboloid]")
{
    // direction -> uv -> direction over a dense hemisphere (rim and pole included), and
    // uv -> direction -> uv over the disk; depth is linear in distance.
    float worstDirection = 0.0f, worstUV = 0.0f;
    for (const glm::vec3& d : fibonacciDirections(50000, 0.0)) {
        const glm::vec2 uv = paraboloidMapFromDirection(d);
        const glm::vec2 st = 2.0f * uv - 1.0f;
        CHECK(glm::dot(st, st) <= 1.0f + 1e-6f);
        worstDirection = std::max(worstDirection, glm::length(paraboloidDirectionFromMap(uv) - d));
    }
    Uniform u(9);
    for (int i = 0; i < 50000; ++i) {
        const glm::vec2 uv(u(), u());
        const glm::vec2 st = 2.0f * uv - 1.0f;
        if (glm::dot(st, st) > 1.0f) continue;
        const glm::vec3 d = paraboloidDirectionFromMap(uv);
        CHECK(d.z >= -1e-6f);
        CHECK(std::abs(glm::length(d) - 1.0f) < 1e-6f);
        worstUV = std::max(worstUV, glm::length(paraboloidMapFromDirection(d) - uv));
    }
    // Measured 2.5e-7 and 8.4e-8: a few float roundings; 1e-6 as asked for (4x and more).
    std::printf("paraboloid round trips: direction %.3g, uv %.3g\n", worstDirection, worstUV);
    CHECK(worstDirection < 1e-6f);
    CHECK(worstUV < 1e-6f);
    // The pole maps to the centre, the rim to the circle of radius 1/2 around it.
    CHECK(glm::length(paraboloidMapFromDirection(glm::vec3(0, 0, 1)) - glm::vec2(0.5f)) == 0.0f);
    CHECK(glm::length(paraboloidMapFromDirection(glm::vec3(0, 1, 0)) - glm::vec2(0.5f, 1.0f)) < 1e-7f);
    const glm::vec3 mapped = paraboloidMapFromPoint(glm::vec3(0.0f, 3.0f, 4.0f), 1.0f, 11.0f);
    CHECK(mapped.z == Approx(0.4f).margin(1e-7)); // (5 - 1) / (11 - 1)
    CHECK(glm::length(glm::vec2(mapped) - paraboloidMapFromDirection(glm::vec3(0.0f, 0.6f, 0.8f))) < 1e-7f);
}

TEST_CASE("light view: paraboloid texel solid angles sum to 2 pi", "[lightview][paraboloid]")
{
    // 128^2 texels: the sum, in double, of the per-texel solid angles must be the hemisphere's.
    const int resolution = 128;
    const double h = 2.0 / resolution;
    double sum = 0.0;
    int outside = 0, inside = 0, rim = 0;
    for (int y = 0; y < resolution; ++y)
        for (int x = 0; x < resolution; ++x) {
            const float omega = paraboloidTexelSolidAngle(glm::ivec2(x, y), resolution);
            sum += omega;
            // The texel's nearest and farthest points from the disk's centre (s, t in [-1, 1]).
            const double s0 = -1.0 + h * x, t0 = -1.0 + h * y;
            const double sNear = std::clamp(0.0, s0, s0 + h), tNear = std::clamp(0.0, t0, t0 + h);
            const double sFar = std::max(std::abs(s0), std::abs(s0 + h)),
                         tFar = std::max(std::abs(t0), std::abs(t0 + h));
            if (sNear * sNear + tNear * tNear >= 1.0) {
                CHECK(omega == 0.0f); // wholly outside the disk: no direction of the hemisphere
                ++outside;
            } else if (sFar * sFar + tFar * tFar <= 1.0) {
                CHECK(omega > 0.0f);
                ++inside;
            } else {
                CHECK(omega >= 0.0f);
                ++rim;
            }
        }
    const double relative = sum / (2.0 * kPi) - 1.0;
    std::printf("paraboloid %d^2: texel solid angles sum to 2 pi (1 %+.3g); texels inside %d, cut by the rim %d, "
                "outside %d\n",
                resolution, relative, inside, rim, outside);
    // Measured +4.1e-9 (the same rule in double: 1.4e-9); 1.5e-8 is about 3x that. A texel-centre
    // rule (density x area where the centre is in the disk) would be off by 9e-4 here, from the
    // rim; the Gauss rule without the splits at the rim's kinks by 2e-6.
    CHECK(std::abs(relative) < 1.5e-8);
    CHECK(outside + inside + rim == resolution * resolution);
    // The rim's texels are exercised: a circle of length L texels crosses about 4L/pi of them, 512.
    CHECK(rim > 3 * resolution);

    // Single texels against a brute-force midpoint sum of 4/(1+s^2+t^2)^2 over the texel's part
    // of the disk (double, 1000^2 points): the centre, an interior texel and texels the rim cuts.
    auto bruteForce = [&](int x, int y) {
        const int m = 1000;
        const double step = h / m;
        double total = 0.0;
        for (int j = 0; j < m; ++j)
            for (int i = 0; i < m; ++i) {
                const double s = -1.0 + h * x + (i + 0.5) * step, t = -1.0 + h * y + (j + 0.5) * step;
                const double r2 = s * s + t * t;
                if (r2 <= 1.0) total += 4.0 / ((1.0 + r2) * (1.0 + r2)) * step * step;
            }
        return total;
    };
    double worstInterior = 0.0, worstRim = 0.0;
    for (glm::ivec2 texel : {glm::ivec2(64, 64), glm::ivec2(10, 70), glm::ivec2(100, 100)}) {
        const double expected = bruteForce(texel.x, texel.y);
        worstInterior =
            std::max(worstInterior, std::abs(paraboloidTexelSolidAngle(texel, resolution) / expected - 1.0));
    }
    // Rim texels, some with only a sliver inside the disk: their error relative to a whole texel's
    // solid angle there (density x area), which is what a sliver's error means for a sum or a flux.
    for (glm::ivec2 texel : {glm::ivec2(127, 64), glm::ivec2(0, 63), glm::ivec2(0, 70), glm::ivec2(109, 109),
                             glm::ivec2(64, 0), glm::ivec2(119, 95), glm::ivec2(75, 126)}) {
        const double expected = bruteForce(texel.x, texel.y);
        REQUIRE(expected > 0.0);
        const double s = -1.0 + h * (texel.x + 0.5), t = -1.0 + h * (texel.y + 0.5);
        const double whole = 4.0 / ((1.0 + s * s + t * t) * (1.0 + s * s + t * t)) * h * h;
        worstRim = std::max(worstRim, std::abs(paraboloidTexelSolidAngle(texel, resolution) - expected) / whole);
    }
    std::printf("paraboloid texels vs brute force: interior %.3g (relative), cut by the rim %.3g (of a whole "
                "texel)\n",
                worstInterior, worstRim);
    // Interior: measured 2.5e-6 (float: a texel's value is the difference of two strip integrals
    // about 2000x larger); rim: measured 2.0e-5 (texel (0, 63): the sqrt-shaped rim at s = -1
    // under the Gauss rule, and the brute force's staircase along the rim). Tolerances about 3x.
    CHECK(worstInterior < 7.5e-6);
    CHECK(worstRim < 6e-5);

    // The density against the mapped area of a small square: |d/du x d/dv| by central differences
    // of the inverse map, in double from the float directions (step 1e-3: truncation ~1e-6,
    // float rounding ~1e-4 of the difference quotient).
    double worstDensity = 0.0;
    Uniform u(21);
    for (int i = 0; i < 200; ++i) {
        const glm::vec2 uv(0.1f + 0.8f * u(), 0.1f + 0.8f * u());
        const glm::vec2 st = 2.0f * uv - 1.0f;
        if (glm::dot(st, st) > 0.95f) continue;
        const float e = 1e-3f;
        const glm::dvec3 du = (glm::dvec3(paraboloidDirectionFromMap(uv + glm::vec2(e, 0))) -
                               glm::dvec3(paraboloidDirectionFromMap(uv - glm::vec2(e, 0)))) /
                              (2.0 * e);
        const glm::dvec3 dv = (glm::dvec3(paraboloidDirectionFromMap(uv + glm::vec2(0, e))) -
                               glm::dvec3(paraboloidDirectionFromMap(uv - glm::vec2(0, e)))) /
                              (2.0 * e);
        const double jacobian = glm::length(glm::cross(du, dv));
        worstDensity = std::max(worstDensity, std::abs(paraboloidSolidAngleDensity(uv) / jacobian - 1.0));
    }
    std::printf("paraboloid density vs finite differences: %.3g\n", worstDensity);
    CHECK(worstDensity < 1.3e-4); // measured 4.3e-5 (float rounding in the differences)
}

TEST_CASE("light view: the directional fit holds the box and is today's ShadowPass matrix", "[lightview]")
{
    const glm::vec3 lower(-3.0f, 0.0f, -1.0f), upper(2.0f, 4.0f, 5.0f);
    Uniform u(17);
    std::vector<glm::vec3> directions = {{0, -1, 0}, {0.05f, -1, 0}, {1, -1, 0.3f}, {0, 0, 1}};
    for (int i = 0; i < 20; ++i)
        directions.push_back(randomDirection(u));
    for (const glm::vec3& direction : directions) {
        INFO("direction " << direction.x << ", " << direction.y << ", " << direction.z);
        const glm::mat4 clipFromWorld = lightViewDirectionalFit(direction, lower, upper);
        // ShadowPass before the move (gl/passes/shadow_pass.cpp): the same bits.
        const float diagonal = std::max(1e-3f, glm::length(upper - lower));
        const glm::vec3 center = 0.5f * (lower + upper);
        const float radius = 0.5f * diagonal * 1.01f;
        const glm::vec3 dir = glm::normalize(direction);
        const glm::vec3 up = std::abs(dir.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
        const glm::mat4 before = glm::ortho(-radius, radius, -radius, radius, radius * 0.5f, radius * 3.5f) *
                                 glm::lookAt(center - dir * (2.0f * radius), center, up);
        CHECK(bitIdentical(clipFromWorld, before));
        // Every corner of the box is inside the clip volume, with the sphere's margin to spare.
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 p(corner & 1 ? upper.x : lower.x, corner & 2 ? upper.y : lower.y,
                              corner & 4 ? upper.z : lower.z);
            const glm::vec4 clip = clipFromWorld * glm::vec4(p, 1.0f);
            CHECK(clip.w == 1.0f);
            CHECK(std::max({std::abs(clip.x), std::abs(clip.y), std::abs(clip.z)}) < 0.995f);
        }
        // Orthographic along the light: points on one light ray share NDC x, y; depth grows.
        const glm::vec4 a = clipFromWorld * glm::vec4(center, 1.0f);
        const glm::vec4 b = clipFromWorld * glm::vec4(center + 0.5f * radius * dir, 1.0f);
        CHECK(std::abs(a.x - b.x) < 1e-5f);
        CHECK(std::abs(a.y - b.y) < 1e-5f);
        CHECK(b.z > a.z);
    }
}

TEST_CASE("spot view: the axis at the centre, the outer cone inscribed in the square", "[light_view][numbers]")
{
    float worstRim = 0.0f;
    const float halfAngle = 0.5f;
    const glm::vec3 position(0.3f, 2.0f, -0.7f);
    Uniform u(11);
    for (int trial = 0; trial < 8; ++trial) {
        const glm::vec3 axis = randomDirection(u);
        const glm::mat4 viewFromWorld = lightViewSpotViewFromWorld(position, axis);
        const glm::mat4 clipFromWorld = lightViewSpotClipFromView(halfAngle, 0.1f, 10.0f) * viewFromWorld;
        auto ndc = [&](glm::vec3 world) {
            const glm::vec4 clip = clipFromWorld * glm::vec4(world, 1.0f);
            return glm::vec3(clip) / clip.w;
        };
        const glm::vec3 centre = ndc(position + 3.0f * axis);
        CHECK(std::abs(centre.x) < 1e-5f);
        CHECK(std::abs(centre.y) < 1e-5f);
        // The view's right and up axes (rows of the rotation) are orthogonal to the axis.
        const glm::vec3 right(viewFromWorld[0][0], viewFromWorld[1][0], viewFromWorld[2][0]);
        const glm::vec3 up(viewFromWorld[0][1], viewFromWorld[1][1], viewFromWorld[2][1]);
        CHECK(std::abs(glm::dot(right, axis)) < 1e-6f);
        CHECK(std::abs(glm::dot(up, axis)) < 1e-6f);
        // Cone rim directions land on the unit circle in NDC x, y: the circle inscribed in the
        // square (it touches the edge midpoints along right and up).
        for (int k = 0; k < 16; ++k) {
            const float phi = 2.0f * static_cast<float>(kPi) * static_cast<float>(k) / 16.0f;
            const glm::vec3 rim =
                std::cos(halfAngle) * axis + std::sin(halfAngle) * (std::cos(phi) * right + std::sin(phi) * up);
            const glm::vec3 p = ndc(position + 2.0f * rim);
            worstRim = std::max(worstRim, std::abs(glm::length(glm::vec2(p)) - 1.0f));
            CHECK(p.z > -1.0f);
            CHECK(p.z < 1.0f);
        }
    }
    MEASURED("spot view: worst | |ndc.xy| - 1 | on the cone rim " << worstRim);
    // Measured 6.0e-7 (float rounding of tan, the rim direction and the projection); 1.5e-6 is 2.5x.
    CHECK(worstRim < 1.5e-6f);
}
