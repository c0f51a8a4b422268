#include "image_downscale.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <vector>

namespace vplgi {

namespace {

Image halve(const Image& src)
{
    Image dst;
    dst.name = src.name;
    dst.width = std::max(1, (src.width + 1) / 2);
    dst.height = std::max(1, (src.height + 1) / 2);
    dst.rgba.resize(static_cast<std::size_t>(dst.width) * static_cast<std::size_t>(dst.height) * 4);
    const auto texel = [&](int x, int y, int c) -> std::uint32_t {
        x = std::min(x, src.width - 1);
        y = std::min(y, src.height - 1);
        return src.rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(src.width) + static_cast<std::size_t>(x)) * 4 +
                        static_cast<std::size_t>(c)];
    };
    for (int y = 0; y < dst.height; ++y)
        for (int x = 0; x < dst.width; ++x)
            for (int c = 0; c < 4; ++c) {
                const std::uint32_t sum = texel(2 * x, 2 * y, c) + texel(2 * x + 1, 2 * y, c) +
                                          texel(2 * x, 2 * y + 1, c) + texel(2 * x + 1, 2 * y + 1, c);
                dst.rgba[(static_cast<std::size_t>(y) * static_cast<std::size_t>(dst.width) + static_cast<std::size_t>(x)) * 4 +
                         static_cast<std::size_t>(c)] = static_cast<std::uint8_t>((sum + 2) / 4); // rounded mean
            }
    return dst;
}

} // namespace

bool downscaleToFit(Image& image, int maxEdge, const std::string& what, const std::string& why)
{
    maxEdge = std::max(maxEdge, 1);
    if (image.width <= maxEdge && image.height <= maxEdge) return false;
    const int width = image.width, height = image.height;
    while (image.width > maxEdge || image.height > maxEdge)
        image = halve(image);
    std::fprintf(stderr, "vplgi: warning: %s: %dx%d image downscaled to %dx%d (%s)\n", what.c_str(), width, height,
                 image.width, image.height, why.c_str());
    return true;
}

} // namespace vplgi
