#include "smcir_rt_technique.h"

#include <chrono>
#include <cstdio>
#include <functional>
#include <utility>

#include "core/params.h"

namespace vplgi {

SMCIRRayTracedTechnique::SMCIRRayTracedTechnique() = default;

SMCIRRayTracedTechnique::~SMCIRRayTracedTechnique()
{
    mWorker.reset(); // joins before the sampler and the Embree scene go away
}

void SMCIRRayTracedTechnique::visitParams(ParamVisitor& v)
{
    mParams.visitParams(v);
    v.field("smcir.synchronous", mSynchronous,
            "run the sampler step on the render thread (no overlap with the GPU frame; for clean timings)");
}

void SMCIRRayTracedTechnique::setScene(const SceneContext& context)
{
    mWorker.reset();
    mScene = &context.scene;
    mRays = std::make_unique<RayScene>(context.scene);
    mSampler = std::make_unique<SMCIRSampler>(context.scene, *mRays, mParams);
    mInitialized = false;
}

void SMCIRRayTracedTechnique::update(const FrameContext& frame)
{
    const float aspect = static_cast<float>(frame.width) / static_cast<float>(frame.height);
    // Everything the sampler reads that this thread writes (camera, lights), by value.
    FrameSnapshot snapshot = FrameSnapshot::of(*mScene, frame.camera, aspect, frame.time);
    if (!mInitialized) {
        // Alg. 1 line 1 and the warm-up iterations; a progress bar on large scenes, where they take seconds.
        std::function<void(int, int)> progress;
        if (mScene->triangleCount() > 50000)
            progress = [](int done, int total) {
                const int width = 30, filled = total > 0 ? done * width / total : width;
                std::fprintf(stderr, "\rsmcir warm-up [%.*s%*s] %d/%d", filled, "##############################",
                             width - filled, "", done, total);
                if (done == total) std::fprintf(stderr, "\n");
            };
        mSampler->initialize(snapshot, progress);
        mWorker = std::make_unique<SMCIRWorker>(*mSampler);
        mInitialized = true;
    } else if (mSynchronous) {
        // Synchronous steps also measure the ray efficiency: the step's rays are recorded and
        // replayed alone (the render thread casts nothing meanwhile, so only the sampler's are kept).
        mRecorder.clear();
        mRays->setRecorder(&mRecorder);
        mSampler->step(snapshot);
        mRays->setRecorder(nullptr);
        mReplayMilliseconds = mRecorder.replay(*mRays) * 1e3;
    } else {
        mWorker->wait();
    }
    mRendered = mSampler->vpls();
    mTimes = mSampler->lastTimes();
    if (!mSynchronous) mWorker->submit(std::move(snapshot));
}

void SMCIRRayTracedTechnique::render(const FrameContext& frame, const GBuffer&, const IndirectTarget& target)
{
    const auto start = std::chrono::steady_clock::now();
    VPLGatherParams gather;
    gather.clampGeometry = computeClampGeometry(mParams, mRays->sceneScale());
    const ImageRGBA32F image = renderVPLGather(*mScene, *mRays, frame.camera, frame.width, frame.height, mRendered, gather);
    // GL rows run bottom to top.
    const std::size_t row = static_cast<std::size_t>(frame.width) * 4;
    std::vector<float> flipped(image.pixels.size());
    for (int y = 0; y < frame.height; ++y)
        std::copy_n(&image.pixels[static_cast<std::size_t>(frame.height - 1 - y) * row], row, &flipped[y * row]);
    glTextureSubImage2D(target.radiance.id(), 0, 0, 0, frame.width, frame.height, GL_RGBA, GL_FLOAT, flipped.data());
    mGatherMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void SMCIRRayTracedTechnique::configureReference(PathTracerParams& params, const std::set<std::string>& explicitKeys) const
{
    // Section 5: "The path traced reference images use the same approximation" (untextured VPLs).
    if (!explicitKeys.count("reference.untexturedBounces")) params.untexturedBounces = !mParams.texturedVPLs;
    // 5.4: the clamped reference clamps as the VPLs are clamped.
    const float clamp = computeClampGeometry(mParams, mRays->sceneScale());
    if (!explicitKeys.count("reference.clampGeometry") && clamp > 0.0f) params.clampGeometry = clamp;
}

std::vector<std::pair<std::string, double>> SMCIRRayTracedTechnique::frameStats() const
{
    // The sampler's stages in the columns of SMCIR Table 2 (measured on the worker thread, for the
    // step whose VPL set this frame renders).
    return {{"sampler: camera rays ms", mTimes.cameraRays},
            {"sampler: candidate sampling ms", mTimes.candidateSampling},
            {"sampler: candidate resampling ms", mTimes.candidateResampling},
            {"sampler: indirect visibility ms", mTimes.indirectVisibility},
            {"sampler: radiosity ms", mTimes.radiosity},
            {"sampler: kNN ms", mTimes.knn},
            {"sampler: selection ms", mTimes.selection},
            {"sampler: total ms", mTimes.total},
            {"sampler: rays", static_cast<double>(mTimes.rays)},
            {"sampler: ray replay ms", mReplayMilliseconds},
            {"sampler: radiance estimates", static_cast<double>(mTimes.radianceEstimates)},
            {"vpls", static_cast<double>(mRendered.validCount())},
            {"vpls changed", static_cast<double>(mRendered.changed.size())},
            {"cpu gather ms", mGatherMilliseconds}};
}

} // namespace vplgi
