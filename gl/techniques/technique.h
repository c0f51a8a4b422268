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
#include "../gpu_scene.h"
#include "../passes/gbuffer_pass.h"
#include "core/direct_lights.h"
#include "core/path_tracer.h"
#include "core/scene.h"

namespace vplgi {

class ParamVisitor;

struct SceneContext {
    const Scene& scene;
    const GpuScene& gpuScene;
    const gl::ShaderLoader& shaders;
};

struct FrameContext {
    const Camera& camera;
    int width = 0;
    int height = 0;
    float time = 0.0f;               // animation time [s]
    std::uint32_t frameIndex = 0;
    bool lightsChanged = false;      // emitters moved or changed this frame
    const DirectLightSet& lights;    // the direct emitters (with shadow layers assigned)
    gl::PassTimer& timer;
};

// HDR indirect radiance [W/(m^2 sr)] at each pixel, cleared to zero before render().
struct IndirectTarget {
    const gl::Texture& radiance;
    const gl::Framebuffer& framebuffer;
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
    // Statistics of the last frame for `vplgi bench` (e.g. "rays", "vpls", "vplsMoved").
    virtual std::vector<std::pair<std::string, double>> frameStats() const { return {}; }
    // What a path-traced reference must simulate to be compared with this technique (`vplgi
    // compare`), e.g. SMCIR's untextured bounces (section 5) and its clamp (5.4). Called after
    // setScene(); `explicitKeys` are the reference.* keys the user set, which win.
    virtual void configureReference(PathTracerParams& /*params*/, const std::set<std::string>& /*explicitKeys*/) const {}
};

// The explicit list of techniques; an unknown name throws Error listing the known ones.
std::unique_ptr<Technique> createTechnique(std::string_view name);
std::vector<std::string> techniqueNames();

} // namespace vplgi
