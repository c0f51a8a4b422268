// vplgi: the command-line entry point. Subcommands: render (headless EGL), view (window).
// Only this function catches: any Error prints one line and exits with status 1.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "commands.h"
#include "core/util/error.h"

namespace {

const char* kUsage =
    "usage: vplgi <command> [options]\n"
    "\n"
    "vplgi renders virtual-light global illumination (SMCIR, VSGL, LightSkin+BRSM) and compares it\n"
    "with references. Every command has --help.\n"
    "\n"
    "commands:\n"
    "  render   render a scene headless (EGL) to a PNG (tone-mapped) or EXR (linear radiance)\n"
    "  view     open a window with camera controls (needs a display)\n"
    "  reference  path-trace a ground-truth EXR (Embree; full, direct, indirect or clamped)\n"
    "  compare  render techniques and references, write an HTML report with metrics and plots\n"
    "  bench    per-pass timings of a technique (and ratios against another)\n"
    "  conform  every technique against the path tracer over seeds and scenes (bias with intervals)\n"
    "  smcir-selection  what SMCIR's selection adds over the frames (CPU sampler only, over seeds)\n"
    "  scenes   list the built-in scenes and techniques\n";

} // namespace

int main(int argc, char** argv)
{
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        std::fputs(kUsage, args.empty() ? stderr : stdout);
        return args.empty() ? 2 : 0;
    }
    const std::string command = args[0];
    args.erase(args.begin());
    try {
        if (command == "render") return vplgi::runRender(args);
        if (command == "view") return vplgi::runView(args);
        if (command == "scenes") return vplgi::runScenes(args);
        if (command == "reference") return vplgi::runReference(args);
        if (command == "compare") return vplgi::runCompare(args);
        if (command == "bench") return vplgi::runBench(args);
        if (command == "conform") return vplgi::runConform(args);
        if (command == "smcir-selection") return vplgi::runSMCIRSelection(args);
        throw vplgi::Error("unknown command \"" + command +
                           "\" (commands: render, view, reference, compare, bench, conform, smcir-selection, scenes; see vplgi --help)");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "vplgi: error: %s\n", e.what());
        return 1;
    }
}
