// The viewer's automatic render scale (app/render_scale.h) against modelled frame times: a frame of
// fixed + perPixel * pixels milliseconds. Closed-form checks of the controller, no GL and no clock.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "app/render_scale.h"

using namespace vplgi;

namespace {

struct Model {
    double fixedMs;    // per frame, whatever the size
    double perPixelMs; // per internal pixel
    double frame(glm::ivec2 size) const { return fixedMs + perPixelMs * double(size.x) * double(size.y); }
};

// Runs `frames` frames at `window` (the slow frames' indices get `spikeMs` more) and returns each
// frame's time; `sizes` gets each frame's internal size.
std::vector<double> run(RenderScale& scale, const Model& model, glm::ivec2 window, int frames,
                        std::vector<glm::ivec2>& sizes, const std::vector<int>& slowFrames = {}, double spikeMs = 0.0)
{
    std::vector<double> times;
    for (int i = 0; i < frames; ++i) {
        const glm::ivec2 size = scale.internalSize(window);
        double ms = model.frame(size);
        for (int slow : slowFrames)
            if (slow == i) ms += spikeMs;
        times.push_back(ms);
        sizes.push_back(size);
        scale.adapt(ms, window);
    }
    return times;
}

} // namespace

TEST_CASE("viewer render scale: the automatic scale settles under the target without swinging back", "[viewer]")
{
    const glm::ivec2 window(1280, 720);
    const double pixels = 1280.0 * 720.0;
    // Frame time at full size 2x (with a small and a large fixed part: the fixed part is what makes
    // frame time not proportional to pixels), 0.9x and 4x the target.
    for (const Model model : {Model{20.0, 980.0 / pixels}, Model{250.0, 750.0 / pixels}, Model{40.0, 410.0 / pixels},
                              Model{60.0, 1940.0 / pixels}}) {
        RenderScale scale(true);
        scale.set("viewer.renderScale", "auto");
        std::vector<glm::ivec2> sizes;
        const std::vector<double> times = run(scale, model, window, 60, sizes);
        INFO("fixed " << model.fixedMs << " ms, full size " << model.frame(window) << " ms");
        // Settled: the last 20 frames at one size, under the target and not needlessly small (a size
        // that leaves the frame under 0.7 x target grows, unless it is the window's).
        for (int i = 40; i < 60; ++i) {
            CHECK(sizes[i] == sizes[59]);
            CHECK(times[i] <= scale.targetMs());
        }
        CHECK((times[59] >= RenderScale::kGrowBelow * scale.targetMs() || sizes[59] == window ||
               sizes[59] == glm::ivec2(RenderScale::kMinWidth, RenderScale::kMinHeight)));
        // Never above the target after the first change: growing aims at 0.85 x target, and the fixed
        // part makes the real frame no slower than that.
        int firstChange = 1;
        while (firstChange < 60 && sizes[firstChange] == sizes[0]) ++firstChange;
        for (int i = firstChange; i < 60; ++i) CHECK(times[i] <= scale.targetMs());
    }
}

TEST_CASE("viewer render scale: one slow frame does not shrink the image, two in a row do", "[viewer]")
{
    const glm::ivec2 window(1280, 720);
    const Model model{20.0, 300.0 / (1280.0 * 720.0)}; // 320 ms at full size: settles at the window
    RenderScale scale(true);
    scale.set("viewer.renderScale", "auto");
    std::vector<glm::ivec2> sizes;
    run(scale, model, window, 40, sizes, {30}, 400.0);
    REQUIRE(sizes[29] == window);
    for (int i = 30; i < 40; ++i) CHECK(sizes[i] == window);

    RenderScale twice(true);
    twice.set("viewer.renderScale", "auto");
    std::vector<glm::ivec2> sizesTwice;
    run(twice, model, window, 40, sizesTwice, {30, 31}, 400.0);
    REQUIRE(sizesTwice[29] == window);
    CHECK(sizesTwice[32].x < window.x);
}

TEST_CASE("viewer render scale: fixed scales, the floor, and a GPU's scale of 1", "[viewer]")
{
    const glm::ivec2 window(1280, 720);
    RenderScale gpu(false);
    gpu.set("viewer.renderScale", "auto");
    CHECK(gpu.internalSize(window) == window);
    CHECK_FALSE(gpu.adapt(5000.0, window));
    RenderScale fixed(true);
    fixed.set("viewer.renderScale", "0.5");
    CHECK(fixed.internalSize(window) == glm::ivec2(640, 360));
    CHECK_FALSE(fixed.adapt(5000.0, window));
    fixed.set("viewer.renderScale", "0.05");
    CHECK(fixed.internalSize(window) == glm::ivec2(320, 180));
    CHECK_THROWS(fixed.set("viewer.renderScale", "2"));
    CHECK_THROWS(fixed.set("viewer.other", "1"));
}
