#include "timer.h"

namespace vplgi::gl {

double PassTimer::total() const
{
    double sum = 0.0;
    for (const PassTime& t : mTimes) sum += t.milliseconds;
    return sum;
}

PassTimer::Scope::Scope(PassTimer& timer, std::string name) : mTimer(timer), mName(std::move(name)), mGroup(mName)
{
    if (mTimer.mMode == Mode::TimerQuery) {
        mQuery = Query("timer " + mName, GL_TIME_ELAPSED);
        glBeginQuery(GL_TIME_ELAPSED, mQuery.id());
    } else {
        glFinish();
        mStart = std::chrono::steady_clock::now();
    }
}

PassTimer::Scope::~Scope()
{
    double ms = 0.0;
    if (mTimer.mMode == Mode::TimerQuery) {
        glEndQuery(GL_TIME_ELAPSED);
        GLuint64 ns = 0;
        glGetQueryObjectui64v(mQuery.id(), GL_QUERY_RESULT, &ns);
        ms = static_cast<double>(ns) * 1e-6;
    } else {
        glFinish();
        ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - mStart).count();
    }
    mTimer.mTimes.push_back({mName, ms});
}

} // namespace vplgi::gl
