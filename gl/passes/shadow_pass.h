// Pass 0: shadow maps for the direct emitters. Point emitters (point, spot, emissive samples) get a
// cube map in a cube-map array storing radial distance / far; directional emitters get an
// orthographic depth map fitted to the scene bounds in a 2D array. All faces of all cubes are drawn
// with one instanced, layered draw per mesh. Re-rendered only when the lights change, and then
// only the cubes of emitters that moved. The face and directional matrices come from
// glsl/shared/light_view.h (shared with the GLSL side and the other light-view passes).
#pragma once

#include "../api/render_target.h"
#include "../api/shader_loader.h"
#include "../debug_view.h"
#include "../gpu_scene.h"
#include "core/scene/direct_lights.h"

namespace vplgi {

class ParamVisitor;

struct ShadowParams {
    int cubeSize = 256;         // point-emitter cube face resolution [texels]
    int mapSize = 2048;         // directional shadow map resolution [texels]
    float normalOffset = 1.5f;  // receiver offset along the normal [shadow texels]
    float depthBias = 0.0f;     // extra constant distance bias [m]
    int pcfRadius = 1;          // directional PCF kernel radius [texels]
    bool updateMovedOnly = true; // re-render only the cubes of emitters that moved (false: all)
    void visitParams(ParamVisitor& visitor);
};

// The names of ShadowPass::debugViews().
inline constexpr const char* kShadowPointView = "shadow.point";
inline constexpr const char* kShadowDirectionalView = "shadow.directional";

class ShadowPass {
public:
    explicit ShadowPass(const gl::ShaderLoader& shaders);
    void reloadShaders(const gl::ShaderLoader& shaders);
    // Assigns shadow layers to the emitters (intensity.w / direction.w) and renders every map.
    void render(const GpuScene& scene, DirectLightSet& lights, const ShadowParams& params);
    // Binds the shadow textures and the directional matrices for the shading passes.
    void bindForReading() const;
    float cubeFarDistance() const { return mFar; }
    // The maps as debug views (renderer.display): "shadow.point" (every cube face, layer = emitter
    // * 6 + face, radial distance / cube far) and "shadow.directional" (depth, layer = directional
    // emitter); null textures before the first render() or without such emitters.
    std::vector<DebugView> debugViews() const;
    // Cube maps re-rendered by the last render() (emitters that moved, or all after a reallocation).
    int lastRenderedCubes() const { return mLastRenderedCubes; }

private:
    void renderCubes(const GpuScene& scene, DirectLightSet& lights, const ShadowParams& params, float near);
    void renderDirectional(const GpuScene& scene, DirectLightSet& lights, const ShadowParams& params);
    SceneProgram mPointProgram;
    SceneProgram mDirectionalProgram;
    gl::RenderTarget mCubes;       // depth only: DEPTH32F cube-map array, layer = emitter * 6 + face
    gl::RenderTarget mDirectional; // depth only: DEPTH32F 2D array, layer = directional emitter
    gl::Buffer mCubeMatrices;
    gl::Buffer mDirectionalMatrices;
    gl::Buffer mEmitters;
    gl::Sampler mSampler;
    gl::Texture mNoPoint;          // placeholders bound where a scene has no emitter of the kind
    gl::Texture mNoDirectional;
    float mFar = 1.0f;
    std::vector<glm::vec3> mRenderedPositions; // emitter positions the cubes were rendered for
    int mLastRenderedCubes = 0;
};

} // namespace vplgi
