// Error metrics for comparing renders with references (SMCIR section 5, MATH.md section 8).
//
// Tone-mapped metrics use one fixed exposure for method and reference (not each image's own
// log-average), Reinhard on luminance: T(Y) = eY / (1 + eY), so |E| is deterministic and in [0, 1].
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/util/image_io.h"

namespace vplgi {

// Reinhard-mapped luminance of a linear RGB radiance.
double toneMappedLuminance(const float* rgb, double exposure);

struct ImageErrors {
    double meanAbsToneMapped = 0.0; // mean |T(Y_method) - T(Y_ref)| (SMCIR's |E| on a single frame)
    double p999AbsToneMapped = 0.0; // 99.9th percentile of |T(Y_method) - T(Y_ref)| over pixels (the spikes: VSGL)
    double rmse = 0.0;              // sqrt(mean over pixels and RGB of (a - b)^2), linear radiance
    double relativeMSE = 0.0;       // mean over pixels and RGB of (a - b)^2 / (b^2 + 0.01)
    double meanRelativeLuminance = 0.0; // mean(Y_method) / mean(Y_ref) - 1 (bias of the mean)
};

// Throws Error when the sizes differ.
ImageErrors compareImages(const ImageRGBA32F& method, const ImageRGBA32F& reference, double exposure);

// The display transform of the GPU tone-map pass (glsl/shared/tonemap.h) on the CPU: sRGB bytes.
ImageRGBA8 toneMapImage(const ImageRGBA32F& radiance, double exposure);

// Per-pixel |T(Y_method) - T(Y_ref)| as a heat map (0 black -> 1 white through purple/orange),
// scaled so that `maxError` maps to the top of the colour ramp.
ImageRGBA8 errorHeatMap(const ImageRGBA32F& method, const ImageRGBA32F& reference, double exposure, double maxError);

// Temporal error at tracked pixels (SMCIR eq. 10): for frames t = 0..T-1 and tracked pixels j,
// E_tj = T(Y_method,tj) - T(Y_ref,tj), E'_tj = E_tj - E_(t-1)j (finite difference per frame).
struct TemporalErrors {
    double meanAbsError = 0.0;      // average |E| over all frames and tracked pixels
    double meanAbsDerivative = 0.0; // average |E'| over frames 1..T-1 and tracked pixels
    std::vector<double> pixelAbsDerivative; // per tracked pixel: average |E'| over frames 1..T-1
};
// `method[t][j]` and `reference[t][j]`: linear luminance at tracked pixel j in frame t.
TemporalErrors temporalErrors(const std::vector<std::vector<double>>& method,
                              const std::vector<std::vector<double>>& reference, double exposure);

// A ratio of two methods' average |E'| at the same tracked pixels, a / b, with a 95% interval: a
// claim such as "|E'| <= 0.5x the other's" rests on a handful of pixels (SMCIR tracks 8), and the
// interval says whether they can decide it. Paired percentile bootstrap over the tracked pixels
// (each resample draws pixels with replacement and takes both methods' values at them; frames
// stay together, as a pixel's frames are not independent). Deterministic for a seed. Not in
// SMCIR, which reports the averages alone.
struct RatioInterval {
    double ratio = 0.0; // mean a / mean b over the tracked pixels (0 when b's mean is 0)
    double low = 0.0;   // 2.5th percentile of the resampled ratios
    double high = 0.0;  // 97.5th percentile
};
RatioInterval temporalDerivativeRatio(const TemporalErrors& a, const TemporalErrors& b, int resamples = 10000,
                                      std::uint64_t seed = 1);

// Evenly spread tracked pixels (deterministic): a jittered grid of `count` pixels away from borders.
std::vector<glm::ivec2> trackedPixels(int width, int height, int count);

// Tracked pixels in indirectly lit regions (SMCIR 5.2 tracks pixels whose indirect light it
// measures), chosen from cheap estimates of the first frame's direct and indirect radiance (the
// path tracer's Direct and Indirect modes at a few samples per pixel, fixed seed):
//  1. D, N: the luminance of `direct` and `indirect`, each averaged over the pixel's 3x3
//     neighbourhood (a few-sample estimate is noisy; the box also keeps away from the image border).
//  2. A pixel is indirectly lit when N >= D (indirect light is at least half of its total) and
//     N >= kTrackedMinIndirectFraction x the 90th percentile of N over the pixels with N > 0 (not
//     tiny in absolute terms: dark corners would make |E| meaninglessly small).
//  3. Candidates: pixels whose whole 3x3 neighbourhood is indirectly lit (away from the region's
//     edges, where a pixel centre and a jittered reference see different surfaces). With fewer than
//     `count` of them, the indirectly lit pixels themselves.
//  4. Farthest-point selection: the candidate nearest the image centre first, then repeatedly the
//     candidate farthest from every chosen one (ties: the first in row-major order).
// Deterministic for given images. Returns fewer than `count` pixels (possibly none) only when
// fewer than `count` pixels are indirectly lit; the caller then falls back to trackedPixels().
// Throws Error when the images differ in size.
constexpr double kTrackedMinIndirectFraction = 0.1;
std::vector<glm::ivec2> indirectTrackedPixels(const ImageRGBA32F& direct, const ImageRGBA32F& indirect, int count);

// The mean of `values` with the half-width of its 95% Student-t interval (0 for one value): how
// `conform` and `smcir-selection` report a quantity measured over seeds.
struct MeanInterval {
    double mean = 0.0;
    double halfWidth = 0.0;
    int count = 0;
};
MeanInterval meanInterval(const std::vector<double>& values);
// "+1.2% [+0.3, +2.1]" (a fraction as percent, with its interval) or "+1.2%" for one value.
std::string percentText(const MeanInterval& i);

// The drift of a per-frame series of N values (N >= 10): the mean of frames [0.9 N, N) over that of
// [0.4 N, 0.5 N), minus 1 (0 when the early mean is not positive). `conform --frames` and
// `smcir-selection` report it.
double driftOf(const std::vector<double>& perFrame);

} // namespace vplgi
