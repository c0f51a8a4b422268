#include "smcir_worker.h"

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

void SMCIRWorker::submit(const Camera& camera, float aspect, bool lightsChanged)
{
    wait();
    {
        std::lock_guard<std::mutex> lock(mMutex);
        mJob = camera;
        mAspect = aspect;
        mInvalidate = lightsChanged;
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
        Camera camera;
        float aspect = 1.0f;
        bool invalidate = false;
        {
            std::unique_lock<std::mutex> lock(mMutex);
            mCondition.wait(lock, [this] { return mStop || mJob.has_value(); });
            if (mStop) return;
            camera = *mJob;
            invalidate = mInvalidate;
            aspect = mAspect;
            mJob.reset();
        }
        try {
            if (invalidate) mSampler.invalidateRadiance();
            mSampler.step(camera, aspect);
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
