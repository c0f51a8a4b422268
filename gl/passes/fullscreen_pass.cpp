#include "fullscreen_pass.h"

namespace vplgi {

FullscreenPass::FullscreenPass(const gl::ShaderLoader& shaders, std::string name, std::string fragmentFile,
                               std::vector<GLenum> targets)
    : mName(std::move(name)), mFragmentFile(std::move(fragmentFile)), mFormats(std::move(targets)),
      mEmptyVertexArray(mName + " (no vertices)")
{
    reloadShaders(shaders);
}

void FullscreenPass::reloadShaders(const gl::ShaderLoader& shaders)
{
    mProgram = shaders.load(mName, {{GL_VERTEX_SHADER, "lib/fullscreen.vert"}, {GL_FRAGMENT_SHADER, mFragmentFile}});
}

void FullscreenPass::render(int width, int height)
{
    if (width != mWidth || height != mHeight) {
        mTargets.clear();
        mFramebuffer = gl::Framebuffer(mName);
        for (std::size_t i = 0; i < mFormats.size(); ++i) {
            gl::TextureDesc desc;
            desc.format = mFormats[i];
            desc.width = width;
            desc.height = height;
            mTargets.emplace_back(mName + " target " + std::to_string(i), desc);
            mFramebuffer.attach(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i), mTargets.back());
        }
        mFramebuffer.setDrawBuffers(static_cast<int>(mFormats.size()));
        mFramebuffer.checkComplete();
        mWidth = width;
        mHeight = height;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, mFramebuffer.id());
    glViewport(0, 0, width, height);
    glUseProgram(mProgram.id());
    glBindVertexArray(mEmptyVertexArray.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
}

} // namespace vplgi
