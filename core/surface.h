// What the CPU side knows about a ray hit: position, normals, texcoords and the evaluated material
// (textures applied exactly as the G-buffer pass does), plus the CPU evaluation of direct light
// with Embree visibility. Used by image tests, the path tracer and VPL samplers.
#pragma once

#include <glm/glm.hpp>

#include "../glsl/shared/brdf.h"
#include "direct_lights.h"
#include "ray_scene.h"

namespace vplgi {

struct SurfacePoint {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};          // shading normal (normal-mapped), unit
    glm::vec3 geometricNormal{0.0f, 1.0f, 0.0f}; // unit, same side as `normal`
    glm::vec2 texcoord{0.0f};
    shared::SurfaceMaterial material{};
    glm::vec3 emission{0.0f};                    // emitted radiance [W/(m^2 sr)]
    int materialIndex = -1;
};

// Surface data at a hit; `towardsViewer` decides the side of double-sided materials.
SurfacePoint surfaceAt(const Scene& scene, const Hit& hit, const glm::vec3& towardsViewer);

// Bilinear, repeat-wrapped texture lookup; sRGB-decoded when `srgb`. Returns RGBA in [0,1].
glm::vec4 sampleImage(const Image& image, glm::vec2 uv, bool srgb);

// Reflected direct radiance towards `wo` (unit, away from the surface) from every emitter of the
// set, with Embree shadow rays. Excludes the point's own emission.
glm::vec3 evaluateDirectLight(const RayScene& rays, const DirectLightSet& lights, const SurfacePoint& point,
                              const glm::vec3& wo);

} // namespace vplgi
