// The VPL pipeline every VPL technique shares (smcir-rt now; smcir and ir next): any VPL sampler
// behind one small interface, a worker thread, one frame of latency, progress and statistics.
//
// Per frame n, advance(snapshot n):
//   first call      initialize(snapshot 0) on the calling thread (progress reported), publish that set
//   asynchronous    wait for the worker's step n-1 (if one runs) -> publish its set -> submit step n
//                   -> return; so frame n shows step n-1: the synchronous frame n-1, bit for bit
//   synchronous     step n on the calling thread -> publish -> return (no latency; and with a
//                   RayScene to record on, the step's rays are replayed alone: the ray efficiency)
// The published set is a copy: the renderer reads it while the worker changes the sampler's. The
// one-frame pipelining is ours, not the papers' (SMCIR runs every step on the GPU within the frame).
// Each job carries its FrameSnapshot by value: the worker never reads what the render thread
// writes (tests/cpu/test_smcir_worker.cpp, under ThreadSanitizer). Jobs run in submission order, so
// the published sets are the synchronous ones one frame later, bit for bit.
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "core/scene/frame_snapshot.h"
#include "core/trace/ray_scene.h"
#include "core/vpl/vpl.h"

namespace vplgi {

using StatList = std::vector<std::pair<std::string, double>>;

// Any VPL sampler: a set of VPLs in stable slots, evolved (or redrawn) once per frame.
class VPLSampler {
public:
    using Progress = std::function<void(int done, int total)>;
    virtual ~VPLSampler() = default;
    // The first set (and any warm-up), for the snapshot's camera and lights.
    virtual void initialize(const FrameSnapshot& snapshot, const Progress& progress) = 0;
    // One frame. Reads only the snapshot and the scene's static parts.
    virtual void step(const FrameSnapshot& snapshot) = 0;
    virtual const VPLSet& vpls() const = 0;
    // Statistics of the last initialize() or step() ("sampler: rays", ...), for `vplgi bench`.
    virtual StatList stats() const = 0;
};

class VPLPipeline {
public:
    // `recordOn`: the RayScene the sampler casts on; when given, synchronous steps record their rays
    // and replay them alone ("sampler: ray replay ms"). It must outlive the pipeline.
    VPLPipeline(std::unique_ptr<VPLSampler> sampler, const RayScene* recordOn = nullptr);
    ~VPLPipeline(); // waits for a running step, then joins the worker
    VPLPipeline(const VPLPipeline&) = delete;
    VPLPipeline& operator=(const VPLPipeline&) = delete;

    // Frame n (see the header): returns the set to render this frame. `progress` reports the
    // initialization (the first call). Rethrows an exception of the worker's step.
    const VPLSet& advance(FrameSnapshot snapshot, bool synchronous, const VPLSampler::Progress& progress = {});
    // The published set and the statistics of the step that made it.
    const VPLSet& published() const { return mPublished; }
    const StatList& stats() const { return mStats; }
    bool initialized() const { return mInitialized; }

private:
    void submit(FrameSnapshot snapshot);
    void wait();
    void run();

    std::unique_ptr<VPLSampler> mSampler;
    const RayScene* mRecordOn = nullptr;
    RayRecorder mRecorder;
    VPLSet mPublished;
    StatList mStats;
    bool mInitialized = false;
    bool mPending = false; // a submitted step whose set has not been published yet

    std::mutex mMutex;
    std::condition_variable mCondition;
    std::optional<FrameSnapshot> mJob;
    bool mBusy = false;
    bool mStop = false;
    std::exception_ptr mError;
    std::thread mThread; // last: started after everything above exists
};

} // namespace vplgi
