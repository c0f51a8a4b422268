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
    // colour 3 emission RGBA16F: emitted radiance, w = specular factor
    // colour 4 surface normals RGBA16F: xy the geometric normal (the triangle's plane, on the
    //   shading normal's side, as core/scene/surface.cpp keeps it), zw the interpolated vertex
    //   normal without the normal map (both octahedral, glsl/shared/normals.h; double-sided
    //   surfaces seen from the back have both flipped, as the shading normal). Which to use: the
    //   shading normal for BRDFs, the geometric one for the below-the-surface test the path tracer
    //   makes (a direction with n_g . w <= 0 carries nothing), the interpolated one for filters and
    //   interpolation weights (issue "Every light type in the RSM techniques", part 2)
    // depth DEPTH32F
    gl::RenderTarget target;

    const gl::Texture& position() const { return target.color(0); }
    const gl::Texture& normal() const { return target.color(1); }
    const gl::Texture& baseColor() const { return target.color(2); }
    const gl::Texture& emission() const { return target.color(3); }
    const gl::Texture& surfaceNormals() const { return target.color(4); }
    const gl::Texture& depth() const { return target.depth(); }
    int width() const { return target.width(); }
    int height() const { return target.height(); }

    // Binds the five colour targets to the kUnitGBuffer* units.
    void bindForReading() const;
};

class GBufferPass {
public:
    explicit GBufferPass(const gl::ShaderLoader& shaders);
    void reloadShaders(const gl::ShaderLoader& shaders);
    void render(const GpuScene& scene, int width, int height);
    const GBuffer& gbuffer() const { return mGBuffer; }

private:
    SceneProgram mProgram;
    GBuffer mGBuffer;
};

} // namespace vplgi
