// The optional shared test assets (../shared beside the repository: glTF scenes and more), found the
// same way by every test that needs them. tests/cli/shared_assets.sh is the shell twin.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace vplgi::test {

// $VPLGI_SHARED_DIR when set and not empty, else the build's default (the CMake cache variable
// VPLGI_SHARED_DIR, <repo>/../shared unless configured otherwise).
std::filesystem::path sharedAssetsDir();

// The path of `relative` (a file or folder) under sharedAssetsDir() when it exists. When it does
// not: with CI=true in the environment the test fails (CI always has ../shared, so its absence is a
// broken set-up, not a reason to skip an acceptance check); otherwise the test is skipped with a
// printed message and nullopt is returned. Call from inside a TEST_CASE.
std::optional<std::filesystem::path> findSharedAsset(const std::string& relative);

} // namespace vplgi::test
