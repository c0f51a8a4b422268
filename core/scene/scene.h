// core::Scene: the one description of a scene that both the GL renderer and the Embree side read.
//
// Conventions (also in README.md, "Scene format"):
//  - Units: metres. Right-handed, y up. Cameras look along their local -z.
//  - Radiometry is RGB, linear (Rec.709 primaries):
//      point/spot light  `intensity` * `color`   = radiant intensity   [W/sr]
//      directional light `intensity` * `color`   = irradiance on a surface facing the light [W/m^2]
//      material `emission`                        = emitted radiance    [W/(m^2 sr)]
//    glTF photometric values (candela, lux, nits) are taken as these radiometric numbers unchanged.
//  - Geometry: meshes hold object-space triangles; instances place meshes in the world
//    (glTF nodes flattened, node transforms kept as worldFromObject).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace vplgi {

struct Vertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 1.0f, 0.0f};
    glm::vec2 texcoord{0.0f};                  // TEXCOORD_0
    glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f}; // xyz tangent, w = bitangent sign (glTF convention)
    glm::vec2 texcoord1{0.0f};                 // TEXCOORD_1
    glm::vec4 color{1.0f};                     // COLOR_0 (linear RGBA), multiplies the base colour
};

// 8-bit RGBA image, rows top to bottom (as glTF/stb deliver them).
struct Image {
    std::string name;
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba; // width * height * 4
};

// Texture reference: an image index (-1 = none), the UV set it reads (TEXCOORD_0 or _1) and its
// KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv, R turning the UVs by `rotation`
// radians from +u towards -v (counter-clockwise with v down, the extension's example).
struct TextureRef {
    int image = -1;
    int texCoord = 0;
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;
    glm::vec2 scale{1.0f};
    bool valid() const { return image >= 0; }
    // The 3x3 affine matrix of the transform (column-major, applied to (u, v, 1)).
    glm::mat3 uvTransform() const
    {
        const float c = std::cos(rotation), s = std::sin(rotation);
        return glm::mat3(c * scale.x, -s * scale.x, 0.0f, s * scale.y, c * scale.y, 0.0f, offset.x, offset.y, 1.0f);
    }
    glm::vec2 uv(const glm::vec2& uv0, const glm::vec2& uv1) const
    {
        return glm::vec2(uvTransform() * glm::vec3(texCoord == 0 ? uv0 : uv1, 1.0f));
    }
};

// glTF 2.0 metallic-roughness material plus KHR_materials_specular's factor and emission.
// The BRDF is defined once in glsl/shared/brdf.h for both GLSL and C++.
struct Material {
    std::string name;
    glm::vec4 baseColor{1.0f};  // linear RGBA factor; multiplies baseColorTexture (sRGB-encoded)
    TextureRef baseColorTexture;
    float metallic = 0.0f;      // [0,1]
    float roughness = 1.0f;     // perceptual roughness [0,1]; alpha = roughness^2
    TextureRef metallicRoughnessTexture; // G = roughness, B = metallic (glTF)
    float specular = 1.0f;      // scales the dielectric F0 of 0.04 (KHR_materials_specular); 0 = pure Lambert
    glm::vec3 emission{0.0f};   // emitted radiance [W/(m^2 sr)] (emissiveFactor * emissive_strength)
    TextureRef emissionTexture;
    TextureRef normalTexture;
    float normalScale = 1.0f;
    // One back-face rule everywhere (docs/back-faces.md): a single-sided surface exists from its front
    // only. From behind it is absent: the rasterizer culls it in the camera and in every light view,
    // rays pass through it (an Embree filter), it neither casts shadows nor reflects light there.
    // glTF's front is the counter-clockwise side, clockwise under a mirroring transform
    // (Instance::winding). Double-sided surfaces are shaded on the side they are seen from.
    bool doubleSided = false;
    // glTF alphaMode: OPAQUE ignores alpha; MASK keeps a point where the base colour's alpha
    // (factor times texture, level 0, bilinear) is >= alphaCutoff and makes it absent elsewhere, in
    // every pass that sees geometry and in every ray (glsl/shared/alpha_mask.h). The loader reads
    // BLEND as MASK at 0.5 (vplgi has no transparency), with a warning.
    enum class AlphaMode { Opaque, Mask };
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;

    bool isEmissive() const { return emission.r > 0.0f || emission.g > 0.0f || emission.b > 0.0f; }
    bool isMasked() const { return alphaMode == AlphaMode::Mask; }
};

// One triangle list with one material (a glTF primitive).
struct Mesh {
    std::string name;
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices; // 3 per triangle
    int material = 0;
    bool hasTangents = false;           // true when tangents were read or generated for normal mapping

    std::size_t triangleCount() const { return indices.size() / 3; }
};

struct Instance {
    int mesh = 0;
    glm::mat4 worldFromObject{1.0f};

    // glTF: a transform with a negative determinant mirrors, and its triangles' front is then the
    // clockwise side: -1, else 1. Multiplies cross(p1 - p0, p2 - p0) of the world corners to give the
    // front normal; the rasterizer takes it as glFrontFace(GL_CW).
    float winding() const { return glm::determinant(glm::mat3(worldFromObject)) < 0.0f ? -1.0f : 1.0f; }
};

enum class LightType { Point, Spot, Directional };

struct Light {
    std::string name;
    LightType type = LightType::Point;
    glm::vec3 position{0.0f};               // point, spot [m]
    glm::vec3 direction{0.0f, -1.0f, 0.0f}; // spot, directional: the direction light travels (unit)
    glm::vec3 color{1.0f};                  // linear RGB, multiplies intensity
    float intensity = 1.0f;                 // [W/sr] point/spot, [W/m^2] directional
    float innerConeAngle = 0.0f;            // spot: full intensity inside [rad]
    float outerConeAngle = 0.7853982f;      // spot: zero outside [rad] (glTF default pi/4)
    float range = 0.0f;                     // 0 = infinite (glTF); kept for completeness, not used for falloff

    glm::vec3 radiantIntensity() const { return color * intensity; }
};

struct Camera {
    std::string name;
    glm::vec3 position{0.0f, 0.0f, 5.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovY = 0.8f;    // vertical field of view [rad]
    float zNear = 0.05f;  // [m]
    float zFar = 1000.0f; // [m]

    glm::mat4 viewFromWorld() const;
    glm::mat4 clipFromView(float aspect) const; // OpenGL clip space, depth [-1,1]
};

// A keyframe of an animated camera or light. Fields not used by the target are ignored.
struct Keyframe {
    float time = 0.0f;        // [s]
    glm::vec3 position{0.0f}; // camera eye or light position
    glm::vec3 target{0.0f};   // camera target, or for lights position+direction (spot/directional aim)
};

// Piecewise-linear animation of one camera or light, named by target kind and name.
struct Animation {
    std::string name;
    enum class Target { Camera, Light } targetKind = Target::Camera;
    std::string targetName;
    std::vector<Keyframe> keys; // sorted by time, at least one
    float duration() const { return keys.empty() ? 0.0f : keys.back().time; }
};

struct AABB {
    glm::vec3 lower{1e30f};
    glm::vec3 upper{-1e30f};
    void extend(const glm::vec3& p) { lower = glm::min(lower, p); upper = glm::max(upper, p); }
    bool empty() const { return lower.x > upper.x; }
    glm::vec3 center() const { return 0.5f * (lower + upper); }
    glm::vec3 extent() const { return upper - lower; }
};

struct Scene {
    std::string name;          // for labels and reports
    std::string source;        // where it came from: "builtin:cornell", a path
    std::vector<Image> images;
    std::vector<Material> materials;
    std::vector<Mesh> meshes;
    std::vector<Instance> instances;
    std::vector<Light> lights;
    std::vector<Camera> cameras;       // cameras[0] is the default
    std::vector<Animation> animations;

    std::size_t triangleCount() const;   // over instances
    AABB worldBounds() const;            // over instances
    const Camera* findCamera(const std::string& name) const;
    const Light* findLight(const std::string& name) const;
    // Checks indices, material/mesh/image references and finite values; throws Error naming the problem.
    void validate() const;
};

// Fills smooth per-vertex normals (area-weighted face normals) for a mesh without normals.
void generateNormals(Mesh& mesh);
// Fills per-vertex tangents from texcoords (needed when the material has a normal map).
void generateTangents(Mesh& mesh, const TextureRef& normalTexture = TextureRef{});
// Camera placed to see the whole scene bounds (used when a scene has no camera).
Camera makeDefaultCamera(const AABB& bounds);
// World-space area of an instance's triangles, and of every instance's [m^2] (double sums).
double instanceSurfaceArea(const Scene& scene, const Instance& instance);
double sceneSurfaceArea(const Scene& scene);

// Applies an animation at time t (clamped to its key range) to the scene's camera or light.
void applyAnimation(Scene& scene, const Animation& animation, float time);

} // namespace vplgi
