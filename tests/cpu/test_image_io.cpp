// Image files: round trips through OpenImageIO, and no half-written files on failure.
#include <catch2/catch.hpp>

#include <filesystem>

#include <unistd.h>

#include "core/error.h"
#include "core/image_io.h"

using namespace vplgi;
namespace fs = std::filesystem;

namespace {

fs::path scratchDirectory(const std::string& name)
{
    fs::path dir = fs::temp_directory_path() / ("vplgi-test-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

} // namespace

TEST_CASE("EXR keeps linear floats exactly, PNG keeps bytes", "[image]")
{
    fs::path dir = scratchDirectory("io");
    ImageRGBA32F linear;
    linear.width = 3;
    linear.height = 2;
    for (int i = 0; i < 24; ++i) linear.pixels.push_back(0.125f * i - 1.0f);
    writeImage((dir / "a.exr").string(), linear);
    ImageRGBA32F back = readImageLinear((dir / "a.exr").string());
    REQUIRE(back.width == 3);
    REQUIRE(back.height == 2);
    CHECK(back.pixels == linear.pixels);

    ImageRGBA8 bytes;
    bytes.width = 2;
    bytes.height = 2;
    bytes.pixels = {0, 10, 20, 255, 30, 40, 50, 255, 60, 70, 80, 255, 90, 100, 110, 255};
    writeImage((dir / "b.png").string(), bytes);
    CHECK(readImage8((dir / "b.png").string()).pixels == bytes.pixels);
    fs::remove_all(dir);
}

TEST_CASE("failed writes leave no file behind", "[image]")
{
    fs::path dir = scratchDirectory("fail");
    ImageRGBA8 bytes;
    bytes.width = 1;
    bytes.height = 1;
    bytes.pixels = {1, 2, 3, 4};
    CHECK_THROWS_WITH(writeImage((dir / "missing" / "x.png").string(), bytes), Catch::Contains("does not exist"));
    CHECK_THROWS_WITH(writeImage((dir / "x.jpg").string(), bytes), Catch::Contains("must end in .png or .exr"));
    CHECK_THROWS_AS(writeImage((dir / "x.exr").string(), bytes), Error);
    CHECK(fs::is_empty(dir));
    CHECK_THROWS_WITH(readImage8((dir / "none.png").string()), Catch::Contains("no such file"));
    fs::remove_all(dir);
}
