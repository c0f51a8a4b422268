#include "core/util/image_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <random>

#include <dlfcn.h>

#include "core/util/error.h"
#include "core/util/image_codec.h"

namespace vplgi {

namespace fs = std::filesystem;

namespace {

std::string lowerExtension(const std::string& path)
{
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

fs::path temporarySibling(const fs::path& target)
{
    std::random_device rd;
    std::string name = "." + target.stem().string() + ".partial-" + std::to_string(rd()) + target.extension().string();
    return target.parent_path() / name;
}

// Writes `bytes` to `file` and closes it, reporting any failure (a full disk, a file size limit,
// an I/O error) as the errno text; the caller removes the file.
bool writeBytes(const fs::path& file, const std::vector<unsigned char>& bytes, std::string& message)
{
    std::FILE* stream = std::fopen(file.c_str(), "wb");
    if (stream == nullptr) {
        message = std::strerror(errno);
        return false;
    }
    bool ok = std::fwrite(bytes.data(), 1, bytes.size(), stream) == bytes.size();
    if (!ok) message = std::strerror(errno);
    if (std::fclose(stream) != 0 && ok) { // fclose flushes: a late error shows here
        message = std::strerror(errno);
        ok = false;
    }
    return ok;
}

#ifdef VPLGI_IMAGE_CODEC_LINKED
// Sanitizer builds: the codec is linked in (core/CMakeLists.txt says why).
const VplgiImageCodec& codec()
{
    return *vplgi_image_codec();
}
#else
// The OpenImageIO codec module (core/util/image_codec.h says why it is loaded on first use): first
// beside the running executable (a copied binary takes its module along), then where the build put it.
const VplgiImageCodec& codec()
{
    static std::once_flag once;
    static const VplgiImageCodec* loaded = nullptr;
    static std::string failure;
    std::call_once(once, [] {
        const std::string name = "libvplgi_image_oiio.so";
        std::vector<std::string> candidates;
        std::error_code ec;
        const fs::path executable = fs::read_symlink("/proc/self/exe", ec);
        if (!ec) candidates.push_back((executable.parent_path() / name).string());
        candidates.push_back(VPLGI_IMAGE_MODULE);
        std::string reasons;
        for (const std::string& candidate : candidates) {
            if (!fs::exists(candidate, ec)) continue;
            void* handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
            if (handle == nullptr) {
                const char* why = dlerror();
                reasons += "; " + candidate + ": " + (why != nullptr ? why : "dlopen failed");
                continue;
            }
            auto entry = reinterpret_cast<VplgiImageCodecEntry>(dlsym(handle, "vplgi_image_codec"));
            const VplgiImageCodec* found = entry != nullptr ? entry() : nullptr;
            if (found == nullptr || found->version != kVplgiImageCodecVersion) {
                reasons += "; " + candidate + ": not this build's module";
                continue;
            }
            loaded = found;
            return;
        }
        failure = "cannot load the image module " + name + " (beside the executable or at " + VPLGI_IMAGE_MODULE +
                  ")" + (reasons.empty() ? ": not found" : reasons);
    });
    if (loaded == nullptr) throw Error(failure);
    return *loaded;
}
#endif

void appendBytes(void* context, const void* bytes, std::size_t size)
{
    auto* encoded = static_cast<std::vector<unsigned char>*>(context);
    const auto* begin = static_cast<const unsigned char*>(bytes);
    encoded->insert(encoded->end(), begin, begin + size);
}

void writeAtomically(const std::string& path, int width, int height, bool floatPixels, const void* pixels)
{
    checkOutputPath(path);
    fs::path target(path);
    fs::path directory = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    require(fs::is_directory(directory), path + ": directory " + directory.string() + " does not exist");
    // Encode in memory, then write the bytes with every error checked: OpenImageIO's PNG writer
    // does not report failed writes to its file (with a full disk it "succeeds" with a truncated
    // file), so it never touches the file itself.
    std::vector<unsigned char> encoded;
    char error[512] = {};
    if (codec().encode(target.filename().c_str(), width, height, floatPixels ? 1 : 0, pixels, &appendBytes, &encoded,
                       error, sizeof error) == 0)
        throw Error(path + ": " + error);
    fs::path temporary = temporarySibling(directory / target.filename());
    std::string message;
    std::error_code ec;
    if (!writeBytes(temporary, encoded, message)) {
        fs::remove(temporary, ec);
        throw Error(path + ": write failed: " + message);
    }
    fs::rename(temporary, target, ec);
    if (ec) {
        fs::remove(temporary, ec);
        throw Error(path + ": cannot rename the finished file into place");
    }
}

// Reads `path` as RGBA into `image` (ImageRGBA32F or ImageRGBA8).
template <typename Image>
Image readRGBA(const std::string& path, bool floatPixels)
{
    require(fs::exists(path), path + ": no such file");
    Image image;
    auto allocate = [](void* context, int width, int height) -> void* {
        auto* target = static_cast<Image*>(context);
        if (width <= 0 || height <= 0) return nullptr;
        target->width = width;
        target->height = height;
        target->pixels.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4, 0);
        return target->pixels.data();
    };
    char error[512] = {};
    if (codec().decode(path.c_str(), floatPixels ? 1 : 0, allocate, &image, error, sizeof error) == 0)
        throw Error(path + ": " + error);
    return image;
}

} // namespace

bool isFloatImagePath(const std::string& path)
{
    std::string ext = lowerExtension(path);
    return ext == ".exr" || ext == ".hdr" || ext == ".pfm";
}

void checkOutputPath(const std::string& path)
{
    std::string ext = lowerExtension(path);
    require(ext == ".png" || ext == ".exr", path + ": output must end in .png or .exr");
}

void checkWritableDirectory(const std::string& path)
{
    const fs::path target(path);
    const fs::path directory = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    std::error_code ec;
    require(fs::exists(directory, ec), path + ": directory " + directory.string() + " does not exist");
    require(fs::is_directory(directory, ec), path + ": " + directory.string() + " is not a directory");
    const fs::path probe =
        temporarySibling(directory / (target.filename().empty() ? fs::path("probe") : target.filename()));
    std::FILE* stream = std::fopen(probe.c_str(), "wb");
    if (stream == nullptr) throw Error(path + ": cannot write in " + directory.string() + ": " + std::strerror(errno));
    std::fclose(stream);
    fs::remove(probe, ec);
}

void writeImage(const std::string& path, const ImageRGBA8& image)
{
    require(!isFloatImagePath(path), path + ": an 8-bit image cannot be written as a float format");
    writeAtomically(path, image.width, image.height, false, image.pixels.data());
}

void writeImage(const std::string& path, const ImageRGBA32F& image)
{
    require(isFloatImagePath(path), path + ": linear images are written as .exr");
    writeAtomically(path, image.width, image.height, true, image.pixels.data());
}

ImageRGBA32F readImageLinear(const std::string& path)
{
    return readRGBA<ImageRGBA32F>(path, true);
}

ImageRGBA8 readImage8(const std::string& path)
{
    return readRGBA<ImageRGBA8>(path, false);
}

} // namespace vplgi
