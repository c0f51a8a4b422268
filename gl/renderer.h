// The renderer: one readable function (renderFrame) lists the passes in order.
//
//   shadows (only when lights changed) -> G-buffer -> direct light -> technique (indirect)
//     -> tone map (display RGBA8 + combined linear radiance) -> window blit | readback
//
// Units: the radiance targets hold W/(m^2 sr); see core/scene/scene.h for light units.
#pragma once

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "api/timer.h"
#include "core/scene/direct_lights.h"
#include "core/util/image_io.h"
#include "core/util/params.h"
#include "core/scene/scene.h"
#include "debug_view.h"
#include "glsl/shared/bindings.h"
#include "gpu_scene.h"
#include "passes/fullscreen_pass.h"
#include "passes/gbuffer_pass.h"
#include "passes/shadow_pass.h"
#include "techniques/technique.h"

namespace vplgi {

class ParamVisitor;

// The names renderer.display accepts: final, direct, indirect, albedo, normal, depth (kDisplay*
// order), the renderer's own texture views (shadow.point, shadow.directional), then those of
// `techniqueViews` (Technique::debugViews()).
std::vector<std::string> displayViewNames(const std::vector<DebugView>& techniqueViews = {});

struct RendererParams {
    float exposure = 1.0f;           // radiance scale before Reinhard tone mapping
    std::string display = "final";   // what the display shows: a name of displayViewNames() (renderer.display)
    std::string antialias = "fxaa";  // the display's antialiasing (frame views): fxaa or none (renderer.antialias)
    int displayLayer = -1;           // layer of a texture view to show alone, -1: all its layers tiled
    ShadowParams shadow;             // shadow.*
    DirectLightParams lights;        // lights.emitterSamples, lights.seed
    // `viewNames`: what renderer.display accepts (the technique's views too: displayViewNames).
    void visitParams(ParamVisitor& visitor, const std::vector<std::string>& viewNames = displayViewNames());
};

class Renderer {
public:
    // `progress` receives the technique's long precomputations (SceneContext::progress): a terminal
    // bar by default, the viewer's window overlay there.
    Renderer(const gl::ShaderLoader& shaders, const Scene& scene, const RendererParams& params,
             std::unique_ptr<Technique> technique, ProgressSink progress = terminalProgressBar());

    // Renders one frame of `camera` at width x height into the output targets.
    void renderFrame(const Camera& camera, int width, int height, float time = 0.0f);
    // Call after changing scene lights (animation): emitters and shadow maps are rebuilt next frame.
    void markLightsChanged() { mLightsChanged = true; }
    // Recompiles every program; on error keeps the old ones and rethrows.
    void reloadShaders();

    ImageRGBA8 readDisplay() const;     // tone-mapped sRGB bytes, rows top to bottom
    ImageRGBA32F readRadiance() const;  // direct + indirect, linear, rows top to bottom
    ImageRGBA32F readDirect() const;    // direct only (incl. emission), linear, rows top to bottom
    const gl::Texture& displayTexture() const { return mOutput.color(0); }
    // After renderFrame(): runs the tone-map pass once more with renderer.display = `view` (a name of
    // displayViewNames()) into a second target of the output's size, for the viewer's
    // picture-in-picture; the frame's own display image is unchanged. Throws Error for an unknown view.
    const gl::Texture& renderInset(const std::string& view);
    // Every texture view renderer.display can show: the renderer's own, then the technique's.
    std::vector<DebugView> debugViews() const;

    // Per-pass times; with GPU timestamp queries they lag the rendered frame (see gl/api/timer.h).
    const gl::PassTimer& timer() const { return mTimer; }
    gl::PassTimer& timer() { return mTimer; }
    // Shadow cube maps re-rendered in the last frame that rebuilt shadows (moved emitters only).
    int lastRenderedShadowCubes() const { return mShadows.lastRenderedCubes(); }
    const DirectLightSet& lights() const { return mLights; }
    Technique& technique() { return *mTechnique; }
    const GpuScene& gpuScene() const { return mGpuScene; }
    // The last frame's G-buffer (gl/passes/gbuffer_pass.h).
    const GBuffer& gbuffer() const { return mGBuffer.gbuffer(); }
    const RendererParams& params() const { return mParams; }
    // The one live parameter set: the renderer's fields and its technique's (Session, CLI, scene
    // file, reports and the viewer all read and write these through visitParams).
    void visitParams(ParamVisitor& visitor);
    // Applies `settings` between frames (unknown keys and bad values throw before anything
    // changes... of the failing key; earlier keys of the list stay applied). Cheap changes take effect
    // next frame; structural ones rebuild what they must (shadow.* and lights.* rebuild the emitters
    // and shadow maps, the technique rebuilds its own state: Technique::applyParamChanges).
    // Returns the keys whose value changed.
    std::set<std::string> applySettings(const Settings& settings);

private:
    void updateFrameUniforms(const Camera& camera, int width, int height);
    ImageRGBA32F readLinear(const gl::Texture& texture) const;
    void bindDisplayView(); // the tone-map pass's inputs for the view renderer.display names

    const gl::ShaderLoader& mShaders;
    const Scene& mScene;
    RendererParams mParams;
    GpuScene mGpuScene;
    SharedRayScene mRays; // before the technique: it outlives the technique's CPU half
    std::unique_ptr<Technique> mTechnique;
    ShadowPass mShadows;
    GBufferPass mGBuffer;
    FullscreenPass mDirect;
    FullscreenPass mToneMap;
    FullscreenPass mAntialias;        // passes/fxaa.frag (renderer.antialias)
    gl::RenderTarget mDirectTarget;   // direct light + emission, RGBA32F
    gl::RenderTarget mIndirectTarget; // the technique's indirect light, RGBA32F
    gl::RenderTarget mOutput;         // colour 0 display RGBA8 (sRGB bytes), colour 1 radiance RGBA32F
    gl::RenderTarget mInset;          // the same for renderInset()
    gl::RenderTarget mAntialiased;    // RGBA8: FXAA's output, copied back into the output's display
    gl::Sampler mAntialiasSampler;    // bilinear, clamped: FXAA's lookups between pixels
    gl::Texture mDisplayView;         // texture view of what renderer.display shows (re-made each frame)
    gl::Texture mNoDisplayView;       // bound to the view's unit while the display shows a frame image
    gl::Buffer mFrameUniforms;
    gl::Buffer mPointEmitters;
    gl::Buffer mDirectionalEmitters;
    DirectLightSet mLights;
    shared::FrameUniforms mFrame{};
    gl::PassTimer mTimer;
    bool mLightsChanged = true;
    std::uint32_t mFrameIndex = 0;
};

} // namespace vplgi
