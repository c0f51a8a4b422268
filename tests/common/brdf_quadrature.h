// Deterministic quadratures of the shared BRDF (glsl/shared/brdf.h) that resolve narrow GGX lobes,
// for checks that must not share anything with the path tracer's sampling code.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

#include "glsl/shared/brdf.h"

namespace vplgi::test {

// Integrates g(theta, phi) sin(theta) over the hemisphere theta in [0, pi/2], phi in [0, 2 pi), by
// the midpoint rule in s with theta = (pi/2) s^4, which puts most nodes near the pole: at
// alpha = 0.002 (kMinAlpha) the GGX lobe about the normal is ~0.002 rad wide and still gets
// hundreds of nodes. `phiSymmetric`: g is even in phi, so [0, pi] is integrated and doubled.
// T is double or glm::dvec3.
template <typename T, typename Integrand>
T integrateAboutNormal(Integrand g, int thetaNodes, int phiNodes, bool phiSymmetric)
{
    constexpr double pi = 3.14159265358979323846;
    const double phiRange = phiSymmetric ? pi : 2.0 * pi;
    T sum(0.0);
    for (int i = 0; i < thetaNodes; ++i) {
        const double s = (i + 0.5) / thetaNodes;
        const double theta = 0.5 * pi * s * s * s * s;
        const double dTheta = 2.0 * pi * s * s * s / thetaNodes; // d/ds of (pi/2) s^4, times ds
        for (int j = 0; j < phiNodes; ++j) {
            const double phi = phiRange * (j + 0.5) / phiNodes;
            sum += g(theta, phi) * (std::sin(theta) * dTheta * (phiRange / phiNodes));
        }
    }
    return phiSymmetric ? 2.0 * sum : sum;
}

// The unit vector at polar angle theta and azimuth phi about +z.
inline glm::vec3 polarDirection(double theta, double phi)
{
    return glm::vec3(static_cast<float>(std::sin(theta) * std::cos(phi)),
                     static_cast<float>(std::sin(theta) * std::sin(phi)), static_cast<float>(std::cos(theta)));
}

// Directional albedo int f_r(wo, wi) cos(theta_i) dwi [per channel] for a view at polar angle
// thetaO (the BRDF is isotropic: nothing else matters), integrated over half vectors h about the
// normal (wi = reflect(-wo, h), dwi = 4 (wo.h) dh), where the GGX lobe is narrow and centred for
// every view. Uses evaluateBRDF only.
inline glm::dvec3 directionalAlbedo(const shared::SurfaceMaterial& material, double thetaO, int thetaNodes = 2000,
                                    int phiNodes = 256)
{
    const glm::vec3 n(0.0f, 0.0f, 1.0f);
    const glm::vec3 wo(static_cast<float>(std::sin(thetaO)), 0.0f, static_cast<float>(std::cos(thetaO)));
    return integrateAboutNormal<glm::dvec3>(
        [&](double theta, double phi) {
            const glm::vec3 h = polarDirection(theta, phi);
            const float woh = glm::dot(wo, h);
            if (woh <= 0.0f) return glm::dvec3(0.0);
            const glm::vec3 wi = 2.0f * woh * h - wo;
            if (wi.z <= 0.0f) return glm::dvec3(0.0);
            return glm::dvec3(shared::evaluateBRDF(material, n, wo, wi)) * (static_cast<double>(wi.z) * 4.0 * woh);
        },
        thetaNodes, phiNodes, true);
}

} // namespace vplgi::test
