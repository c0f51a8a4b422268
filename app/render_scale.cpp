#include "render_scale.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "core/util/error.h"

namespace vplgi {

namespace {

float parseNumber(const std::string& key, const std::string& value, float min, float max)
{
    char* end = nullptr;
    const float v = std::strtof(value.c_str(), &end);
    char range[64];
    std::snprintf(range, sizeof range, "[%g, %g]", static_cast<double>(min), static_cast<double>(max));
    require(!value.empty() && *end == '\0' && std::isfinite(v) && v >= min && v <= max,
            key + ": \"" + value + "\" is not a number in " + range + (key == "viewer.renderScale" ? " or auto" : ""));
    return v;
}

} // namespace

void RenderScale::set(const std::string& key, const std::string& value)
{
    if (key == "viewer.renderScale") {
        mAutomatic = value == "auto";
        // The automatic scale starts at the floor and grows while frames stay under the target: the
        // first frame at full size can take a minute on llvmpipe (vsgl at 1280 x 720: 66 s).
        mScale = mAutomatic ? 0.0f : parseNumber(key, value, 0.05f, 1.0f);
        mSettle = 2;
        mPreviousMs = 0.0;
    } else if (key == "viewer.targetMs") {
        mTargetMs = parseNumber(key, value, 1.0f, 60000.0f);
    } else {
        throw Error("unknown parameter \"" + key + "\" (viewer keys: viewer.renderScale=auto|S, viewer.targetMs=T)");
    }
}

void RenderScale::take(Settings& settings)
{
    Settings rest;
    for (const auto& [key, value] : settings) {
        if (isViewerKey(key))
            set(key, value);
        else
            rest.emplace_back(key, value);
    }
    settings = std::move(rest);
}

float RenderScale::minimumScale(glm::ivec2 window) const
{
    const float sx = window.x > 0 ? static_cast<float>(kMinWidth) / static_cast<float>(window.x) : 1.0f;
    const float sy = window.y > 0 ? static_cast<float>(kMinHeight) / static_cast<float>(window.y) : 1.0f;
    return std::min(1.0f, std::max(sx, sy));
}

glm::ivec2 RenderScale::internalSize(glm::ivec2 window) const
{
    float scale = 1.0f;
    if (!mAutomatic)
        scale = mScale;
    else if (mSoftware)
        scale = std::max(mScale, minimumScale(window));
    // The floor holds for a fixed scale too; a window smaller than 320 x 180 renders at its own size.
    const glm::ivec2 floor(std::min(window.x, kMinWidth), std::min(window.y, kMinHeight));
    return glm::max(floor, glm::ivec2(glm::round(glm::vec2(window) * scale)));
}

bool RenderScale::adapt(double frameMs, glm::ivec2 window)
{
    if (!adapting() || frameMs <= 0.0) return false;
    if (mSettle > 0) {
        --mSettle;
        return false;
    }
    // The faster of the last two frames: one slow frame (a shadow map's rebuild) does not shrink the
    // image, two in a row do.
    const double previous = mPreviousMs;
    mPreviousMs = frameMs;
    if (previous <= 0.0) return false;
    const double measured = std::min(previous, frameMs);
    // The target is a ceiling: shrink above it, grow below kGrowBelow of it, each time aiming at kAim
    // of it with frame time ~ pixels. A frame's fixed costs (not per pixel) make that aim safe both
    // ways: after growing the frame is at most the aim (the fixed part does not grow), after
    // shrinking at least the aim (it does not shrink), so the scale neither overshoots the target
    // nor swings back.
    if (measured <= mTargetMs && measured >= kGrowBelow * mTargetMs) return false;
    const float minimum = minimumScale(window);
    const float current = std::max(mScale, minimum);
    const double ratio = kAim * mTargetMs / measured;
    // Steps of 1/64 down (fewer reallocations of the render targets), at most 2x in area per change.
    float next = current * static_cast<float>(std::sqrt(std::clamp(ratio, 0.5, 2.0)));
    next = std::clamp(std::floor(next * 64.0f) / 64.0f, minimum, 1.0f);
    if (std::abs(next - current) < 1.0f / 128.0f) return false;
    mScale = next;
    mSettle = 2;
    mPreviousMs = 0.0;
    return true;
}

std::string RenderScale::describe(glm::ivec2 window) const
{
    const glm::ivec2 size = internalSize(window);
    char text[160];
    const float shown = static_cast<float>(size.x) / static_cast<float>(std::max(window.x, 1));
    if (!mAutomatic)
        std::snprintf(text, sizeof text, "%d x %d (scale %.2f)", size.x, size.y, static_cast<double>(shown));
    else if (mSoftware)
        std::snprintf(text, sizeof text, "%d x %d (scale %.2f, auto: target %.0f ms)", size.x, size.y,
                      static_cast<double>(shown), static_cast<double>(mTargetMs));
    else
        std::snprintf(text, sizeof text, "%d x %d (auto: 1 on a GPU)", size.x, size.y);
    return text;
}

} // namespace vplgi
