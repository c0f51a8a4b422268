// Image files through OpenImageIO (a module loaded on the first read or write: core/util/image_codec.h).
// Writes are atomic: a temporary file in the same directory is
// renamed over the target, so a failed write never leaves a half-written file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vplgi {

// Linear RGBA float image, rows top to bottom.
struct ImageRGBA32F {
    int width = 0;
    int height = 0;
    std::vector<float> pixels; // width * height * 4

    float* at(int x, int y) { return &pixels[(static_cast<std::size_t>(y) * width + x) * 4]; }
    const float* at(int x, int y) const { return &pixels[(static_cast<std::size_t>(y) * width + x) * 4]; }
};

// Display-ready 8-bit RGBA (sRGB-encoded), rows top to bottom.
struct ImageRGBA8 {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels; // width * height * 4
};

void writeImage(const std::string& path, const ImageRGBA8& image);     // .png .jpg .tga ...
void writeImage(const std::string& path, const ImageRGBA32F& image);   // .exr (linear), .hdr
ImageRGBA32F readImageLinear(const std::string& path);                 // as stored (no decoding)
ImageRGBA8 readImage8(const std::string& path);

// True for extensions whose format stores linear floats (.exr, .hdr, .pfm).
bool isFloatImagePath(const std::string& path);
// Throws Error unless the extension is one vplgi writes (png, exr).
void checkOutputPath(const std::string& path);
// Throws Error unless a file can be created next to `path` (in its directory, which must exist):
// commands call it before their work, so that an unwritable output fails in a second, not after a
// long render. Creates and removes a temporary file there.
void checkWritableDirectory(const std::string& path);

} // namespace vplgi
