// glsl/shared/normals.h: the octahedral packing of the G-buffer's geometric and interpolated normals.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <glm/gtc/packing.hpp>

#include "glsl/shared/normals.h"
#include "measured.h"

using namespace vplgi;

namespace {

// In double, as atan2(|a x b|, a . b): acos of a float dot product near 1 cannot resolve below ~6e-4 rad.
double angleBetween(const glm::vec3& a, const glm::vec3& b)
{
    const glm::dvec3 x(a), y(b);
    return std::atan2(glm::length(glm::cross(x, y)), glm::dot(x, y));
}

// Through float16 as the G-buffer's RGBA16F attachment stores the two components.
glm::vec2 throughHalf(const glm::vec2& e)
{
    return glm::unpackHalf2x16(glm::packHalf2x16(e));
}

} // namespace

TEST_CASE("octahedral normals: exact on the axes, round trip within float16's step everywhere", "[normals][numbers]")
{
    // The six axes and the eight octant diagonals land on representable points: exact, also in half.
    for (int axis = 0; axis < 3; ++axis)
        for (float sign : {1.0f, -1.0f}) {
            glm::vec3 n(0.0f);
            n[axis] = sign;
            CHECK(shared::octDecode(throughHalf(shared::octEncode(n))) == n);
        }
    // A Fibonacci sphere of 200000 directions (both hemispheres, the folded seams included):
    // float32 round trip to float rounding, float16 within a step of the encoding.
    const int count = 200000;
    double worst32 = 0.0, worst16 = 0.0;
    for (int i = 0; i < count; ++i) {
        const double z = 1.0 - (2.0 * i + 1.0) / count;
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        const double phi = 2.399963229728653 * i; // golden angle
        const glm::vec3 n(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
                          static_cast<float>(z));
        const glm::vec2 e = shared::octEncode(glm::normalize(n));
        REQUIRE(std::abs(e.x) <= 1.0f);
        REQUIRE(std::abs(e.y) <= 1.0f);
        worst32 = std::max(worst32, angleBetween(shared::octDecode(e), glm::normalize(n)));
        worst16 = std::max(worst16, angleBetween(shared::octDecode(throughHalf(e)), glm::normalize(n)));
    }
    MEASURED("octahedral round trip over " << count << " directions: worst " << worst32 << " rad (float32), "
             << worst16 << " rad (float16)");
    // Bounds about 2x the measured worst (printed above; float16's step is 2^-11 near |e| = 1).
    CHECK(worst32 < 1e-6);  // measured 3.4e-7
    CHECK(worst16 < 2e-3);  // measured 1.02e-3
}
