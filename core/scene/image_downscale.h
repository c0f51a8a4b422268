// Large textures are downscaled on load (issue 13 part 6): an image with an edge above a cap is
// halved (2x2 box filter) until it fits, with a one-line warning, rather than failing at upload
// (GL_MAX_TEXTURE_SIZE) or taking gigabytes. The loader uses kMaxImageEdge, the GPU upload the
// GL implementation's limit when that is lower.
#pragma once

#include <string>

#include "core/scene/scene.h"

namespace vplgi {

// The loader's cap on either edge of a decoded image [texels]: the smallest GL_MAX_TEXTURE_SIZE
// of current desktop drivers is 16384; 8192 keeps an RGBA8 texture at 256 MiB at most.
constexpr int kMaxImageEdge = 8192;

// Halves `image` until both edges are at most maxEdge (each halving averages 2x2 texels; an odd
// edge's last texel is averaged with itself). Returns false when it already fits; else prints
// "vplgi: warning: <what>: WxH image downscaled to wxh (<why>)" and returns true.
bool downscaleToFit(Image& image, int maxEdge, const std::string& what, const std::string& why);

} // namespace vplgi
