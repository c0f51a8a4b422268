// The determinism check of the techniques' image tests: the same renderer rendering twice and a
// second renderer of the same settings give the same bits, the image is lit, and its hash is
// recorded for tests/gl/threads_identical.sh (which compares LP_NUM_THREADS=1 and 2).
#pragma once

#include <catch2/catch.hpp>

#include <memory>
#include <string>

#include "buffer_readback.h"
#include "determinism.h"
#include "gl_test_context.h"

namespace vplgi::test {

inline void checkTechniqueBitIdentical(const Scene& scene, const std::string& technique, const Settings& settings,
                                       int width, int height)
{
    INFO(technique);
    const Camera& camera = scene.cameras[0];
    std::unique_ptr<Renderer> first = makeTechniqueRenderer(scene, technique, settings);
    const ImageRGBA32F a = renderIndirect(*first, camera, width, height);
    const ImageRGBA32F b = renderIndirect(*first, camera, width, height); // the same renderer again
    std::unique_ptr<Renderer> second = makeTechniqueRenderer(scene, technique, settings);
    const ImageRGBA32F c = renderIndirect(*second, camera, width, height);
    CHECK(firstBitDifference(a.pixels, b.pixels) == -1);
    CHECK(firstBitDifference(a.pixels, c.pixels) == -1);
    double sum = 0.0;
    for (float v : a.pixels) sum += v;
    CHECK(sum > 0.0); // something was lit
    CHECK(recordHash(technique, hashBytes(a.pixels.data(), a.pixels.size() * sizeof(float))));
}

} // namespace vplgi::test
