// One type for every texture-plus-framebuffer (STYLE.md: nobody writes that set-up by hand twice).
// A RenderTarget is a list of colour formats (+ an optional depth format) -> one texture per
// attachment and one framebuffer, all labelled "<name> <attachment>", created on resize() and
// re-created only when the size changes. Passes draw into targets their caller hands them.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "objects.h"

namespace vplgi::gl {

struct RenderTargetDesc {
    std::vector<GLenum> colorFormats;      // sized internal formats, in location order
    std::vector<std::string> colorNames;   // labels per attachment (default "colour <i>")
    GLenum depthFormat = GL_NONE;          // e.g. GL_DEPTH_COMPONENT32F; GL_NONE = no depth
    GLenum textureTarget = GL_TEXTURE_2D;  // GL_TEXTURE_2D_ARRAY / GL_TEXTURE_CUBE_MAP_ARRAY: layered
    int levels = 1;                        // mip levels of the colour textures (0 = full chain)

    // Plain 2D colour attachments with their labels.
    static RenderTargetDesc colors(std::vector<GLenum> formats, std::vector<std::string> names = {})
    {
        RenderTargetDesc desc;
        desc.colorFormats = std::move(formats);
        desc.colorNames = std::move(names);
        return desc;
    }
};

class RenderTarget {
public:
    RenderTarget() = default;
    RenderTarget(std::string name, RenderTargetDesc desc);

    // (Re)creates the textures and the framebuffer when the size (or layer count) differs; returns
    // true when it did. Layered targets attach all layers (layered rendering). Throws Error naming the
    // target when the framebuffer is incomplete.
    bool resize(int width, int height, int layers = 1);
    // Clears every colour attachment to `color` and the depth attachment to `depth`.
    void clear(const glm::vec4& color = glm::vec4(0.0f), float depth = 1.0f) const;
    // Binds the framebuffer for drawing with the viewport over the whole target.
    void bindForDrawing() const;

    const Texture& color(int index) const { return mColors.at(static_cast<std::size_t>(index)); }
    const Texture& depth() const { return mDepth; }
    const Framebuffer& framebuffer() const { return mFramebuffer; }
    int colorCount() const { return static_cast<int>(mDesc.colorFormats.size()); }
    int width() const { return mWidth; }
    int height() const { return mHeight; }
    int layers() const { return mLayers; }
    const std::string& name() const { return mName; }
    explicit operator bool() const { return static_cast<bool>(mFramebuffer); }

private:
    std::string mName;
    RenderTargetDesc mDesc;
    std::vector<Texture> mColors;
    Texture mDepth;
    Framebuffer mFramebuffer;
    int mWidth = 0;
    int mHeight = 0;
    int mLayers = 0;
};

} // namespace vplgi::gl
