// The viewer's internal resolution (issue 28 part 5): the scene renders at the window's size times
// viewer.renderScale and is upscaled (bilinear) to the window. "auto" (the default) follows the frame
// time toward viewer.targetMs on a software rasterizer (llvmpipe: a frame's cost is nearly all per
// pixel) and is 1 on a GPU. Never below 320 x 180 in either direction (or the window, when smaller).
// Viewer keys are the viewer's own: `--set viewer.*` and a script's `set viewer.*` come here, not to
// the renderer (which would reject them as unknown).
#pragma once

#include <glm/glm.hpp>
#include <string>

#include "core/util/params.h"

namespace vplgi {

class RenderScale {
public:
    static constexpr int kMinWidth = 320, kMinHeight = 180;

    // `software`: the automatic scale adapts (else it stays 1).
    explicit RenderScale(bool software = false) : mSoftware(software) {}
    void setSoftware(bool software) { mSoftware = software; }

    // viewer.renderScale = auto | S in [0.05, 1]; viewer.targetMs = T in [1, 60000]. Throws Error
    // (one line) for another viewer.* key or a bad value.
    void set(const std::string& key, const std::string& value);
    static bool isViewerKey(const std::string& key) { return key.rfind("viewer.", 0) == 0; }
    // Moves the viewer.* entries of `settings` into this object (checked), leaving the rest.
    void take(Settings& settings);

    // The size the scene renders at for a window of `window` pixels.
    glm::ivec2 internalSize(glm::ivec2 window) const;
    // After a frame of `frameMs` wall-clock milliseconds at `window`: the automatic scale keeps the
    // frame under the target. Measured: the faster of the last two frames (two frames to settle after
    // a change). Above the target or below kGrowBelow x target it moves to aim at kAim x target (frame
    // time ~ pixels: scale ~ sqrt(kAim target / measured), at most 2x in area, floored to 1/64).
    // Returns true when it changed.
    bool adapt(double frameMs, glm::ivec2 window);
    static constexpr double kAim = 0.85, kGrowBelow = 0.7;

    bool automatic() const { return mAutomatic; }
    bool adapting() const { return mAutomatic && mSoftware; }
    float scale() const { return mScale; }
    float targetMs() const { return mTargetMs; }
    std::string describe(glm::ivec2 window) const; // "640 x 360 (0.50, auto: target 500 ms)"

private:
    float minimumScale(glm::ivec2 window) const;

    bool mSoftware = false;
    bool mAutomatic = true;
    float mScale = 1.0f;     // fixed, or the automatic one's current value
    float mTargetMs = 500.0f;
    int mSettle = 2;         // frames before the next measurement counts (the first ones allocate)
    double mPreviousMs = 0;  // the last counted frame since the last change (0: none yet)
};

} // namespace vplgi
