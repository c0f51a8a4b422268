// Technique "smcir-rt": SMCIR's VPL sampler (core/vpl/smcir_sampler.h, Algorithm 1) rendered by the
// CPU gather of every VPL with Embree visibility (core/vpl/vpl_gather.h), as SMCIR Fig. 8's
// "All VPLs - ray tracing". It measures the quality of the VPL distribution apart from shadow-map,
// interleaving and filtering artefacts; the GPU technique `smcir` builds on the same sampler.
//
// Overview, per frame n:
//   update():  VPLPipeline::advance(snapshot n) (core/vpl/vpl_pipeline.h): the worker thread runs step n
//              on a snapshot of frame n (camera, lights by value) while this frame renders the set of
//              step n-1 (one frame of latency; this pipelining is ours, not the paper's, which runs
//              every step on the GPU within the frame). Deterministic for a seed.
//   render():  gather the published set at every pixel on the CPU, upload to the indirect target
// With smcir.synchronous the step runs on the render thread instead (frame n shows step n): slower,
// but the stage times are then measured without the GPU frame competing for the same cores, and the
// step's rays are recorded and replayed alone for the ray efficiency (core/trace/ray_scene.h RayRecorder).
//
// References: Hedman, Karras, Lehtinen, "Sequential Monte Carlo Instant Radiosity", TVCG 2017,
// sections 3 and 4, Fig. 8.
#pragma once

#include <memory>

#include "core/trace/ray_scene.h"
#include "core/vpl/smcir_sampler.h"
#include "core/vpl/vpl_gather.h"
#include "core/vpl/vpl_pipeline.h"
#include "technique.h"

namespace vplgi {

class SMCIRRayTracedTechnique final : public Technique {
public:
    SMCIRRayTracedTechnique();
    ~SMCIRRayTracedTechnique() override;
    std::string_view name() const override { return "smcir-rt"; }
    void setScene(const SceneContext& context) override;
    void update(const FrameContext& frame) override;
    void render(const FrameContext& frame, const GBuffer& gbuffer, const IndirectTarget& target) override;
    void visitParams(ParamVisitor& visitor) override;
    std::vector<std::pair<std::string, double>> frameStats() const override;
    // conform compares it with: as smcir.
    PathTracerParams::Mode matchedReferenceMode() const override { return PathTracerParams::Mode::Clamped; }
    void configureReference(PathTracerParams& params, const std::set<std::string>& explicitKeys) const override;
    void applyParamChanges(const std::set<std::string>& changedKeys) override;

private:
    void startPipeline();
    SMCIRParams mParams;
    bool mSynchronous = false;  // step on the render thread (no overlap): uncontended stage timings
    const Scene* mScene = nullptr;
    const RayScene* mRays = nullptr; // the renderer's shared Embree scene
    ProgressSink mProgress;
    std::unique_ptr<VPLPipeline> mPipeline;
    const VPLSet* mRendered = nullptr; // the set this frame renders (the pipeline's published copy)
    double mGatherMilliseconds = 0.0;
};

} // namespace vplgi
