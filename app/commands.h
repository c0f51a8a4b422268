// The subcommands of the vplgi executable. Each parses its own options (with --help) and returns
// the process exit status; errors are thrown as vplgi::Error.
#pragma once

#include <string>
#include <vector>

namespace vplgi {

int runRender(const std::vector<std::string>& args);
int runView(const std::vector<std::string>& args);
int runScenes(const std::vector<std::string>& args);
int runReference(const std::vector<std::string>& args);
int runCompare(const std::vector<std::string>& args);
int runBench(const std::vector<std::string>& args);
int runConform(const std::vector<std::string>& args);
int runSMCIRSelection(const std::vector<std::string>& args);

} // namespace vplgi
