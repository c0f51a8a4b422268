// Error metrics against hand-computed values.
#include <catch2/catch.hpp>

#include "core/util/error.h"
#include "core/util/metrics.h"

using namespace vplgi;

namespace {

ImageRGBA32F constantImage(int w, int h, float value)
{
    ImageRGBA32F image;
    image.width = w;
    image.height = h;
    image.pixels.assign(static_cast<std::size_t>(w) * h * 4, value);
    return image;
}

} // namespace

TEST_CASE("image metrics of constant images have closed forms", "[metrics]")
{
    ImageRGBA32F a = constantImage(4, 3, 1.0f), b = constantImage(4, 3, 3.0f);
    ImageErrors e = compareImages(a, b, 1.0);
    // T(1) = 1/2, T(3) = 3/4 (grey: luminance equals the channel value).
    CHECK(e.meanAbsToneMapped == Approx(0.25));
    CHECK(e.p999AbsToneMapped == Approx(0.25));
    CHECK(e.rmse == Approx(2.0));
    CHECK(e.relativeMSE == Approx(4.0 / 9.01));
    CHECK(e.meanRelativeLuminance == Approx(1.0 / 3.0 - 1.0));
    CHECK(compareImages(b, b, 1.0).rmse == 0.0);
    CHECK_THROWS_AS(compareImages(a, constantImage(3, 4, 1.0f), 1.0), Error);
}

TEST_CASE("the 99.9th percentile error picks out spikes by nearest rank", "[metrics]")
{
    // 2000 pixels: the nearest rank is ceil(0.999 * 2000) = 1998, the third largest error.
    ImageRGBA32F method = constantImage(50, 40, 1.0f), reference = constantImage(50, 40, 1.0f);
    auto spike = [&](int pixel) {
        for (int c = 0; c < 3; ++c) method.pixels[static_cast<std::size_t>(pixel) * 4 + c] = 3.0f;
    };
    spike(7);
    spike(1500);
    CHECK(compareImages(method, reference, 1.0).p999AbsToneMapped == 0.0); // two spikes lie above the rank
    spike(42);
    CHECK(compareImages(method, reference, 1.0).p999AbsToneMapped == Approx(0.25)); // T(3) - T(1)
}

TEST_CASE("the heat map ramps from black to white", "[metrics]")
{
    ImageRGBA32F a = constantImage(2, 1, 0.0f), b = constantImage(2, 1, 0.0f);
    b.pixels[4] = b.pixels[5] = b.pixels[6] = 1.0f; // pixel 1: T = 0.5
    ImageRGBA8 heat = errorHeatMap(a, b, 1.0, 0.5);
    CHECK(heat.pixels[0] == 0);
    CHECK(heat.pixels[4] == 255);
    CHECK(heat.pixels[5] == 255);
    CHECK(heat.pixels[6] == 255);
}

TEST_CASE("temporal errors follow SMCIR eq. 10", "[metrics]")
{
    // One tracked pixel, reference constant 1 (T = 0.5); method alternates 1 and 3 (T = 0.5, 0.75).
    std::vector<std::vector<double>> reference = {{1.0}, {1.0}, {1.0}, {1.0}};
    std::vector<std::vector<double>> flicker = {{1.0}, {3.0}, {1.0}, {3.0}};
    std::vector<std::vector<double>> steady = {{3.0}, {3.0}, {3.0}, {3.0}};
    TemporalErrors f = temporalErrors(flicker, reference, 1.0);
    TemporalErrors s = temporalErrors(steady, reference, 1.0);
    CHECK(f.meanAbsError == Approx(0.125));
    CHECK(f.meanAbsDerivative == Approx(0.25));
    CHECK(s.meanAbsError == Approx(0.25)); // more error ...
    CHECK(s.meanAbsDerivative == 0.0);     // ... but no flicker
}

TEST_CASE("tracked pixels are distinct and inside the image", "[metrics]")
{
    auto pixels = trackedPixels(64, 48, 8);
    REQUIRE(pixels.size() == 8);
    for (std::size_t i = 0; i < pixels.size(); ++i) {
        CHECK(pixels[i].x >= 0);
        CHECK(pixels[i].x < 64);
        CHECK(pixels[i].y >= 0);
        CHECK(pixels[i].y < 48);
        for (std::size_t j = 0; j < i; ++j) CHECK(pixels[i] != pixels[j]);
    }
}
