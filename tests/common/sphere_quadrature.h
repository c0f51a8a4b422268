// A deterministic quadrature over the whole sphere that resolves narrow lobes about a chosen axis,
// for checking the spherical-Gaussian maths (glsl/shared/sg.h) without Monte Carlo noise.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

namespace vplgi::test {

// Integrates g(w) dw over the sphere, w a glm::dvec3, by the midpoint rule in s with
// theta = pi s^4 from `axis` (any length; renormalised here): nodes cluster at the axis, where the lobes under test
// peak (a lobe of width 1e-3 rad still gets ~100 theta nodes with 2000 in all), and phi in [0, 2 pi) uniformly
// (spectrally accurate for smooth periodic integrands). T is double or glm::dvec3.
template <typename T, typename Integrand>
T integrateSphereAbout(const glm::dvec3& unnormalisedAxis, Integrand g, int thetaNodes, int phiNodes)
{
    constexpr double pi = 3.14159265358979323846;
    // Renormalised: a float axis is unit only to ~6e-8, and so would be the nodes near it, which a
    // lobe of sharpness 1e6 turns into a 6% error.
    const glm::dvec3 axis = glm::normalize(unnormalisedAxis);
    // Orthonormal tangents of the axis (Duff et al. 2017), in double.
    const double sign = std::copysign(1.0, axis.z);
    const double a = -1.0 / (sign + axis.z);
    const double c = axis.x * axis.y * a;
    const glm::dvec3 t(1.0 + sign * axis.x * axis.x * a, sign * c, -sign * axis.x);
    const glm::dvec3 b(c, sign + axis.y * axis.y * a, -axis.y);
    T sum(0.0);
    for (int i = 0; i < thetaNodes; ++i) {
        const double s = (i + 0.5) / thetaNodes;
        const double theta = pi * s * s * s * s;
        const double weight = std::sin(theta) * 4.0 * pi * s * s * s / thetaNodes * (2.0 * pi / phiNodes);
        const double sinTheta = std::sin(theta), cosTheta = std::cos(theta);
        for (int j = 0; j < phiNodes; ++j) {
            const double phi = 2.0 * pi * (j + 0.5) / phiNodes;
            const glm::dvec3 w = sinTheta * std::cos(phi) * t + sinTheta * std::sin(phi) * b + cosTheta * axis;
            sum += g(w) * weight;
        }
    }
    return sum;
}

} // namespace vplgi::test
