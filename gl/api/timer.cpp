#include "timer.h"

#include <algorithm>
#include <cassert>
#include <limits>

#include "context.h"

namespace vplgi::gl {

double FrameTimes::total() const
{
    double sum = 0.0;
    for (const PassTime& t : passes)
        if (t.depth == 0) sum += t.milliseconds;
    return sum;
}

PassTimer::Mode PassTimer::defaultMode()
{
    return isSoftwareRenderer() ? Mode::FinishAndWallClock : Mode::TimestampQueries;
}

void PassTimer::beginFrame()
{
    if (mRecordingSlot >= 0) endFrame();
    collect(-1);
    // The ring's next set: the oldest in flight. If it is still pending the GPU is kFrameSlots
    // frames behind; waiting for it then is what bounds both the lag and the number of queries.
    const int slotIndex = static_cast<int>(mFramesBegun % kFrameSlots);
    FrameSlot& slot = mSlots[slotIndex];
    if (slot.state == FrameSlot::State::Pending) collect(slot.times.frame);
    assert(slot.state == FrameSlot::State::Free);
    slot.state = FrameSlot::State::Recording;
    slot.times.frame = mFramesBegun++;
    slot.times.passes.clear();
    slot.queriesUsed = 0;
    slot.scopeQueries.clear();
    mRecordingSlot = slotIndex;
}

void PassTimer::endFrame()
{
    if (mRecordingSlot < 0) return;
    assert(mOpenScopes.empty() && "a PassTimer::Scope is still open at the end of the frame");
    FrameSlot& slot = recording();
    mRecordingSlot = -1;
    slot.state = FrameSlot::State::Pending;
    // Wall-clock times are complete once the last scope closed (it called glFinish).
    if (mMode == Mode::FinishAndWallClock) tryPublish(slot, true);
}

void PassTimer::resolve(bool wait)
{
    collect(wait ? std::numeric_limits<std::int64_t>::max() : -1);
}

std::vector<FrameTimes> PassTimer::takeCompletedFrames()
{
    std::vector<FrameTimes> frames(std::make_move_iterator(mUnread.begin()), std::make_move_iterator(mUnread.end()));
    mUnread.clear();
    return frames;
}

std::size_t PassTimer::issueTimestamp(FrameSlot& slot)
{
    if (slot.queriesUsed == slot.queries.size()) {
        const std::size_t slotIndex = static_cast<std::size_t>(&slot - mSlots.data());
        slot.queries.emplace_back("pass timer set " + std::to_string(slotIndex) + " query " +
                                      std::to_string(slot.queries.size()),
                                  GL_TIMESTAMP);
    }
    glQueryCounter(slot.queries[slot.queriesUsed].id(), GL_TIMESTAMP);
    return slot.queriesUsed++;
}

std::size_t PassTimer::openScope(const std::string& name)
{
    if (mRecordingSlot < 0) beginFrame(); // a scope outside beginFrame/endFrame starts a frame
    FrameSlot& slot = recording();
    PassTime t;
    t.name = name;
    t.depth = static_cast<int>(mOpenScopes.size());
    t.path = mOpenScopes.empty() ? name : slot.times.passes[mOpenScopes.back()].path + " / " + name;
    const std::size_t index = slot.times.passes.size();
    slot.times.passes.push_back(std::move(t));
    if (mMode == Mode::TimestampQueries) slot.scopeQueries.push_back({issueTimestamp(slot), 0});
    mOpenScopes.push_back(index);
    return index;
}

void PassTimer::closeScope(std::size_t index, double wallMilliseconds)
{
    assert(!mOpenScopes.empty() && mOpenScopes.back() == index && "PassTimer scopes must close in reverse order");
    mOpenScopes.pop_back();
    FrameSlot& slot = recording();
    if (mMode == Mode::TimestampQueries)
        slot.scopeQueries[index][1] = issueTimestamp(slot);
    else
        slot.times.passes[index].milliseconds = wallMilliseconds;
}

void PassTimer::collect(std::int64_t waitThrough)
{
    std::vector<FrameSlot*> pending;
    for (FrameSlot& slot : mSlots)
        if (slot.state == FrameSlot::State::Pending) pending.push_back(&slot);
    std::sort(pending.begin(), pending.end(),
              [](const FrameSlot* a, const FrameSlot* b) { return a->times.frame < b->times.frame; });
    // In frame order, so that published frames (and takeCompletedFrames) never go backwards.
    for (FrameSlot* slot : pending)
        if (!tryPublish(*slot, slot->times.frame <= waitThrough)) break;
}

bool PassTimer::tryPublish(FrameSlot& slot, bool wait)
{
    if (mMode == Mode::TimestampQueries) {
        if (!wait) {
            // Checked in issue order: the first one not yet available ends the poll.
            for (std::size_t q = 0; q < slot.queriesUsed; ++q) {
                GLint available = GL_FALSE;
                glGetQueryObjectiv(slot.queries[q].id(), GL_QUERY_RESULT_AVAILABLE, &available);
                if (available != GL_TRUE) return false;
            }
        }
        std::vector<GLuint64> ns(slot.queriesUsed, 0);
        for (std::size_t q = 0; q < slot.queriesUsed; ++q)
            glGetQueryObjectui64v(slot.queries[q].id(), GL_QUERY_RESULT, &ns[q]); // waits only when wait is true
        for (std::size_t i = 0; i < slot.times.passes.size(); ++i) {
            PassTime& t = slot.times.passes[i];
            t.beginNs = ns[slot.scopeQueries[i][0]];
            t.endNs = ns[slot.scopeQueries[i][1]];
            t.milliseconds = t.endNs > t.beginNs ? static_cast<double>(t.endNs - t.beginNs) * 1e-6 : 0.0;
        }
    }
    slot.state = FrameSlot::State::Free;
    publish(std::move(slot.times));
    slot.times = FrameTimes{};
    return true;
}

void PassTimer::publish(FrameTimes&& times)
{
    mLatest = times;
    mUnread.push_back(std::move(times));
    while (mUnread.size() > kMaxUnread)
        mUnread.pop_front();
}

PassTimer::Scope::Scope(PassTimer& timer, std::string name) : mTimer(timer), mGroup(name), mIndex(timer.openScope(name))
{
    if (mTimer.mMode == Mode::FinishAndWallClock) {
        glFinish();
        mStart = std::chrono::steady_clock::now();
    }
}

PassTimer::Scope::~Scope()
{
    double ms = 0.0;
    if (mTimer.mMode == Mode::FinishAndWallClock) {
        glFinish();
        ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - mStart).count();
    }
    mTimer.closeScope(mIndex, ms);
}

} // namespace vplgi::gl
