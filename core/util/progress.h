// Progress of long CPU work (warm-up, precomputation) reported to whoever shows it: a terminal bar
// today, the viewer's window overlay later. Called on the thread doing the work, between steps.
#pragma once

#include <functional>
#include <string>

namespace vplgi {

// task: what is running ("smcir warm-up"); done of total steps (done == total: finished).
using ProgressSink = std::function<void(const std::string& task, int done, int total)>;

// "\r<task> [#####     ] done/total" on stderr, a newline when done == total; when stderr is not a
// terminal, only the finished bar.
ProgressSink terminalProgressBar();

} // namespace vplgi
