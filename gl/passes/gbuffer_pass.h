// Pass 1: the deferred G-buffer. Targets follow the output size; every later pass reads them.
#pragma once

#include "../api/render_target.h"
#include "../api/shader_loader.h"
#include "../gpu_scene.h"

namespace vplgi {

struct GBuffer {
    // colour 0 position RGBA32F: world position [m], w = 1 where geometry was hit
    // colour 1 normal RGBA16F: shading normal, w = perceptual roughness
    // colour 2 base colour RGBA16F: base colour, w = metallic
    // colour 3 emission RGBA16F: emitted radiance, w = specular factor; depth DEPTH32F
    gl::RenderTarget target;

    const gl::Texture& position() const { return target.color(0); }
    const gl::Texture& normal() const { return target.color(1); }
    const gl::Texture& baseColor() const { return target.color(2); }
    const gl::Texture& emission() const { return target.color(3); }
    const gl::Texture& depth() const { return target.depth(); }
    int width() const { return target.width(); }
    int height() const { return target.height(); }

    // Binds the four colour targets to the kUnitGBuffer* units.
    void bindForReading() const;
};

class GBufferPass {
public:
    explicit GBufferPass(const gl::ShaderLoader& shaders);
    void reloadShaders(const gl::ShaderLoader& shaders);
    void render(const GpuScene& scene, int width, int height);
    const GBuffer& gbuffer() const { return mGBuffer; }

private:
    gl::Program mProgram;
    GBuffer mGBuffer;
};

} // namespace vplgi
