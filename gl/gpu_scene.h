// The scene on the GPU: one vertex/index buffer pair per mesh, material textures (sRGB where glTF
// says so), and a draw loop over instances. Built once from core::Scene; read-only afterwards.
#pragma once

#include <map>
#include <utility>
#include <vector>

#include "api/objects.h"
#include "core/scene/scene.h"

namespace vplgi {

class GpuScene {
public:
    explicit GpuScene(const Scene& scene);

    enum class Bind { Geometry, GeometryAndMaterial };
    // Draws every instance with `program` bound by the caller: sets uWorldFromObject (and
    // uNormalFromObject + material uniforms/textures with GeometryAndMaterial); instanceCount > 1
    // issues instanced draws (layered shadow rendering).
    void draw(const gl::Program& program, Bind bind, GLsizei instanceCount = 1) const;

    const Scene& scene() const { return mScene; }

private:
    struct MeshBuffers {
        gl::Buffer vertices;
        gl::Buffer indices;
        gl::VertexArray vertexArray;
        GLsizei indexCount = 0;
    };
    const gl::Texture& imageTexture(int image, bool srgb) const;
    void bindMaterial(const gl::Program& program, const Material& material, bool hasTangents) const;

    const Scene& mScene;
    std::vector<MeshBuffers> mMeshes;
    std::map<std::pair<int, bool>, gl::Texture> mImageTextures;
    gl::Texture mWhite;      // default for colour and metallic-roughness textures
    gl::Texture mFlatNormal; // default normal map (0.5, 0.5, 1)
    gl::Sampler mMaterialSampler;
};

} // namespace vplgi
