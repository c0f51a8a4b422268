// A fragment-shader pass over the whole viewport writing into its own colour targets.
// Used by the direct-light and tone-map passes (and later filters).
#pragma once

#include <string>
#include <vector>

#include "../api/shader_loader.h"

namespace vplgi {

class FullscreenPass {
public:
    // `targets`: the sized formats of the colour attachments, in location order.
    FullscreenPass(const gl::ShaderLoader& shaders, std::string name, std::string fragmentFile,
                   std::vector<GLenum> targets);
    void reloadShaders(const gl::ShaderLoader& shaders);
    // Resizes the targets when needed, then draws one triangle with the program bound.
    void render(int width, int height);
    const gl::Texture& target(int index) const { return mTargets[index]; }
    const gl::Program& program() const { return mProgram; }

private:
    std::string mName;
    std::string mFragmentFile;
    std::vector<GLenum> mFormats;
    gl::Program mProgram;
    std::vector<gl::Texture> mTargets;
    gl::Framebuffer mFramebuffer;
    gl::VertexArray mEmptyVertexArray;
    int mWidth = 0;
    int mHeight = 0;
};

} // namespace vplgi
