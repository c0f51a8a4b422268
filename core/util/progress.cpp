#include "core/util/progress.h"

#include <cstdio>

namespace vplgi {

ProgressSink terminalProgressBar()
{
    return [](const std::string& task, int done, int total) {
        const int width = 30, filled = total > 0 ? done * width / total : width;
        std::fprintf(stderr, "\r%s [%.*s%*s] %d/%d", task.c_str(), filled, "##############################",
                     width - filled, "", done, total);
        if (done >= total) std::fprintf(stderr, "\n");
        std::fflush(stderr);
    };
}

} // namespace vplgi
