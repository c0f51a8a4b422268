#include "core/util/image_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <random>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "core/util/error.h"

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

void writeAtomically(const std::string& path, int width, int height, OIIO::TypeDesc type, const void* pixels)
{
    checkOutputPath(path);
    fs::path target(path);
    fs::path directory = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    require(fs::is_directory(directory), path + ": directory " + directory.string() + " does not exist");
    // Encode in memory, then write the bytes with every error checked: OpenImageIO's PNG writer
    // does not report failed writes to its file (with a full disk it "succeeds" with a truncated
    // file), so it never touches the file itself.
    std::vector<unsigned char> encoded;
    {
        OIIO::Filesystem::IOVecOutput proxy(encoded);
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(target.filename().string());
        require(out != nullptr && out->supports("ioproxy"), path + ": cannot write this format");
        OIIO::ImageSpec spec(width, height, 4, type);
        if (type == OIIO::TypeDesc::FLOAT) spec.attribute("compression", "zip");
        bool ok = out->set_ioproxy(&proxy) && out->open(target.filename().string(), spec) &&
                  out->write_image(type, pixels) && out->close();
        if (!ok) throw Error(path + ": write failed: " + out->geterror());
    }
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

std::unique_ptr<OIIO::ImageInput> openInput(const std::string& path)
{
    require(fs::exists(path), path + ": no such file");
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
    require(in != nullptr, path + ": cannot read image: " + OIIO::geterror());
    return in;
}

template <typename T>
std::vector<T> readRGBA(OIIO::ImageInput& in, const std::string& path, OIIO::TypeDesc type)
{
    const OIIO::ImageSpec& spec = in.spec();
    int channels = spec.nchannels;
    std::vector<T> raw(static_cast<std::size_t>(spec.width) * spec.height * channels);
    require(in.read_image(0, 0, 0, channels, type, raw.data()), path + ": read failed: " + in.geterror());
    std::vector<T> rgba(static_cast<std::size_t>(spec.width) * spec.height * 4);
    const T opaque = type == OIIO::TypeDesc::FLOAT ? T(1) : T(255);
    for (std::size_t p = 0; p < static_cast<std::size_t>(spec.width) * spec.height; ++p) {
        for (int c = 0; c < 4; ++c) {
            T value = c < channels ? raw[p * channels + c] : (c == 3 ? opaque : raw[p * channels]);
            rgba[p * 4 + c] = value;
        }
    }
    return rgba;
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
    writeAtomically(path, image.width, image.height, OIIO::TypeDesc::UINT8, image.pixels.data());
}

void writeImage(const std::string& path, const ImageRGBA32F& image)
{
    require(isFloatImagePath(path), path + ": linear images are written as .exr");
    writeAtomically(path, image.width, image.height, OIIO::TypeDesc::FLOAT, image.pixels.data());
}

ImageRGBA32F readImageLinear(const std::string& path)
{
    std::unique_ptr<OIIO::ImageInput> in = openInput(path);
    ImageRGBA32F image;
    image.width = in->spec().width;
    image.height = in->spec().height;
    image.pixels = readRGBA<float>(*in, path, OIIO::TypeDesc::FLOAT);
    return image;
}

ImageRGBA8 readImage8(const std::string& path)
{
    std::unique_ptr<OIIO::ImageInput> in = openInput(path);
    ImageRGBA8 image;
    image.width = in->spec().width;
    image.height = in->spec().height;
    image.pixels = readRGBA<std::uint8_t>(*in, path, OIIO::TypeDesc::UINT8);
    return image;
}

} // namespace vplgi
