#include "smcir_rt_technique.h"

#include <chrono>
#include <cstdio>
#include <functional>
#include <utility>

#include "core/util/params.h"

namespace vplgi {

SMCIRRayTracedTechnique::SMCIRRayTracedTechnique() = default;

SMCIRRayTracedTechnique::~SMCIRRayTracedTechnique() = default; // the pipeline joins its worker

void SMCIRRayTracedTechnique::visitParams(ParamVisitor& v)
{
    mParams.visitParams(v);
    v.field("smcir.synchronous", mSynchronous,
            "run the sampler step on the render thread (no overlap with the GPU frame; for clean timings and "
            "the ray replay)");
}

void SMCIRRayTracedTechnique::setScene(const SceneContext& context)
{
    mScene = &context.scene;
    mRays = &context.rays.get();
    mProgress = context.progress;
    startPipeline();
}

void SMCIRRayTracedTechnique::startPipeline()
{
    mPipeline.reset(); // joins a running step before its sampler goes
    mRendered = nullptr;
    mPipeline = std::make_unique<VPLPipeline>(std::make_unique<SMCIRSampler>(*mScene, *mRays, mParams), mRays);
}

void SMCIRRayTracedTechnique::update(const FrameContext& frame)
{
    const float aspect = static_cast<float>(frame.width) / static_cast<float>(frame.height);
    // Alg. 1 line 1 and the warm-up iterations report progress on large scenes, where they take seconds.
    VPLSampler::Progress progress;
    if (mProgress && mScene->triangleCount() > 50000)
        progress = [this](int done, int total) { mProgress("smcir warm-up", done, total); };
    // Everything the sampler reads that this thread writes (camera, lights), by value.
    mRendered = &mPipeline->advance(FrameSnapshot::of(*mScene, frame.camera, aspect, frame.time), mSynchronous, progress);
}

void SMCIRRayTracedTechnique::render(const FrameContext& frame, const GBuffer&, const IndirectTarget& target)
{
    const auto start = std::chrono::steady_clock::now();
    VPLGatherParams gather;
    gather.clampGeometry = computeClampGeometry(mParams, mRays->sceneScale());
    const ImageRGBA32F image = renderVPLGather(*mScene, *mRays, frame.camera, frame.width, frame.height, *mRendered, gather);
    gl::uploadTopDownRGBA32F(target.radiance(), image.pixels, frame.width, frame.height);
    mGatherMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void SMCIRRayTracedTechnique::applyParamChanges(const std::set<std::string>& changedKeys)
{
    // Read every frame, nothing to rebuild: the clamp (render) and where the step runs.
    static const std::set<std::string> cheap = {"smcir.clampScale", "smcir.synchronous"};
    bool structural = false;
    for (const std::string& key : changedKeys)
        if (key.rfind("smcir.", 0) == 0 && !cheap.count(key)) structural = true;
    if (!structural || !mScene) return;
    // The sampler keeps a copy of its parameters (budget-sized slots, seeds): start it over, with
    // initialisation and warm-up at the next update().
    startPipeline();
}

void SMCIRRayTracedTechnique::configureReference(PathTracerParams& params, const std::set<std::string>& explicitKeys) const
{
    configureSMCIRReference(mParams, mRays->sceneScale(), params, explicitKeys);
}

std::vector<std::pair<std::string, double>> SMCIRRayTracedTechnique::frameStats() const
{
    // The sampler's stages in the columns of SMCIR Table 2, for the step whose VPL set this frame
    // renders (measured on the worker thread, or on this one with smcir.synchronous).
    std::vector<std::pair<std::string, double>> stats = mPipeline->stats();
    const VPLSet& set = mPipeline->published();
    stats.emplace_back("vpls", static_cast<double>(set.validCount()));
    stats.emplace_back("vpls changed", static_cast<double>(set.changed.size()));
    stats.emplace_back("cpu gather ms", mGatherMilliseconds);
    return stats;
}

} // namespace vplgi
