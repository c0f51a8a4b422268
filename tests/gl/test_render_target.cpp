// gl::RenderTarget (one texture-plus-framebuffer type for every pass) and FullscreenPass drawing into
// a caller's target: labels, resize only on a size change, clears, viewports, layers, additive blending.
#include <catch2/catch.hpp>

#include <vector>

#include "gl/api/debug.h"
#include "gl/api/render_target.h"
#include "gl/passes/fullscreen_pass.h"
#include "gl_test_context.h"

using namespace vplgi;

TEST_CASE("render target: labelled attachments, re-created only when the size changes", "[gl]")
{
    test::ensureGLContext();
    gl::RenderTargetDesc desc = gl::RenderTargetDesc::colors({GL_RGBA32F, GL_RGBA8}, {"radiance", "display"});
    desc.depthFormat = GL_DEPTH_COMPONENT32F;
    gl::RenderTarget target("test target", desc);
    CHECK_FALSE(target);
    CHECK(target.resize(8, 4));
    CHECK(target.width() == 8);
    CHECK(target.height() == 4);
    CHECK(test::objectLabel(GL_TEXTURE, target.color(0).id()) == "test target radiance");
    CHECK(test::objectLabel(GL_TEXTURE, target.color(1).id()) == "test target display");
    CHECK(test::objectLabel(GL_TEXTURE, target.depth().id()) == "test target depth");
    CHECK(test::objectLabel(GL_FRAMEBUFFER, target.framebuffer().id()) == "test target");
    const GLuint first = target.color(0).id();
    CHECK_FALSE(target.resize(8, 4)); // same size: nothing re-created
    CHECK(target.color(0).id() == first);
    CHECK(target.resize(16, 4));
    CHECK(target.color(0).width() == 16);
    target.clear(glm::vec4(0.25f, 0.5f, 0.75f, 1.0f));
    const std::vector<float> pixels = gl::readTextureRGBA32F(target.color(0));
    CHECK(pixels.size() == 16 * 4 * 4);
    CHECK(pixels[0] == 0.25f);
    CHECK(pixels[pixels.size() - 2] == 0.75f);
    CHECK_THROWS(gl::RenderTarget("no attachments", gl::RenderTargetDesc{}));
    gl::checkDebugMessages();
}

TEST_CASE("fullscreen pass draws into a caller's target: viewport, layer, additive blending", "[gl]")
{
    test::ensureGLContext();
    gl::ShaderLoader loader(std::string(VPLGI_SOURCE_DIR) + "/glsl");
    FullscreenPass pass(loader, "constant", "../tests/gl/glsl/fullscreen_constant.frag");
    auto setValue = [&](glm::vec4 v) { glProgramUniform4f(pass.program().id(), 2, v.x, v.y, v.z, v.w); };

    gl::RenderTarget flat("flat", gl::RenderTargetDesc::colors({GL_RGBA32F}));
    flat.resize(4, 4);
    flat.clear();
    setValue({1.0f, 2.0f, 3.0f, 4.0f});
    FullscreenDraw left;
    left.viewport = {0, 0, 2, 4}; // the left half only
    pass.render(flat, left);
    setValue({0.5f, 0.5f, 0.5f, 0.5f});
    FullscreenDraw add;
    add.blend = FullscreenDraw::Blend::Add; // the whole target, added
    pass.render(flat, add);
    std::vector<float> pixels = gl::readTextureRGBA32F(flat.color(0));
    CHECK(pixels[0] == 1.5f);                // (0, 0): written, then added
    CHECK(pixels[3 * 4] == 0.5f);            // (3, 0): only added
    CHECK(pixels[(3 * 4 + 1) * 4 + 2] == 3.5f); // (1, 3): left half

    gl::RenderTargetDesc layeredDesc = gl::RenderTargetDesc::colors({GL_RGBA32F});
    layeredDesc.textureTarget = GL_TEXTURE_2D_ARRAY;
    gl::RenderTarget layered("layered", layeredDesc);
    layered.resize(2, 2, 3);
    layered.clear();
    setValue({7.0f, 7.0f, 7.0f, 7.0f});
    FullscreenDraw layer2;
    layer2.layer = 2;
    pass.render(layered, layer2);
    CHECK(gl::readTextureRGBA32F(layered.color(0), 2)[0] == 7.0f);
    CHECK(gl::readTextureRGBA32F(layered.color(0), 1)[0] == 0.0f); // other layers untouched
    FullscreenDraw outside;
    outside.layer = 3;
    CHECK_THROWS(pass.render(layered, outside));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkDebugMessages();
}
