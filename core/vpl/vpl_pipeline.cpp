#include "core/vpl/vpl_pipeline.h"

#include <chrono>

namespace vplgi {

VPLPipeline::VPLPipeline(std::unique_ptr<VPLSampler> sampler, const RayScene* recordOn)
    : mSampler(std::move(sampler)), mRecordOn(recordOn), mThread([this] { run(); })
{
}

VPLPipeline::~VPLPipeline()
{
    {
        std::unique_lock<std::mutex> lock(mMutex);
        mCondition.wait(lock, [this] { return !mBusy; });
        mStop = true;
    }
    mCondition.notify_all();
    mThread.join();
}

const VPLSet& VPLPipeline::advance(FrameSnapshot snapshot, bool synchronous, const VPLSampler::Progress& progress)
{
    if (!mInitialized) {
        mSampler->initialize(snapshot, progress);
        mInitialized = true;
        mPublished = mSampler->vpls();
        mStats = mSampler->stats();
        return mPublished; // frame 0 shows the initial set; step 1 takes frame 1's snapshot
    }
    if (mPending) { // a step of the worker's (also when switching to synchronous)
        wait();
        mPending = false;
        mPublished = mSampler->vpls();
        mStats = mSampler->stats();
    }
    if (synchronous) {
        double replayMs = 0.0;
        if (mRecordOn) {
            mRecorder.clear();
            mRecordOn->setRecorder(&mRecorder);
        }
        mSampler->step(snapshot);
        if (mRecordOn) {
            mRecordOn->setRecorder(nullptr);
            replayMs = mRecorder.replay(*mRecordOn) * 1e3;
        }
        mPublished = mSampler->vpls();
        mStats = mSampler->stats();
        if (mRecordOn) mStats.emplace_back("sampler: ray replay ms", replayMs);
        return mPublished;
    }
    submit(std::move(snapshot));
    mPending = true;
    return mPublished;
}

void VPLPipeline::submit(FrameSnapshot snapshot)
{
    wait();
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mJob = std::move(snapshot);
        mBusy = true;
    }
    mCondition.notify_all();
}

void VPLPipeline::wait()
{
    std::unique_lock<std::mutex> lock(mMutex);
    mCondition.wait(lock, [this] { return !mBusy; });
    if (mError) {
        std::exception_ptr error = mError;
        mError = nullptr;
        std::rethrow_exception(error);
    }
}

void VPLPipeline::run()
{
    for (;;) {
        std::optional<FrameSnapshot> job;
        {
            std::unique_lock<std::mutex> lock(mMutex);
            mCondition.wait(lock, [this] { return mStop || mJob.has_value(); });
            if (mStop) return;
            job = std::move(mJob);
            mJob.reset();
        }
        try {
            mSampler->step(*job);
        } catch (...) {
            std::lock_guard<std::mutex> lock(mMutex);
            mError = std::current_exception();
        }
        {
            std::lock_guard<std::mutex> lock(mMutex);
            mBusy = false;
        }
        mCondition.notify_all();
    }
}

} // namespace vplgi
