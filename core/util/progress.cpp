#include "core/util/progress.h"

#include <cstdio>

#include <unistd.h>

namespace vplgi {

ProgressSink terminalProgressBar()
{
    // Into a log (not a terminal) only the finished bar, not one per update joined by carriage returns.
    const bool terminal = isatty(fileno(stderr)) != 0;
    return [terminal](const std::string& task, int done, int total) {
        if (!terminal && done < total) return;
        const int width = 30, filled = total > 0 ? done * width / total : width;
        std::fprintf(stderr, "\r%s [%.*s%*s] %d/%d", task.c_str(), filled, "##############################",
                     width - filled, "", done, total);
        if (done >= total) std::fprintf(stderr, "\n");
        std::fflush(stderr);
    };
}

} // namespace vplgi
