// Per-pass timing. On software rasterizers (llvmpipe) GL_TIME_ELAPSED is not trustworthy
// (../shared/ENVIRONMENT.md), so passes are bracketed by glFinish and a wall clock; on GPUs a
// GL_TIME_ELAPSED query is used. Every scope also pushes a KHR_debug group.
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "debug.h"
#include "objects.h"

namespace vplgi::gl {

struct PassTime {
    std::string name;
    double milliseconds = 0.0;
};

class PassTimer {
public:
    enum class Mode { FinishAndWallClock, TimerQuery };
    explicit PassTimer(Mode mode) : mMode(mode) {}
    Mode mode() const { return mMode; }

    void beginFrame() { mTimes.clear(); }
    const std::vector<PassTime>& times() const { return mTimes; }
    double total() const;

    class Scope {
    public:
        Scope(PassTimer& timer, std::string name);
        ~Scope();
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        PassTimer& mTimer;
        std::string mName;
        DebugGroup mGroup;
        Query mQuery;
        std::chrono::steady_clock::time_point mStart;
    };

private:
    Mode mMode;
    std::vector<PassTime> mTimes;
};

} // namespace vplgi::gl
