#include "gbuffer_pass.h"

#include "glsl/shared/bindings.h"

namespace vplgi {

namespace {

SceneProgram loadProgram(const gl::ShaderLoader& shaders)
{
    return SceneProgram(shaders, "gbuffer",
                        {{GL_VERTEX_SHADER, "passes/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "passes/gbuffer.frag"}});
}

} // namespace

void GBuffer::bindForReading() const
{
    using namespace shared;
    glBindTextureUnit(kUnitGBufferPosition, position().id());
    glBindTextureUnit(kUnitGBufferNormal, normal().id());
    glBindTextureUnit(kUnitGBufferBaseColor, baseColor().id());
    glBindTextureUnit(kUnitGBufferEmission, emission().id());
    glBindTextureUnit(kUnitGBufferSurfaceNormals, surfaceNormals().id());
    for (int unit : {kUnitGBufferPosition, kUnitGBufferNormal, kUnitGBufferBaseColor, kUnitGBufferEmission,
                     kUnitGBufferSurfaceNormals})
        glBindSampler(static_cast<GLuint>(unit), 0);
}

GBufferPass::GBufferPass(const gl::ShaderLoader& shaders) : mProgram(loadProgram(shaders))
{
    gl::RenderTargetDesc desc;
    desc.colorFormats = {GL_RGBA32F, GL_RGBA16F, GL_RGBA16F, GL_RGBA16F, GL_RGBA16F};
    desc.colorNames = {"position", "normal", "base colour", "emission", "surface normals"};
    desc.depthFormat = GL_DEPTH_COMPONENT32F;
    mGBuffer.target = gl::RenderTarget("gbuffer", desc);
}

void GBufferPass::reloadShaders(const gl::ShaderLoader& shaders)
{
    mProgram = loadProgram(shaders);
}

void GBufferPass::render(const GpuScene& scene, int width, int height)
{
    mGBuffer.target.resize(width, height);
    mGBuffer.target.bindForDrawing();
    mGBuffer.target.clear(glm::vec4(0.0f), 1.0f);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    scene.draw(mProgram, GpuScene::Bind::GeometryAndMaterial);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
}

} // namespace vplgi
