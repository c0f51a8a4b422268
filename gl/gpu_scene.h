// The scene on the GPU: one vertex/index buffer pair per mesh, material textures (sRGB where glTF
// says so), and a draw loop over instances. Built once from core::Scene; read-only afterwards.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "api/objects.h"
#include "api/shader_loader.h"
#include "core/scene/scene.h"

namespace vplgi {

// The program of a pass that rasterizes the scene, in two variants: the one it was loaded as, for
// opaque materials, and one compiled with VPLGI_ALPHA_MASK (glsl/lib/alpha_mask.glsl) for
// alpha-masked materials, compiled on first use (scenes without masks never build it). Only the
// masked variant has a discard, so opaque draws keep early depth tests. set() sets a uniform on both.
class SceneProgram {
public:
    SceneProgram() = default;
    SceneProgram(const gl::ShaderLoader& shaders, std::string name, std::vector<gl::ShaderStage> stages,
                 std::vector<std::string> defines = {});

    const gl::Program& opaque() const { return mOpaque; }
    const gl::Program& masked() const;

    template <typename T>
    void set(const char* uniform, const T& value) const
    {
        mOpaque.set(uniform, value);
        if (mMasked) mMasked.set(uniform, value);
        else mPending[uniform] = [value](const gl::Program& p, const char* u) { p.set(u, value); };
    }

private:
    gl::ShaderLoader mShaders;
    std::string mName;
    std::vector<gl::ShaderStage> mStages;
    std::vector<std::string> mDefines;
    gl::Program mOpaque;
    mutable gl::Program mMasked;
    // What set() set before the masked variant was built, replayed on it then.
    mutable std::map<std::string, std::function<void(const gl::Program&, const char*)>> mPending;
};

class GpuScene {
public:
    explicit GpuScene(const Scene& scene);

    enum class Bind { Geometry, GeometryAndMaterial };
    // Draws every instance with the program's opaque variant, or its masked one for alpha-masked
    // materials (binding each as it goes): sets uWorldFromObject (and uNormalFromObject + material
    // uniforms/textures with GeometryAndMaterial; masked materials get their base colour texture and
    // uAlphaMask either way); instanceCount > 1 issues instanced draws (layered shadow rendering).
    // Leaves no program bound.
    void draw(const SceneProgram& program, Bind bind, GLsizei instanceCount = 1) const;

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
    static void setTextureUVs(const gl::Program& program, const Material& material);

    const Scene& mScene;
    std::vector<MeshBuffers> mMeshes;
    std::map<std::pair<int, bool>, gl::Texture> mImageTextures;
    gl::Texture mWhite;      // default for colour and metallic-roughness textures
    gl::Texture mFlatNormal; // default normal map (0.5, 0.5, 1)
    gl::Sampler mMaterialSampler;
    gl::Sampler mMaskSampler; // level 0, bilinear, no anisotropy: what the alpha test reads in depth-only passes
};

} // namespace vplgi
