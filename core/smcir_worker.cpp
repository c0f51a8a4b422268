#include "smcir_worker.h"

#include <utility>

#include "smcir_sampler.h"

namespace vplgi {

SMCIRWorker::SMCIRWorker(SMCIRSampler& sampler) : mSampler(sampler), mThread([this] { run(); }) {}

SMCIRWorker::~SMCIRWorker()
{
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mStop = true;
    }
    mCondition.notify_all();
    mThread.join();
}

void SMCIRWorker::submit(FrameSnapshot snapshot)
{
    wait();
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mJob = std::move(snapshot);
        mBusy = true;
    }
    mCondition.notify_all();
}

void SMCIRWorker::wait()
{
    std::unique_lock<std::mutex> lock(mMutex);
    mCondition.wait(lock, [this] { return !mBusy; });
    if (mError) {
        std::exception_ptr error = mError;
        mError = nullptr;
        std::rethrow_exception(error);
    }
}

void SMCIRWorker::run()
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
            mSampler.step(*job);
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
