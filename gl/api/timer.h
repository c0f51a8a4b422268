// Per-pass timing with nestable scopes. Every scope also pushes a KHR_debug group.
//
// Two backends:
// - FinishAndWallClock (software rasterizers such as llvmpipe, where GPU timer queries are not
//   trustworthy, ../shared/ENVIRONMENT.md): glFinish + a steady clock at scope begin and end. The
//   frame's times are complete when the frame ends, so times() is the frame just rendered.
// - TimestampQueries (GPUs): a GL_TIMESTAMP query at scope begin and at scope end. Timestamps nest,
//   unlike GL_TIME_ELAPSED (only one may be active per target, so a scope inside the renderer's
//   technique scope would be GL_INVALID_OPERATION). Results are not read at once, which would stall
//   the pipeline: each frame records into one of kFrameSlots query sets, and later frames poll
//   GL_QUERY_RESULT_AVAILABLE without blocking and publish the frames whose results are complete.
//   times() is therefore the most recent complete frame, usually 1-3 frames behind; timesFrame()
//   says which one. resolve(true) waits for everything issued (shutdown, end of a benchmark).
//
// Scopes are recorded in the order they open (a parent before its children), each with its depth
// (0 = top level). total() sums the top-level scopes only: nested ones are inside their parent.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <deque>
#include <iterator>
#include <string>
#include <vector>

#include "debug.h"
#include "objects.h"

namespace vplgi::gl {

struct PassTime {
    std::string name; // the scope's own name
    std::string path; // "parent / child" for nested scopes; equal to name at depth 0
    int depth = 0;    // 0 = top level
    double milliseconds = 0.0;
    std::uint64_t beginNs = 0; // GPU timestamps [ns] (TimestampQueries only; 0 otherwise)
    std::uint64_t endNs = 0;
};

struct FrameTimes {
    std::int64_t frame = -1; // index of the frame that issued these scopes (0 = first beginFrame)
    std::vector<PassTime> passes;
    double total() const; // sum of the top-level scopes [ms]
};

class PassTimer {
public:
    enum class Mode { FinishAndWallClock, TimestampQueries };
    // FinishAndWallClock on software rasterizers (gl::isSoftwareRenderer()), TimestampQueries otherwise.
    static Mode defaultMode();

    explicit PassTimer(Mode mode) : mMode(mode) {}
    Mode mode() const { return mMode; }

    // Ends an open frame, publishes the older frames whose results are available (never blocks
    // unless all kFrameSlots sets are still in flight) and starts recording a new frame.
    void beginFrame();
    // Closes the frame being recorded (all scopes must be closed). With FinishAndWallClock it is
    // published at once; with TimestampQueries it is published once its results are available.
    void endFrame();
    // Publishes every closed frame whose results are available; with wait = true waits for all of them.
    void resolve(bool wait);

    // The most recent complete frame (empty before the first one is published) and its index.
    const std::vector<PassTime>& times() const { return mLatest.passes; }
    std::int64_t timesFrame() const { return mLatest.frame; }
    double total() const { return mLatest.total(); }
    // Frames begun so far; the next beginFrame() records frame framesBegun().
    std::int64_t framesBegun() const { return mFramesBegun; }
    // Every frame published since the last call, oldest first, for callers that need each frame's
    // times (bench). Only the newest kMaxUnread are kept for callers that never take them.
    std::vector<FrameTimes> takeCompletedFrames();

    class Scope {
    public:
        Scope(PassTimer& timer, std::string name);
        ~Scope();
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        PassTimer& mTimer;
        DebugGroup mGroup;
        std::size_t mIndex; // into the recording frame's scopes
        std::chrono::steady_clock::time_point mStart;
    };

    // Sets of queries in flight: a frame's results must be available before its set is reused.
    static constexpr int kFrameSlots = 4;
    static constexpr std::size_t kMaxUnread = 64;

private:
    struct FrameSlot {
        enum class State { Free, Recording, Pending };
        State state = State::Free;
        FrameTimes times;
        std::vector<Query> queries;                           // created on demand, re-used every frame
        std::size_t queriesUsed = 0;                          // this frame's, in issue order
        std::vector<std::array<std::size_t, 2>> scopeQueries; // begin and end query of each scope
    };

    std::size_t openScope(const std::string& name);
    void closeScope(std::size_t index, double wallMilliseconds);
    std::size_t issueTimestamp(FrameSlot& slot);
    // Publishes closed frames oldest first, waiting for those up to frame `waitThrough` and stopping
    // at the first later one whose results are not available yet.
    void collect(std::int64_t waitThrough);
    // Publishes `slot` if its results are available (or always, waiting, when wait is true).
    bool tryPublish(FrameSlot& slot, bool wait);
    void publish(FrameTimes&& times);
    FrameSlot& recording() { return mSlots[mRecordingSlot]; }

    Mode mMode;
    std::array<FrameSlot, kFrameSlots> mSlots;
    int mRecordingSlot = -1; // slot of the frame being recorded; -1 between frames
    std::int64_t mFramesBegun = 0;
    std::vector<std::size_t> mOpenScopes; // stack of indices into the recording frame's scopes
    FrameTimes mLatest;
    std::deque<FrameTimes> mUnread;
};

} // namespace vplgi::gl
