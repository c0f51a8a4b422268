#include "gbuffer_pass.h"

#include "glsl/shared/bindings.h"

namespace vplgi {

namespace {

gl::Program loadProgram(const gl::ShaderLoader& shaders)
{
    return shaders.load("gbuffer", {{GL_VERTEX_SHADER, "passes/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "passes/gbuffer.frag"}});
}

} // namespace

void GBuffer::bindForReading() const
{
    using namespace shared;
    glBindTextureUnit(kUnitGBufferPosition, position.id());
    glBindTextureUnit(kUnitGBufferNormal, normal.id());
    glBindTextureUnit(kUnitGBufferBaseColor, baseColor.id());
    glBindTextureUnit(kUnitGBufferEmission, emission.id());
    for (int unit : {kUnitGBufferPosition, kUnitGBufferNormal, kUnitGBufferBaseColor, kUnitGBufferEmission})
        glBindSampler(static_cast<GLuint>(unit), 0);
}

GBufferPass::GBufferPass(const gl::ShaderLoader& shaders) : mProgram(loadProgram(shaders)) {}

void GBufferPass::reloadShaders(const gl::ShaderLoader& shaders)
{
    mProgram = loadProgram(shaders);
}

void GBufferPass::resize(int width, int height)
{
    if (mGBuffer.width == width && mGBuffer.height == height) return;
    auto target = [&](const char* name, GLenum format) {
        gl::TextureDesc desc;
        desc.format = format;
        desc.width = width;
        desc.height = height;
        return gl::Texture(std::string("gbuffer ") + name, desc);
    };
    mGBuffer.position = target("position", GL_RGBA32F);
    mGBuffer.normal = target("normal", GL_RGBA16F);
    mGBuffer.baseColor = target("base colour", GL_RGBA16F);
    mGBuffer.emission = target("emission", GL_RGBA16F);
    mGBuffer.depth = target("depth", GL_DEPTH_COMPONENT32F);
    mGBuffer.framebuffer = gl::Framebuffer("gbuffer");
    const gl::Framebuffer& fb = mGBuffer.framebuffer;
    fb.attach(GL_COLOR_ATTACHMENT0, mGBuffer.position);
    fb.attach(GL_COLOR_ATTACHMENT1, mGBuffer.normal);
    fb.attach(GL_COLOR_ATTACHMENT2, mGBuffer.baseColor);
    fb.attach(GL_COLOR_ATTACHMENT3, mGBuffer.emission);
    fb.attach(GL_DEPTH_ATTACHMENT, mGBuffer.depth);
    fb.setDrawBuffers(4);
    fb.checkComplete();
    mGBuffer.width = width;
    mGBuffer.height = height;
}

void GBufferPass::render(const GpuScene& scene, int width, int height)
{
    resize(width, height);
    const GLuint fb = mGBuffer.framebuffer.id();
    glBindFramebuffer(GL_FRAMEBUFFER, fb);
    glViewport(0, 0, width, height);
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    for (int i = 0; i < 4; ++i) glClearNamedFramebufferfv(fb, GL_COLOR, i, zero);
    const float far = 1.0f;
    glClearNamedFramebufferfv(fb, GL_DEPTH, 0, &far);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glUseProgram(mProgram.id());
    scene.draw(mProgram, GpuScene::Bind::GeometryAndMaterial);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
}

} // namespace vplgi
