// Virtual point lights as the VPL techniques publish them (SMCIR section 3.1, MATH.md 1.4).
//
// A VPL y is a diffuse (cosine) emitter: it carries the exitant radiance L(y) of the surface it
// sits on and the density p(y) [1/m^2] of VPL positions there; its intensity is I(y) = L(y) / p(y)
// [W/sr] (eq. 6). With n valid VPLs the indirect radiance at a shaded point x is (eq. 5, one primary
// hit per pixel):
//     L_ind(x -> eye) = (1/n) sum_i f(x, w_o, w_i) * G(x <-> y_i) * V(x, y_i) * I(y_i),
//     G = cos+(n_x . w_i) cos+(n_y . -w_i) / |x - y_i|^2     (clamped to G_max by the renderer)
//
// One convention everywhere (CPU gather, GPU shading): n is the number of *valid* slots, and the
// densities are normalised by the same n (eq. 7 with n for I), so p integrates to 1 over the set and
// a set that is short of its budget (after initialisation, in open scenes, after cleared slots) is
// neither too dark nor too bright. The paper writes I for both; they agree when the set is full.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace vplgi {

struct VPL {
    glm::vec3 position{0.0f};  // [m], on a surface
    glm::vec3 normal{0.0f, 1.0f, 0.0f}; // unit, the side it emits towards
    glm::vec3 radiance{0.0f};  // L(y): exitant radiance of the diffuse surface [W/(m^2 sr)]
    float density = 0.0f;      // p(y): VPL positions per unit area [1/m^2], integrates to 1 over the set
    bool valid = false;        // slot in use

    // Numeric guard: a density so small (or a radiance so large) that L / p overflows, or a NaN
    // anywhere, gives no light rather than an infinite one that would poison every pixel it reaches.
    glm::vec3 intensity() const
    {
        if (!(density > 0.0f)) return glm::vec3(0.0f);
        const glm::vec3 i = radiance / density;
        return std::isfinite(i.x) && std::isfinite(i.y) && std::isfinite(i.z) ? i : glm::vec3(0.0f);
    }
};

// The VPL set as a renderer sees it: stable slots (a VPL keeps its slot while it lives) and the
// slots that changed since the previous publication (the GPU re-renders only their shadow maps).
struct VPLSet {
    std::vector<VPL> slots;              // size = VPL budget I
    std::vector<std::uint32_t> changed;  // slots whose position or normal changed (moved, created)
    std::uint64_t generation = 0;        // increases with every published set
    // Number of valid slots: the n of the estimator and of the densities.
    std::size_t validCount() const
    {
        std::size_t n = 0;
        for (const VPL& v : slots) n += v.valid ? 1 : 0;
        return n;
    }
};

} // namespace vplgi
