#include "shared_assets.h"

#include <cstdlib>
#include <cstring>

#include <catch2/catch.hpp>

namespace vplgi::test {

std::filesystem::path sharedAssetsDir()
{
    const char* env = std::getenv("VPLGI_SHARED_DIR");
    if (env != nullptr && *env != '\0') return env;
    return VPLGI_SHARED_DIR;
}

std::optional<std::filesystem::path> findSharedAsset(const std::string& relative)
{
    const std::filesystem::path path = sharedAssetsDir() / relative;
    if (std::filesystem::exists(path)) return path;
    const char* ci = std::getenv("CI");
    if (ci != nullptr && std::strcmp(ci, "true") == 0)
        FAIL(path.string() << " is absent and CI=true: shared assets are required in CI (set VPLGI_SHARED_DIR)");
    WARN("skipped: " << path.string() << " is absent (set VPLGI_SHARED_DIR to the shared assets)");
    return std::nullopt;
}

} // namespace vplgi::test
