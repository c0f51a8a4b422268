#include "render_target.h"

#include <utility>

#include "core/util/error.h"

namespace vplgi::gl {

RenderTarget::RenderTarget(std::string name, RenderTargetDesc desc) : mName(std::move(name)), mDesc(std::move(desc))
{
    require(!mDesc.colorFormats.empty() || mDesc.depthFormat != GL_NONE,
            "render target " + mName + ": no attachment");
}

bool RenderTarget::resize(int width, int height, int layers)
{
    require(width > 0 && height > 0 && layers > 0, "render target " + mName + ": size must be positive");
    if (mFramebuffer && width == mWidth && height == mHeight && layers == mLayers) return false;
    auto make = [&](const std::string& label, GLenum format, int levels) {
        TextureDesc desc;
        desc.target = mDesc.textureTarget;
        desc.format = format;
        desc.width = width;
        desc.height = height;
        desc.layers = layers;
        desc.levels = levels;
        return Texture(mName + " " + label, desc);
    };
    mColors.clear();
    mFramebuffer = Framebuffer(mName);
    for (std::size_t i = 0; i < mDesc.colorFormats.size(); ++i) {
        const std::string label = i < mDesc.colorNames.size() ? mDesc.colorNames[i] : "colour " + std::to_string(i);
        mColors.push_back(make(label, mDesc.colorFormats[i], mDesc.levels));
        mFramebuffer.attach(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i), mColors.back());
    }
    mDepth = Texture();
    if (mDesc.depthFormat != GL_NONE) {
        mDepth = make("depth", mDesc.depthFormat, 1);
        mFramebuffer.attach(GL_DEPTH_ATTACHMENT, mDepth);
    }
    mFramebuffer.setDrawBuffers(colorCount());
    mFramebuffer.checkComplete();
    mWidth = width;
    mHeight = height;
    mLayers = layers;
    return true;
}

void RenderTarget::clear(const glm::vec4& color, float depth) const
{
    for (int i = 0; i < colorCount(); ++i) glClearNamedFramebufferfv(mFramebuffer.id(), GL_COLOR, i, &color[0]);
    if (mDepth) glClearNamedFramebufferfv(mFramebuffer.id(), GL_DEPTH, 0, &depth);
}

void RenderTarget::bindForDrawing() const
{
    glBindFramebuffer(GL_FRAMEBUFFER, mFramebuffer.id());
    glViewport(0, 0, mWidth, mHeight);
}

} // namespace vplgi::gl
