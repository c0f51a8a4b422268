// Image files: round trips through OpenImageIO, and no half-written files on failure, whether the
// write is refused before a file is opened or fails while the bytes go out.
#include <catch2/catch.hpp>

#include <csignal>
#include <filesystem>
#include <random>

#include <sys/resource.h>
#include <unistd.h>

#include "core/util/error.h"
#include "core/util/image_io.h"

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

namespace {

// Limits the size of files this process writes (RLIMIT_FSIZE) while it lives: a write(2) past the
// limit fails with EFBIG, as one on a full disk fails with ENOSPC. SIGXFSZ, which would kill the
// process first, is ignored meanwhile.
class FileSizeLimit {
public:
    explicit FileSizeLimit(rlim_t bytes)
    {
        REQUIRE(::getrlimit(RLIMIT_FSIZE, &mSaved) == 0);
        mSavedHandler = std::signal(SIGXFSZ, SIG_IGN);
        rlimit limited = mSaved;
        limited.rlim_cur = bytes;
        REQUIRE(::setrlimit(RLIMIT_FSIZE, &limited) == 0);
    }
    ~FileSizeLimit()
    {
        ::setrlimit(RLIMIT_FSIZE, &mSaved);
        std::signal(SIGXFSZ, mSavedHandler);
    }
    FileSizeLimit(const FileSizeLimit&) = delete;
    FileSizeLimit& operator=(const FileSizeLimit&) = delete;

private:
    rlimit mSaved{};
    void (*mSavedHandler)(int) = SIG_DFL;
};

} // namespace

TEST_CASE("a write that fails midway leaves the old file, no partial file and no temporary", "[image]")
{
    // A real failure after the temporary file was created and partly written: the file size limit
    // stops the bytes at 4 KiB, far below the size of these noise images (PNG ~64 KiB, EXR ~256
    // KiB, both incompressible). Before the fix, OpenImageIO's PNG writer ignored the failed
    // writes and a truncated 4 KiB PNG was renamed over the target.
    fs::path dir = scratchDirectory("midway");
    std::mt19937 engine(3u);
    ImageRGBA8 bytes;
    bytes.width = bytes.height = 128;
    for (int i = 0; i < 128 * 128 * 4; ++i) // opaque: OpenImageIO premultiplies by alpha on the way out
        bytes.pixels.push_back(i % 4 == 3 ? std::uint8_t{255} : static_cast<std::uint8_t>(engine()));
    ImageRGBA32F linear;
    linear.width = linear.height = 128;
    for (int i = 0; i < 128 * 128 * 4; ++i) linear.pixels.push_back(static_cast<float>(engine()) * 0x1p-32f);

    // The previous versions of the targets, tiny images written without a limit.
    ImageRGBA8 oldBytes;
    oldBytes.width = oldBytes.height = 1;
    oldBytes.pixels = {9, 8, 7, 255};
    ImageRGBA32F oldLinear;
    oldLinear.width = oldLinear.height = 1;
    oldLinear.pixels = {0.5f, 0.25f, 0.125f, 1.0f};
    const std::string png = (dir / "noise.png").string(), exr = (dir / "noise.exr").string();
    writeImage(png, oldBytes);
    writeImage(exr, oldLinear);
    {
        FileSizeLimit limit(4096);
        CHECK_THROWS_WITH(writeImage(png, bytes), png + ": write failed: File too large");
        CHECK_THROWS_WITH(writeImage(exr, linear), exr + ": write failed: File too large");
        // Failing onto a new name: nothing appears.
        CHECK_THROWS_WITH(writeImage((dir / "new.png").string(), bytes), Catch::Contains("write failed"));
    }
    int entries = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
        INFO("left in the directory: " << entry.path().string());
        CHECK((entry.path().filename() == "noise.png" || entry.path().filename() == "noise.exr"));
        ++entries;
    }
    CHECK(entries == 2);
    CHECK(readImage8(png).pixels == oldBytes.pixels); // the old files are untouched
    CHECK(readImageLinear(exr).pixels == oldLinear.pixels);

    // The same images are written in full once the limit is gone (the failures above were the limit).
    writeImage(png, bytes);
    writeImage(exr, linear);
    CHECK(readImage8(png).pixels == bytes.pixels);
    CHECK(readImageLinear(exr).pixels == linear.pixels);
    fs::remove_all(dir);
}
