// Pass 1: the deferred G-buffer. Targets follow the output size; every later pass reads them.
#pragma once

#include "../api/shader_loader.h"
#include "../gpu_scene.h"

namespace vplgi {

struct GBuffer {
    gl::Texture position;  // RGBA32F: world position [m], w = 1 where geometry was hit
    gl::Texture normal;    // RGBA16F: shading normal, w = perceptual roughness
    gl::Texture baseColor; // RGBA16F: base colour, w = metallic
    gl::Texture emission;  // RGBA16F: emitted radiance, w = specular factor
    gl::Texture depth;     // DEPTH32F
    gl::Framebuffer framebuffer;
    int width = 0;
    int height = 0;

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
    void resize(int width, int height);
    gl::Program mProgram;
    GBuffer mGBuffer;
};

} // namespace vplgi
