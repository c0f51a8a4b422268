// Warnings: input that vplgi accepts but changes or that is probably not what the user meant
// (degenerate triangles dropped on load, a scene without any light) is reported as one line,
// "vplgi: warning: <what>", on stderr, and the run goes on. Errors (core/util/error.h) stop it.
// Header-only so that any library can warn without a link dependency.
#pragma once

#include <cstdio>
#include <functional>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace vplgi {

namespace detail {

using WarningSink = std::function<void(const std::string&)>;

inline std::mutex& warningMutex()
{
    static std::mutex mutex;
    return mutex;
}

// Empty: print to stderr.
inline WarningSink& warningSink()
{
    static WarningSink sink;
    return sink;
}

} // namespace detail

// Reports one warning (one line, no trailing newline; the message names the thing).
inline void warn(const std::string& message)
{
    std::lock_guard<std::mutex> lock(detail::warningMutex());
    if (detail::warningSink())
        detail::warningSink()(message);
    else
        std::fprintf(stderr, "vplgi: warning: %s\n", message.c_str());
}

// For tests: while alive, warnings are collected here instead of printed.
class WarningCapture {
public:
    WarningCapture()
    {
        std::lock_guard<std::mutex> lock(detail::warningMutex());
        mPrevious = std::exchange(detail::warningSink(), [this](const std::string& m) { mMessages.push_back(m); });
    }
    ~WarningCapture()
    {
        std::lock_guard<std::mutex> lock(detail::warningMutex());
        detail::warningSink() = std::move(mPrevious);
    }
    WarningCapture(const WarningCapture&) = delete;
    WarningCapture& operator=(const WarningCapture&) = delete;

    const std::vector<std::string>& messages() const { return mMessages; }

private:
    detail::WarningSink mPrevious;
    std::vector<std::string> mMessages;
};

} // namespace vplgi
