#include "fuzz_sandbox.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <system_error>
#include <vector>

namespace vplgi::fuzz {

namespace {

namespace fs = std::filesystem;

std::string gSandbox; // global: the atexit handler needs it after sandboxDir()'s frame is gone

void removeSandbox()
{
    std::error_code ec;
    if (!gSandbox.empty()) fs::remove_all(gSandbox, ec);
}

std::string makeSandbox()
{
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/vplgi-fuzz-XXXXXX";
    std::vector<char> name(pattern.begin(), pattern.end());
    name.push_back('\0');
    if (mkdtemp(name.data()) == nullptr) {
        std::perror("vplgi fuzz: mkdtemp");
        std::abort();
    }
    gSandbox = fs::canonical(name.data()).string();
    std::atexit(removeSandbox);

    if (const char* files = std::getenv("VPLGI_FUZZ_FILES"); files != nullptr && *files != '\0') {
        std::error_code ec;
        fs::copy(files, gSandbox, fs::copy_options::recursive, ec);
        if (ec) {
            std::fprintf(stderr, "vplgi fuzz: cannot copy %s into %s: %s\n", files, gSandbox.c_str(),
                         ec.message().c_str());
            std::abort();
        }
    }
    // tinygltf also looks for URIs in the working directory; make that the sandbox as well.
    if (chdir(gSandbox.c_str()) != 0) {
        std::perror("vplgi fuzz: chdir");
        std::abort();
    }
    return gSandbox;
}

} // namespace

const std::string& sandboxDir()
{
    static const std::string dir = makeSandbox();
    return dir;
}

} // namespace vplgi::fuzz
