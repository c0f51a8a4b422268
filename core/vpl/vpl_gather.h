// The CPU renderer of a VPL set (SMCIR Fig. 8, "All VPLs - ray tracing"): every pixel gathers every
// VPL with Embree visibility and the same geometry-term clamping the GPU uses, so the quality of a
// VPL distribution is measured apart from shadow-map artefacts. Technique `smcir-rt` and the tests
// use it.
//
//   L_ind(x -> eye) = (1/n) sum_i f(x, w_o, w_i) min(G(x <-> y_i), G_max) V(x, y_i) I(y_i)   (SMCIR eq. 5/6)
//
// with n the number of valid VPLs (core/vpl/vpl.h: the densities are normalised by the same n), f the
// shared BRDF (glsl/shared/brdf.h) and I(y) = L(y)/p(y).
#pragma once

#include <set>
#include <string>

#include <glm/glm.hpp>

#include "core/util/image_io.h"
#include "core/trace/path_tracer.h"
#include "core/trace/ray_scene.h"
#include "core/scene/surface.h"
#include "core/vpl/vpl.h"

namespace vplgi {

struct VPLGatherParams {
    float clampGeometry = 0.0f; // G_max [1/m^2]; 0 = no clamping
    int interleaveTile = 1;     // > 1: interleaved sampling with tiles of this size, the subsets and
                                // scale of glsl/shared/vpl.h (GL pixel rows, bottom up, as the GPU)
};

// G_max = 1/d^2 with d = clampScale * sceneDiagonal / sqrt(vplCount): the clamp follows the expected
// VPL spacing, so it relaxes as the budget grows (SMCIR 5.4; smcir.clampScale, ir.clampScale).
// 0 when clampScale is 0 (no clamping).
float clampGeometryFor(float clampScale, int vplCount, float sceneDiagonal);

// What a path-traced reference must simulate to be compared with a VPL method (smcir, smcir-rt, ir):
// untextured bounces unless its VPLs see textures (SMCIR section 5), the same clamp (5.4; 0 =
// none), and the same bounce cap: the reflection at the primary hit plus `vplBounces`, the most
// reflections the light a VPL carries has undergone, counting the one at the VPL, and the VPLs'
// Lambert assumption: `diffuseVertices` (reference.diffuseVertices: 1 for SMCIR, whose VPL reflects its
// diffuse lobe while its radiance paths keep the BRDF; 2 for IR, whose light paths bounce diffusely).
// Keys in `explicitKeys` (reference.*) are left as the user set them.
void configureVPLReference(bool texturedVPLs, float clampGeometry, int vplBounces, int diffuseVertices,
                           PathTracerParams& reference, const std::set<std::string>& explicitKeys);

// Indirect radiance reflected at `point` towards `wo` (unit, away from the surface), from the VPLs
// of interleaving class `subset` (slots i with i mod tile^2 = subset; all of them when tile = 1).
glm::vec3 gatherVPLs(const RayScene& rays, const VPLSet& vpls, const SurfacePoint& point, const glm::vec3& wo,
                     const VPLGatherParams& params, int subset = 0);

// The indirect image of `camera` (pixel centres, rows top to bottom); pixels that see nothing are 0.
// Multi-threaded (TBB), deterministic.
ImageRGBA32F renderVPLGather(const Scene& scene, const RayScene& rays, const Camera& camera, int width, int height,
                             const VPLSet& vpls, const VPLGatherParams& params);

} // namespace vplgi
