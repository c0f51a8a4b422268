// Helpers of the VPL sampler tests (ir, mir): equal sets and the mean of a gathered image.
#pragma once

#include "core/util/image_io.h"
#include "core/vpl/vpl.h"

namespace vplgi::test {

// Every slot equal bit for bit (valid, position, normal, radiance, density); `changed` not compared.
inline bool identicalSets(const VPLSet& a, const VPLSet& b)
{
    if (a.slots.size() != b.slots.size()) return false;
    for (std::size_t i = 0; i < a.slots.size(); ++i) {
        const VPL &u = a.slots[i], &v = b.slots[i];
        if (u.valid != v.valid || u.position != v.position || u.normal != v.normal || u.radiance != v.radiance ||
            u.density != v.density)
            return false;
    }
    return true;
}

// The mean of an image's green channel (the furnace is grey).
inline double meanGreen(const ImageRGBA32F& image)
{
    double sum = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) sum += image.at(x, y)[1];
    return sum / (static_cast<double>(image.width) * image.height);
}

} // namespace vplgi::test
