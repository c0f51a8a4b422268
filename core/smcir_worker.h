// Runs SMCIRSampler::step on its own thread so that the CPU sampling of frame n overlaps the GPU
// rendering of frame n with the VPL set of frame n - 1. This pipelining is ours, not the paper's:
// SMCIR runs every step on the GPU within the frame (section 4); on a CPU sampler it hides the
// sampler's time behind the GPU frame at the cost of one frame of latency.
//
// Each job carries a FrameSnapshot by value (camera, lights): the worker reads nothing that the
// render thread writes, so the render thread may animate the scene while a step runs. Jobs run
// strictly in submission order, so results are deterministic and equal to calling step() with the
// same snapshots on one thread; an exception in the worker is rethrown by wait().
#pragma once

#include <condition_variable>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>

#include "frame_snapshot.h"

namespace vplgi {

class SMCIRSampler;

class SMCIRWorker {
public:
    explicit SMCIRWorker(SMCIRSampler& sampler);
    ~SMCIRWorker();
    SMCIRWorker(const SMCIRWorker&) = delete;
    SMCIRWorker& operator=(const SMCIRWorker&) = delete;

    // Starts one step with `snapshot` (waits for the previous one first).
    void submit(FrameSnapshot snapshot);
    // Blocks until no step is running; rethrows a worker exception. Afterwards the sampler may be
    // read (vpls(), lastTimes()) on the calling thread until the next submit().
    void wait();

private:
    void run();
    SMCIRSampler& mSampler;
    std::mutex mMutex;
    std::condition_variable mCondition;
    std::optional<FrameSnapshot> mJob;
    bool mBusy = false;
    bool mStop = false;
    std::exception_ptr mError;
    std::thread mThread;
};

} // namespace vplgi
