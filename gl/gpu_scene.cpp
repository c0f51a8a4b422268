#include "gpu_scene.h"

#include <cstddef>

#include <glm/gtc/matrix_inverse.hpp>

#include "core/scene/image_downscale.h"
#include "gl/api/limits.h"
#include "glsl/shared/bindings.h"

namespace vplgi {

namespace {

gl::Texture makeTexture(const std::string& name, int width, int height, bool srgb, const std::uint8_t* rgba)
{
    gl::TextureDesc desc;
    desc.format = srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8;
    desc.width = width;
    desc.height = height;
    desc.levels = 0; // full mip chain
    gl::Texture texture(name, desc);
    // glTF images have their first row at v = 0 and GL samples row 0 at t = 0: upload as is.
    glTextureSubImage2D(texture.id(), 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glGenerateTextureMipmap(texture.id());
    return texture;
}

} // namespace

SceneProgram::SceneProgram(const gl::ShaderLoader& shaders, std::string name, std::vector<gl::ShaderStage> stages,
                           std::vector<std::string> defines)
    : mShaders(shaders), mName(std::move(name)), mStages(std::move(stages)), mDefines(std::move(defines)),
      mOpaque(mShaders.load(mName, mStages, mDefines))
{
}

const gl::Program& SceneProgram::masked() const
{
    if (!mMasked) {
        std::vector<std::string> defines = mDefines;
        defines.push_back("VPLGI_ALPHA_MASK");
        mMasked = mShaders.load(mName + " (alpha mask)", mStages, defines);
        for (const auto& [uniform, setter] : mPending)
            setter(mMasked, uniform.c_str());
        mPending.clear();
    }
    return mMasked;
}

GpuScene::GpuScene(const Scene& scene) : mScene(scene)
{
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& mesh = scene.meshes[i];
        MeshBuffers buffers;
        const std::string name = "mesh " + std::to_string(i) + " " + mesh.name;
        buffers.vertices = gl::Buffer(name + " vertices", static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(Vertex)),
                                      mesh.vertices.data(), false);
        buffers.indices = gl::Buffer(name + " indices", static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                                     mesh.indices.data(), false);
        buffers.indexCount = static_cast<GLsizei>(mesh.indices.size());
        buffers.vertexArray = gl::VertexArray(name);
        GLuint vao = buffers.vertexArray.id();
        glVertexArrayVertexBuffer(vao, 0, buffers.vertices.id(), 0, sizeof(Vertex));
        glVertexArrayElementBuffer(vao, buffers.indices.id());
        auto attribute = [vao](GLuint location, GLint size, std::size_t offset) {
            glEnableVertexArrayAttrib(vao, location);
            glVertexArrayAttribFormat(vao, location, size, GL_FLOAT, GL_FALSE, static_cast<GLuint>(offset));
            glVertexArrayAttribBinding(vao, location, 0);
        };
        attribute(0, 3, offsetof(Vertex, position));
        attribute(1, 3, offsetof(Vertex, normal));
        attribute(2, 2, offsetof(Vertex, texcoord));
        attribute(3, 4, offsetof(Vertex, tangent));
        attribute(4, 2, offsetof(Vertex, texcoord1));
        attribute(5, 4, offsetof(Vertex, color));
        mMeshes.push_back(std::move(buffers));
    }
    const std::uint8_t white[4] = {255, 255, 255, 255};
    const std::uint8_t flat[4] = {128, 128, 255, 255};
    mWhite = makeTexture("default white", 1, 1, false, white);
    mFlatNormal = makeTexture("default flat normal", 1, 1, false, flat);
    gl::SamplerDesc samplerDesc;
    samplerDesc.minFilter = GL_LINEAR_MIPMAP_LINEAR;
    samplerDesc.wrap = GL_REPEAT;
    samplerDesc.maxAnisotropy = 8.0f;
    mMaterialSampler = gl::Sampler("material sampler", samplerDesc);
    // The alpha test reads level 0 bilinearly (glsl/shared/alpha_mask.h); with the material sampler
    // (trilinear, 8x anisotropic) bound, llvmpipe took 19x longer for ir on cutout at 48x36 (37.5 s
    // against 2.0 s, nearly all in the 2048 VPLs' shadow maps), though textureLod reads one level.
    gl::SamplerDesc maskDesc;
    maskDesc.minFilter = GL_LINEAR;
    maskDesc.wrap = GL_REPEAT;
    mMaskSampler = gl::Sampler("alpha mask sampler", maskDesc);
    // Upload every image in the formats its materials use it in.
    for (const Material& m : scene.materials) {
        if (m.baseColorTexture.valid()) imageTexture(m.baseColorTexture.image, true);
        if (m.emissionTexture.valid()) imageTexture(m.emissionTexture.image, true);
        if (m.metallicRoughnessTexture.valid()) imageTexture(m.metallicRoughnessTexture.image, false);
        if (m.normalTexture.valid()) imageTexture(m.normalTexture.image, false);
    }
}

const gl::Texture& GpuScene::imageTexture(int image, bool srgb) const
{
    auto key = std::make_pair(image, srgb);
    auto it = mImageTextures.find(key);
    if (it != mImageTextures.end()) return it->second;
    const Image& loaded = mScene.images[image];
    const std::string name = "image " + std::to_string(image) + " " + loaded.name;
    // The loader caps images at kMaxImageEdge; an implementation with a smaller GL_MAX_TEXTURE_SIZE
    // gets a downscaled copy (with a warning) instead of a GL error and a missing texture.
    Image downscaled;
    const int maxEdge = gl::queryLimits().maxTextureSize;
    if (maxEdge > 0 && (loaded.width > maxEdge || loaded.height > maxEdge)) {
        downscaled = loaded;
        downscaleToFit(downscaled, maxEdge, name, "GL_MAX_TEXTURE_SIZE " + std::to_string(maxEdge));
    }
    const Image& img = downscaled.rgba.empty() ? loaded : downscaled;
    auto& textures = const_cast<std::map<std::pair<int, bool>, gl::Texture>&>(mImageTextures);
    return textures
        .emplace(key, makeTexture(name + (srgb ? " (sRGB)" : ""), img.width, img.height, srgb, img.rgba.data()))
        .first->second;
}

void GpuScene::setTextureUVs(const gl::Program& program, const Material& m)
{
    // glsl/lib/material_uv.glsl: per texture unit 0-3, its KHR_texture_transform and UV set.
    const TextureRef* refs[4] = {};
    refs[shared::kUnitBaseColor] = &m.baseColorTexture;
    refs[shared::kUnitMetallicRoughness] = &m.metallicRoughnessTexture;
    refs[shared::kUnitEmission] = &m.emissionTexture;
    refs[shared::kUnitNormalMap] = &m.normalTexture;
    glm::mat3 transforms[4];
    glm::ivec4 sets(0);
    for (int unit = 0; unit < 4; ++unit) {
        transforms[unit] = refs[unit]->uvTransform();
        sets[unit] = refs[unit]->texCoord;
    }
    glProgramUniformMatrix3fv(program.id(), program.uniformLocation("uTextureTransform"), 4, GL_FALSE, &transforms[0][0][0]);
    glProgramUniform4i(program.id(), program.uniformLocation("uTextureSet"), sets.x, sets.y, sets.z, sets.w);
}

void GpuScene::bindMaterial(const gl::Program& program, const Material& m, bool hasTangents) const
{
    using namespace shared;
    auto bindTexture = [&](int unit, const TextureRef& ref, bool srgb, const gl::Texture& fallback) {
        glBindTextureUnit(static_cast<GLuint>(unit), ref.valid() ? imageTexture(ref.image, srgb).id() : fallback.id());
        glBindSampler(static_cast<GLuint>(unit), mMaterialSampler.id());
    };
    bindTexture(kUnitBaseColor, m.baseColorTexture, true, mWhite);
    bindTexture(kUnitMetallicRoughness, m.metallicRoughnessTexture, false, mWhite);
    bindTexture(kUnitEmission, m.emissionTexture, true, mWhite);
    bindTexture(kUnitNormalMap, m.normalTexture, false, mFlatNormal);
    program.set("uBaseColor", m.baseColor);
    program.set("uMaterial", glm::vec4(m.metallic, m.roughness, m.specular, m.normalScale));
    program.set("uEmission", glm::vec4(m.emission, 0.0f));
    setTextureUVs(program, m);
    glProgramUniform4i(program.id(), program.uniformLocation("uTextures"),
                       m.normalTexture.valid() && hasTangents ? 1 : 0, m.doubleSided ? 1 : 0, 0, 0);
}

void GpuScene::draw(const SceneProgram& programs, Bind bind, GLsizei instanceCount) const
{
    GLuint bound = 0;
    for (const Instance& instance : mScene.instances) {
        const Mesh& mesh = mScene.meshes[instance.mesh];
        const MeshBuffers& buffers = mMeshes[instance.mesh];
        if (buffers.indexCount == 0) continue;
        const Material& material = mScene.materials[mesh.material];
        const gl::Program& program = material.isMasked() ? programs.masked() : programs.opaque();
        if (program.id() != bound) {
            glUseProgram(program.id());
            bound = program.id();
        }
        program.set("uWorldFromObject", instance.worldFromObject);
        if (material.isMasked()) {
            // glsl/lib/alpha_mask.glsl: the base colour texture's alpha (level 0) times the factor's;
            // bindMaterial binds the texture and its UVs when the pass takes the whole material.
            program.set("uAlphaMask", glm::vec2(material.alphaCutoff, material.baseColor.a));
            if (bind == Bind::Geometry) {
                glBindTextureUnit(shared::kUnitBaseColor, material.baseColorTexture.valid()
                                                              ? imageTexture(material.baseColorTexture.image, true).id()
                                                              : mWhite.id());
                glBindSampler(shared::kUnitBaseColor, mMaskSampler.id());
                setTextureUVs(program, material);
            }
        }
        if (bind == Bind::GeometryAndMaterial) {
            program.set("uNormalFromObject", glm::mat4(glm::inverseTranspose(glm::mat3(instance.worldFromObject))));
            bindMaterial(program, material, mesh.hasTangents);
        }
        // The back-face rule (Material::doubleSided): single-sided surfaces are culled from behind in
        // every pass, the camera's and every light view's (all right-handed, light_view.h, so the
        // winding alone decides); a mirroring instance's front is clockwise.
        if (material.doubleSided) glDisable(GL_CULL_FACE);
        else glEnable(GL_CULL_FACE);
        glFrontFace(instance.winding() < 0.0f ? GL_CW : GL_CCW);
        glBindVertexArray(buffers.vertexArray.id());
        glDrawElementsInstanced(GL_TRIANGLES, buffers.indexCount, GL_UNSIGNED_INT, nullptr, instanceCount);
    }
    glBindVertexArray(0);
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
    glUseProgram(0);
}

} // namespace vplgi
