#include "fullscreen_pass.h"

#include "core/util/error.h"

namespace vplgi {

FullscreenPass::FullscreenPass(const gl::ShaderLoader& shaders, std::string name, std::string fragmentFile,
                               std::vector<std::string> defines)
    : mName(std::move(name)), mFragmentFile(std::move(fragmentFile)), mDefines(std::move(defines)),
      mEmptyVertexArray(mName + " (no vertices)")
{
    reloadShaders(shaders);
}

void FullscreenPass::reloadShaders(const gl::ShaderLoader& shaders)
{
    mProgram = shaders.load(mName, {{GL_VERTEX_SHADER, "lib/fullscreen.vert"}, {GL_FRAGMENT_SHADER, mFragmentFile}},
                            mDefines);
}

void FullscreenPass::render(const gl::RenderTarget& target, const FullscreenDraw& draw) const
{
    require(static_cast<bool>(target), "fullscreen pass " + mName + ": target " + target.name() + " has no storage");
    require(draw.layer >= 0 && draw.layer < target.layers(), "fullscreen pass " + mName + ": layer out of range");
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer().id());
    if (draw.viewport.z > 0) glViewport(draw.viewport.x, draw.viewport.y, draw.viewport.z, draw.viewport.w);
    else glViewport(0, 0, target.width(), target.height());
    if (draw.blend == FullscreenDraw::Blend::Add) {
        glEnable(GL_BLEND);
        glBlendFunc(GL_ONE, GL_ONE);
        glBlendEquation(GL_FUNC_ADD);
    }
    glUseProgram(mProgram.id());
    glProgramUniform1i(mProgram.id(), 0, draw.layer); // lib/fullscreen.vert: layout(location = 0) uLayer
    glBindVertexArray(mEmptyVertexArray.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
    if (draw.blend != FullscreenDraw::Blend::None) glDisable(GL_BLEND);
}

} // namespace vplgi
