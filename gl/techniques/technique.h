// The one interface every GI technique implements (STYLE.md). The renderer owns the G-buffer,
// direct light and display passes; a technique adds indirect radiance into the IndirectTarget.
// Its CPU half lives in core/, its GPU half here; techniques share passes by composition.
#pragma once

#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../api/shader_loader.h"
#include "../api/timer.h"
#include "../debug_view.h"
#include "../gpu_scene.h"
#include "../passes/gbuffer_pass.h"
#include "core/scene/direct_lights.h"
#include "core/trace/path_tracer.h"
#include "core/util/progress.h"
#include "core/trace/ray_scene.h"
#include "core/scene/scene.h"

namespace vplgi {

class ParamVisitor;

// One Embree BVH per scene, shared by every CPU half and built on first use (`direct` never pays
// for it). Owned by the renderer; it outlives the technique.
class SharedRayScene {
public:
    explicit SharedRayScene(const Scene& scene) : mScene(scene) {}
    const RayScene& get() const
    {
        if (!mRays) mRays = std::make_unique<RayScene>(mScene);
        return *mRays;
    }

private:
    const Scene& mScene;
    mutable std::unique_ptr<RayScene> mRays;
};

// What setScene() gets: the scene (its geometry and materials do not change while the technique
// lives; lights and cameras do, so CPU halves on other threads take FrameSnapshots), its GPU
// buffers, the shader loader, the shared Embree scene, and where to report long precomputations.
struct SceneContext {
    const Scene& scene;
    const GpuScene& gpuScene;
    const gl::ShaderLoader& shaders;
    const SharedRayScene& rays;
    ProgressSink progress;
};

// What update() and render() get each frame.
struct FrameContext {
    const Camera& camera;
    int width = 0;
    int height = 0;
    float time = 0.0f;               // animation time [s]
    std::uint32_t frameIndex = 0;
    bool lightsChanged = false;      // emitters moved or changed this frame
    const DirectLightSet& lights;    // the direct emitters (with shadow layers assigned)
    gl::PassTimer& timer;            // open nested scopes for a technique's own passes
    glm::mat4 viewFromWorld{1.0f};   // the camera's, as in the frame uniform block
    glm::mat4 clipFromWorld{1.0f};
    glm::vec2 jitter{0.0f};          // sub-pixel offset of this frame's projection [pixels] (0: none yet)
    std::string display{};           // renderer.display this frame: a technique draws a debug view's
                                     // overlay only while it is shown
};

// HDR indirect radiance [W/(m^2 sr)] at each pixel (one RGBA32F colour attachment), cleared to zero
// before render(). Bindings live during render(): the frame uniform block (kBindingFrame), the
// emitter SSBOs (kBindingPointEmitters, kBindingDirectionalEmitters); the G-buffer is handed in and
// bound by gbuffer.bindForReading() on request; everything else a technique binds itself.
struct IndirectTarget {
    const gl::RenderTarget& target;
    const gl::Texture& radiance() const { return target.color(0); }
};

class Technique {
public:
    virtual ~Technique() = default;
    virtual std::string_view name() const = 0;
    virtual void setScene(const SceneContext& context) = 0;
    virtual void update(const FrameContext& frame) = 0;
    virtual void render(const FrameContext& frame, const GBuffer& gbuffer, const IndirectTarget& target) = 0;
    virtual void visitParams(ParamVisitor& visitor) = 0;
    virtual void reloadShaders(const gl::ShaderLoader&) {}
    // Called after visitParams changed `changedKeys` between frames (a live change from the viewer
    // or Renderer::applySettings): apply cheap ones at once, rebuild state on structural ones.
    virtual void applyParamChanges(const std::set<std::string>& /*changedKeys*/) {}
    // The textures this technique can show (DebugView: gl/debug_view.h has the fields, the kinds
    // and an example; the renderer adds its shadow maps). The names are the same for the
    // technique's whole life, from construction on (the CLI checks renderer.display against them
    // before setScene); the texture pointers are read after render() each frame and may be null
    // until the technique has created them.
    virtual std::vector<DebugView> debugViews() const { return {}; }
    // Statistics of the last frame for `vplgi bench` (e.g. "rays", "vpls", "vplsMoved").
    virtual std::vector<std::pair<std::string, double>> frameStats() const { return {}; }
    // What a path-traced reference must simulate to be compared with this technique (`vplgi
    // compare`), e.g. SMCIR's untextured bounces (section 5) and its clamp (5.4). Called after
    // setScene(); `explicitKeys` are the reference.* keys the user set, which win.
    virtual void configureReference(PathTracerParams& /*params*/, const std::set<std::string>& /*explicitKeys*/) const {}
    // The part of the light transport this technique estimates, which `vplgi conform` compares it
    // with (its matched reference, then configureReference): Indirect (all of it) by default; the
    // VPL techniques estimate the clamped indirect light (SMCIR 5.4), the RSM techniques one bounce.
    virtual PathTracerParams::Mode matchedReferenceMode() const { return PathTracerParams::Mode::Indirect; }
};

// The explicit list of techniques; an unknown name throws Error listing the known ones.
std::unique_ptr<Technique> createTechnique(std::string_view name);
std::vector<std::string> techniqueNames();

} // namespace vplgi
