// An orthonormal frame around a unit normal, for sampling directions on a surface.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace vplgi {

// Orthonormal t, b with (t, b, n) right-handed (Duff et al. 2017, "Building an Orthonormal Basis,
// Revisited"); n must be unit length.
inline void makeBasis(const glm::vec3& n, glm::vec3& t, glm::vec3& b)
{
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    t = glm::vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = glm::vec3(c, sign + n.y * n.y * a, -n.y);
}

} // namespace vplgi
