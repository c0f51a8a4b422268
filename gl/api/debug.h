// KHR_debug output: a synchronous callback that prints driver messages and remembers high-severity
// ones. Throwing from inside the driver's callback is not safe, so checkDebugMessages() throws
// afterwards (the renderer calls it after every frame; tests after every check).
#pragma once

#include <string>

namespace vplgi::gl {

void installDebugCallback(bool throwOnHighSeverity);
// Throws Error with the first high-severity message since the last call (when enabled).
void checkDebugMessages();
// Number of high-severity or error-type messages seen so far (tests, render --stats).
int highSeverityMessageCount();

// Scoped debug group (shows up in RenderDoc / apitrace).
class DebugGroup {
public:
    explicit DebugGroup(const std::string& name);
    ~DebugGroup();
    DebugGroup(const DebugGroup&) = delete;
    DebugGroup& operator=(const DebugGroup&) = delete;
};

} // namespace vplgi::gl
