// A fragment-shader pass over a viewport of a target its caller hands it: the direct-light and
// tone-map passes, and the techniques' screen-space passes (filters, combines). The pass owns only
// its program; what it writes belongs to the caller (gl::RenderTarget).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "../api/render_target.h"
#include "../api/shader_loader.h"

namespace vplgi {

struct FullscreenDraw {
    enum class Blend { None, Add };       // Add: result += output (e.g. accumulating indirect light)
    glm::ivec4 viewport{0, 0, 0, 0};      // x, y, width, height; zero width = the whole target
    int layer = 0;                        // layer of a layered target (gl_Layer from the vertex shader)
    Blend blend = Blend::None;
};

class FullscreenPass {
public:
    // `defines` ("NAME" or "NAME VALUE") are injected after #version (gl::ShaderLoader).
    FullscreenPass(const gl::ShaderLoader& shaders, std::string name, std::string fragmentFile,
                   std::vector<std::string> defines = {});
    void reloadShaders(const gl::ShaderLoader& shaders);
    // Draws one triangle over the viewport of `target` with the program bound. The caller binds
    // inputs (textures, buffers) beforehand.
    void render(const gl::RenderTarget& target, const FullscreenDraw& draw = {}) const;
    const gl::Program& program() const { return mProgram; }

private:
    std::string mName;
    std::string mFragmentFile;
    std::vector<std::string> mDefines;
    gl::Program mProgram;
    gl::VertexArray mEmptyVertexArray;
};

} // namespace vplgi
