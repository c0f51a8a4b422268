// What the CPU side knows about a ray hit: position, normals, texcoords and the evaluated material
// (textures applied exactly as the G-buffer pass does), plus the CPU evaluation of direct light
// with Embree visibility. Used by image tests, the path tracer and VPL samplers.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "glsl/shared/brdf.h"
#include "core/scene/direct_lights.h"
#include "core/trace/ray_scene.h"

namespace vplgi {

struct SurfacePoint {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};          // shading normal (normal-mapped), unit
    glm::vec3 geometricNormal{0.0f, 1.0f, 0.0f}; // unit, same side as `normal`
    glm::vec2 texcoord{0.0f};  // TEXCOORD_0
    glm::vec2 texcoord1{0.0f}; // TEXCOORD_1
    shared::SurfaceMaterial material{};
    glm::vec3 emission{0.0f};                    // emitted radiance [W/(m^2 sr)]
    int materialIndex = -1;
};

// The "untextured version of the scene" SMCIR generates its VPLs on (section 5: "we use an
// untextured version of the scene for the VPL generation and use average material colors as
// albedos. The path traced reference images use the same approximation"). Per material: the base
// colour factor times the mean of its base-colour texture (sRGB-decoded, as GL filters it), and the
// metallic and roughness factors times the means of their texture channels. Normal maps are off.
// Alpha-masked materials average over the texels their mask keeps (rays never see the others).
// COLOR_0 enters as the material's area-weighted mean vertex colour; a texture's mean is over the
// whole image, whatever part of it KHR_texture_transform maps onto the surface.
struct UntexturedMaterials {
    std::vector<glm::vec3> baseColor; // per material, linear RGB
    std::vector<float> metallic;
    std::vector<float> roughness;
};
UntexturedMaterials computeUntexturedMaterials(const Scene& scene);

// Surface data at a hit; `towardsViewer` decides the side of double-sided materials. With
// `untextured`, the material is that table's (mean albedo, no normal map); emission stays textured
// (emitters are lights, and the direct pass and the path tracer sample them as they are).
SurfacePoint surfaceAt(const Scene& scene, const Hit& hit, const glm::vec3& towardsViewer,
                       const UntexturedMaterials* untextured = nullptr);

// Bilinear, repeat-wrapped texture lookup; sRGB-decoded when `srgb`. Returns RGBA in [0,1].
glm::vec4 sampleImage(const Image& image, glm::vec2 uv, bool srgb);

// Whether a point of material `m` is present (glsl/shared/alpha_mask.h): always for opaque
// materials; for masked ones where the base colour's alpha (factor times COLOR_0's alpha
// `vertexAlpha` times the texture's at `baseColorUV`, its set and transform applied, bilinear) is
// >= the cutoff.
bool alphaMaskKeeps(const Scene& scene, const Material& m, glm::vec2 baseColorUV, float vertexAlpha = 1.0f);
// The same at Embree barycentrics (u, v) on triangle `triangle` of `mesh`, which has material `m`.
bool alphaMaskKeeps(const Scene& scene, const Material& m, const Mesh& mesh, int triangle, glm::vec2 barycentric);
// The fraction of a material's texture area that its alpha mask keeps (1 for opaque materials): the
// fraction of texels kept, i.e. the mask of the nearest-texel reconstruction (bilinear filtering moves
// the outline by under a texel). Not in any paper: what the untextured material tables and LightSkin's
// cache areas scale by.
float alphaCoverage(const Scene& scene, const Material& m);

// Reflected direct radiance towards `wo` (unit, away from the surface) from every emitter of the
// set, with Embree shadow rays. Excludes the point's own emission. With `shadowRays`, adds the number
// of shadow rays it cast there (the samplers' ray counts).
glm::vec3 evaluateDirectLight(const RayScene& rays, const DirectLightSet& lights, const SurfacePoint& point,
                              const glm::vec3& wo, std::uint64_t* shadowRays = nullptr);

} // namespace vplgi
