// Runs SMCIRSampler::step on its own thread so that the CPU sampling of frame n overlaps the GPU
// rendering of frame n with the VPL set of frame n - 1 (SMCIR section 4). Jobs run strictly in
// submission order, so results are deterministic; an exception in the worker is rethrown by wait().
#pragma once

#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "scene.h"

namespace vplgi {

class SMCIRSampler;

class SMCIRWorker {
public:
    explicit SMCIRWorker(SMCIRSampler& sampler);
    ~SMCIRWorker();
    SMCIRWorker(const SMCIRWorker&) = delete;
    SMCIRWorker& operator=(const SMCIRWorker&) = delete;

    // Starts one step for `camera` (waits for the previous one first). With `lightsChanged` the
    // sampler re-estimates every VPL's radiance in that step.
    void submit(const Camera& camera, float aspect, bool lightsChanged);
    // Blocks until no step is running; rethrows a worker exception.
    void wait();

private:
    void run();
    SMCIRSampler& mSampler;
    std::mutex mMutex;
    std::condition_variable mCondition;
    std::optional<Camera> mJob;
    float mAspect = 1.0f;
    bool mInvalidate = false;
    bool mBusy = false;
    bool mStop = false;
    std::exception_ptr mError;
    std::thread mThread;
};

} // namespace vplgi
