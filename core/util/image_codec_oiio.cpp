// The image codec module: encoding and decoding through OpenImageIO, behind the C interface of
// core/util/image_codec.h (why it is a module: there). Only image_io.cpp loads it.
#include "core/util/image_codec.h"

#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace {

int fail(char* error, int errorSize, const std::string& message)
{
    if (error != nullptr && errorSize > 0) std::snprintf(error, static_cast<std::size_t>(errorSize), "%s", message.c_str());
    return 0;
}

int encode(const char* fileName, int width, int height, int floatPixels, const void* pixels, VplgiImageSink sink,
           void* sinkContext, char* error, int errorSize)
{
    try {
        const OIIO::TypeDesc type = floatPixels != 0 ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
        // Into memory: OpenImageIO's PNG writer does not report failed writes to its file (with a
        // full disk it "succeeds" with a truncated file), so image_io.cpp writes the bytes itself.
        std::vector<unsigned char> encoded;
        OIIO::Filesystem::IOVecOutput proxy(encoded);
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(fileName);
        if (out == nullptr || !out->supports("ioproxy")) return fail(error, errorSize, "cannot write this format");
        OIIO::ImageSpec spec(width, height, 4, type);
        if (floatPixels != 0) spec.attribute("compression", "zip");
        const bool ok = out->set_ioproxy(&proxy) && out->open(fileName, spec) && out->write_image(type, pixels) &&
                        out->close();
        if (!ok) return fail(error, errorSize, "write failed: " + out->geterror());
        sink(sinkContext, encoded.data(), encoded.size());
        return 1;
    } catch (const std::exception& e) {
        return fail(error, errorSize, std::string("write failed: ") + e.what());
    } catch (...) {
        return fail(error, errorSize, "write failed");
    }
}

template <typename T>
int decodeAs(const char* path, OIIO::TypeDesc type, VplgiImageAllocate allocate, void* allocateContext, char* error,
             int errorSize)
{
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
    if (in == nullptr) return fail(error, errorSize, "cannot read image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    const int channels = spec.nchannels;
    const std::size_t count = static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height);
    std::vector<T> raw(count * static_cast<std::size_t>(channels));
    if (!in->read_image(0, 0, 0, channels, type, raw.data())) return fail(error, errorSize, "read failed: " + in->geterror());
    T* rgba = static_cast<T*>(allocate(allocateContext, spec.width, spec.height));
    if (rgba == nullptr) return fail(error, errorSize, "read failed: no memory for the pixels");
    const T opaque = type == OIIO::TypeDesc::FLOAT ? T(1) : T(255);
    for (std::size_t p = 0; p < count; ++p)
        for (int c = 0; c < 4; ++c)
            rgba[p * 4 + static_cast<std::size_t>(c)] =
                c < channels ? raw[p * static_cast<std::size_t>(channels) + static_cast<std::size_t>(c)]
                             : (c == 3 ? opaque : raw[p * static_cast<std::size_t>(channels)]);
    return 1;
}

int decode(const char* path, int floatPixels, VplgiImageAllocate allocate, void* allocateContext, char* error,
           int errorSize)
{
    try {
        return floatPixels != 0
                   ? decodeAs<float>(path, OIIO::TypeDesc::FLOAT, allocate, allocateContext, error, errorSize)
                   : decodeAs<unsigned char>(path, OIIO::TypeDesc::UINT8, allocate, allocateContext, error, errorSize);
    } catch (const std::exception& e) {
        return fail(error, errorSize, std::string("read failed: ") + e.what());
    } catch (...) {
        return fail(error, errorSize, "read failed");
    }
}

const VplgiImageCodec kCodec{kVplgiImageCodecVersion, &encode, &decode};

} // namespace

extern "C" __attribute__((visibility("default"))) const VplgiImageCodec* vplgi_image_codec(void)
{
    return &kCodec;
}
