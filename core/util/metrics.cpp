#include "core/util/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "glsl/shared/tonemap.h"
#include "core/util/error.h"
#include "core/util/random.h"

namespace vplgi {

double toneMappedLuminance(const float* rgb, double exposure)
{
    double y = exposure * (0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]);
    y = std::max(0.0, y);
    return y / (1.0 + y);
}

namespace {

void requireSameSize(const ImageRGBA32F& a, const ImageRGBA32F& b)
{
    require(a.width == b.width && a.height == b.height,
            "images differ in size: " + std::to_string(a.width) + "x" + std::to_string(a.height) + " vs " +
                std::to_string(b.width) + "x" + std::to_string(b.height));
}

double mapped(double y, double exposure)
{
    y = std::max(0.0, y * exposure);
    return y / (1.0 + y);
}

} // namespace

ImageErrors compareImages(const ImageRGBA32F& method, const ImageRGBA32F& reference, double exposure)
{
    requireSameSize(method, reference);
    ImageErrors e;
    const std::size_t pixels = static_cast<std::size_t>(method.width) * method.height;
    double sumAbs = 0.0, sumSq = 0.0, sumRel = 0.0, sumYm = 0.0, sumYr = 0.0;
    std::vector<double> absErrors(pixels);
    for (std::size_t p = 0; p < pixels; ++p) {
        const float* a = &method.pixels[p * 4];
        const float* b = &reference.pixels[p * 4];
        absErrors[p] = std::abs(toneMappedLuminance(a, exposure) - toneMappedLuminance(b, exposure));
        sumAbs += absErrors[p];
        for (int c = 0; c < 3; ++c) {
            double d = double(a[c]) - double(b[c]);
            sumSq += d * d;
            sumRel += d * d / (double(b[c]) * b[c] + 0.01);
        }
        sumYm += 0.2126 * a[0] + 0.7152 * a[1] + 0.0722 * a[2];
        sumYr += 0.2126 * b[0] + 0.7152 * b[1] + 0.0722 * b[2];
    }
    e.meanAbsToneMapped = sumAbs / pixels;
    // Nearest rank: the smallest error that at least 99.9% of the pixels do not exceed.
    if (pixels > 0) {
        const std::size_t rank = static_cast<std::size_t>(std::ceil(0.999 * static_cast<double>(pixels))) - 1;
        std::nth_element(absErrors.begin(), absErrors.begin() + static_cast<std::ptrdiff_t>(rank), absErrors.end());
        e.p999AbsToneMapped = absErrors[rank];
    }
    e.rmse = std::sqrt(sumSq / (3.0 * pixels));
    e.relativeMSE = sumRel / (3.0 * pixels);
    e.meanRelativeLuminance = sumYr > 0.0 ? sumYm / sumYr - 1.0 : 0.0;
    return e;
}

ImageRGBA8 toneMapImage(const ImageRGBA32F& radiance, double exposure)
{
    ImageRGBA8 out;
    out.width = radiance.width;
    out.height = radiance.height;
    out.pixels.resize(static_cast<std::size_t>(out.width) * out.height * 4);
    for (std::size_t p = 0; p < static_cast<std::size_t>(out.width) * out.height; ++p) {
        const float* c = &radiance.pixels[p * 4];
        glm::vec3 mapped = shared::toneMapReinhard(glm::vec3(c[0], c[1], c[2]), static_cast<float>(exposure));
        for (int k = 0; k < 3; ++k)
            out.pixels[p * 4 + k] = static_cast<std::uint8_t>(std::lround(255.0f * shared::encodeSRGB(mapped[k])));
        out.pixels[p * 4 + 3] = 255;
    }
    return out;
}

ImageRGBA8 errorHeatMap(const ImageRGBA32F& method, const ImageRGBA32F& reference, double exposure, double maxError)
{
    requireSameSize(method, reference);
    // A perceptually ordered ramp: black, purple, orange, yellow, white.
    static const glm::vec3 kRamp[5] = {{0, 0, 0}, {0.35f, 0.05f, 0.5f}, {0.9f, 0.3f, 0.1f}, {1.0f, 0.85f, 0.2f}, {1, 1, 1}};
    ImageRGBA8 out;
    out.width = method.width;
    out.height = method.height;
    out.pixels.resize(static_cast<std::size_t>(out.width) * out.height * 4);
    for (std::size_t p = 0; p < static_cast<std::size_t>(out.width) * out.height; ++p) {
        double e = std::abs(toneMappedLuminance(&method.pixels[p * 4], exposure) -
                            toneMappedLuminance(&reference.pixels[p * 4], exposure));
        double t = std::clamp(e / std::max(maxError, 1e-12), 0.0, 1.0) * 4.0;
        int i = std::min(3, static_cast<int>(t));
        glm::vec3 c = glm::mix(kRamp[i], kRamp[i + 1], static_cast<float>(t - i));
        for (int k = 0; k < 3; ++k) out.pixels[p * 4 + k] = static_cast<std::uint8_t>(std::lround(255.0 * c[k]));
        out.pixels[p * 4 + 3] = 255;
    }
    return out;
}

TemporalErrors temporalErrors(const std::vector<std::vector<double>>& method,
                              const std::vector<std::vector<double>>& reference, double exposure)
{
    require(method.size() == reference.size() && !method.empty(), "temporal errors need the same non-zero frame count");
    TemporalErrors t;
    std::size_t countE = 0, countD = 0;
    std::vector<double> previous;
    t.pixelAbsDerivative.assign(method[0].size(), 0.0);
    for (std::size_t f = 0; f < method.size(); ++f) {
        require(method[f].size() == reference[f].size(), "temporal errors: tracked pixel counts differ");
        std::vector<double> current(method[f].size());
        for (std::size_t j = 0; j < current.size(); ++j) {
            current[j] = mapped(method[f][j], exposure) - mapped(reference[f][j], exposure);
            t.meanAbsError += std::abs(current[j]);
            ++countE;
            if (f > 0) {
                t.meanAbsDerivative += std::abs(current[j] - previous[j]);
                t.pixelAbsDerivative[j] += std::abs(current[j] - previous[j]) / static_cast<double>(method.size() - 1);
                ++countD;
            }
        }
        previous = std::move(current);
    }
    if (countE) t.meanAbsError /= static_cast<double>(countE);
    if (countD) t.meanAbsDerivative /= static_cast<double>(countD);
    return t;
}

RatioInterval temporalDerivativeRatio(const TemporalErrors& a, const TemporalErrors& b, int resamples,
                                      std::uint64_t seed)
{
    const std::vector<double>& x = a.pixelAbsDerivative;
    const std::vector<double>& y = b.pixelAbsDerivative;
    require(x.size() == y.size(), "|E'| ratio: tracked pixel counts differ");
    require(resamples > 0, "|E'| ratio: resamples must be positive");
    const auto ratioOf = [](double sumX, double sumY) { return sumY > 0.0 ? sumX / sumY : 0.0; };
    RatioInterval r;
    if (x.empty()) return r;
    double sumX = 0.0, sumY = 0.0;
    for (std::size_t j = 0; j < x.size(); ++j) {
        sumX += x[j];
        sumY += y[j];
    }
    r.ratio = ratioOf(sumX, sumY);
    Pcg32 rng(mix64(seed), 0x5eedu);
    std::vector<double> ratios(static_cast<std::size_t>(resamples));
    const auto n = static_cast<std::uint32_t>(x.size());
    for (double& ratio : ratios) {
        double rx = 0.0, ry = 0.0;
        for (std::uint32_t k = 0; k < n; ++k) {
            const std::uint32_t j = rng.below(n);
            rx += x[j];
            ry += y[j];
        }
        ratio = ratioOf(rx, ry);
    }
    std::sort(ratios.begin(), ratios.end());
    const auto at = [&](double q) {
        return ratios[static_cast<std::size_t>(std::lround(q * static_cast<double>(ratios.size() - 1)))];
    };
    r.low = at(0.025);
    r.high = at(0.975);
    return r;
}

std::vector<glm::ivec2> trackedPixels(int width, int height, int count)
{
    std::vector<glm::ivec2> pixels;
    const int columns = std::max(1, static_cast<int>(std::ceil(std::sqrt(count * double(width) / height))));
    const int rows = std::max(1, (count + columns - 1) / columns);
    for (int i = 0; i < count; ++i) {
        int cx = i % columns, cy = i / columns;
        // Cell centres, shifted by a fixed irrational offset so the grid does not align with geometry.
        double fx = (cx + 0.5 + 0.25 * std::sin(1.7 * i)) / columns;
        double fy = (cy + 0.5 + 0.25 * std::cos(2.3 * i)) / rows;
        pixels.push_back({std::clamp(static_cast<int>(fx * width), 0, width - 1),
                          std::clamp(static_cast<int>(fy * height), 0, height - 1)});
    }
    return pixels;
}

namespace {

// Luminance averaged over the 3x3 neighbourhood; 0 on the one-pixel border (no full neighbourhood).
std::vector<double> boxedLuminance(const ImageRGBA32F& image)
{
    const int w = image.width, h = image.height;
    std::vector<double> y(static_cast<std::size_t>(w) * h, 0.0), boxed(y.size(), 0.0);
    for (std::size_t p = 0; p < y.size(); ++p) {
        const float* c = &image.pixels[p * 4];
        y[p] = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    }
    for (int py = 1; py + 1 < h; ++py)
        for (int px = 1; px + 1 < w; ++px) {
            double sum = 0.0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) sum += y[static_cast<std::size_t>(py + dy) * w + px + dx];
            boxed[static_cast<std::size_t>(py) * w + px] = sum / 9.0;
        }
    return boxed;
}

} // namespace

std::vector<glm::ivec2> indirectTrackedPixels(const ImageRGBA32F& direct, const ImageRGBA32F& indirect, int count)
{
    requireSameSize(direct, indirect);
    const int w = direct.width, h = direct.height;
    const std::vector<double> d = boxedLuminance(direct), n = boxedLuminance(indirect);

    // Step 2: the absolute floor from the 90th percentile of the positive indirect luminances.
    std::vector<double> positive;
    for (double v : n)
        if (v > 0.0) positive.push_back(v);
    if (positive.empty()) return {};
    const std::size_t rank = static_cast<std::size_t>(0.9 * static_cast<double>(positive.size() - 1));
    std::nth_element(positive.begin(), positive.begin() + static_cast<std::ptrdiff_t>(rank), positive.end());
    const double floor = kTrackedMinIndirectFraction * positive[rank];
    std::vector<char> lit(n.size(), 0);
    for (std::size_t p = 0; p < n.size(); ++p) lit[p] = n[p] > 0.0 && n[p] >= d[p] && n[p] >= floor;

    // Step 3: erode by the 3x3 neighbourhood (border pixels are never lit: their boxes are 0).
    std::vector<glm::ivec2> candidates, litPixels;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            if (!lit[static_cast<std::size_t>(y) * w + x]) continue;
            litPixels.push_back({x, y});
            bool inside = true;
            for (int dy = -1; dy <= 1 && inside; ++dy)
                for (int dx = -1; dx <= 1 && inside; ++dx) {
                    const int qx = x + dx, qy = y + dy;
                    inside = qx >= 0 && qy >= 0 && qx < w && qy < h && lit[static_cast<std::size_t>(qy) * w + qx];
                }
            if (inside) candidates.push_back({x, y});
        }
    if (static_cast<int>(candidates.size()) < count) candidates = litPixels;
    if (static_cast<int>(candidates.size()) < count) return {};

    // Step 4: farthest-point selection from the candidate nearest the centre (strict comparisons
    // keep the first in row-major order on ties).
    auto distance2 = [](glm::ivec2 a, glm::dvec2 b) {
        const double dx = a.x - b.x, dy = a.y - b.y;
        return dx * dx + dy * dy;
    };
    const glm::dvec2 centre(0.5 * (w - 1), 0.5 * (h - 1));
    std::size_t first = 0;
    for (std::size_t i = 1; i < candidates.size(); ++i)
        if (distance2(candidates[i], centre) < distance2(candidates[first], centre)) first = i;
    std::vector<glm::ivec2> chosen{candidates[first]};
    std::vector<double> nearest(candidates.size());
    for (std::size_t i = 0; i < candidates.size(); ++i) nearest[i] = distance2(candidates[i], glm::dvec2(chosen[0]));
    while (static_cast<int>(chosen.size()) < count) {
        std::size_t best = 0;
        for (std::size_t i = 1; i < candidates.size(); ++i)
            if (nearest[i] > nearest[best]) best = i;
        chosen.push_back(candidates[best]);
        for (std::size_t i = 0; i < candidates.size(); ++i)
            nearest[i] = std::min(nearest[i], distance2(candidates[i], glm::dvec2(candidates[best])));
    }
    return chosen;
}

MeanInterval meanInterval(const std::vector<double>& values)
{
    // t_{0.975, df} for df = 1..30; 1.96 beyond.
    static const double kT[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                                2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
    MeanInterval r;
    r.count = static_cast<int>(values.size());
    if (values.empty()) return r;
    for (double v : values)
        r.mean += v / r.count;
    if (r.count < 2) return r;
    double variance = 0.0;
    for (double v : values)
        variance += (v - r.mean) * (v - r.mean) / (r.count - 1);
    const int df = r.count - 1;
    r.halfWidth = (df <= 30 ? kT[df - 1] : 1.96) * std::sqrt(variance / r.count);
    return r;
}

std::string percentText(const MeanInterval& i)
{
    char text[96];
    if (i.count < 2)
        std::snprintf(text, sizeof text, "%+.1f%%", 100.0 * i.mean);
    else
        std::snprintf(text, sizeof text, "%+.1f%% [%+.1f, %+.1f]", 100.0 * i.mean, 100.0 * (i.mean - i.halfWidth),
                      100.0 * (i.mean + i.halfWidth));
    return text;
}

double driftOf(const std::vector<double>& perFrame)
{
    const int n = static_cast<int>(perFrame.size());
    require(n >= 10, "driftOf needs at least 10 frames");
    auto windowMean = [&](double from, double to) {
        const int a = static_cast<int>(from * n), b = static_cast<int>(to * n);
        double sum = 0.0;
        for (int f = a; f < b; ++f)
            sum += perFrame[static_cast<std::size_t>(f)] / (b - a);
        return sum;
    };
    const double early = windowMean(0.4, 0.5);
    return early > 0.0 ? windowMean(0.9, 1.0) / early - 1.0 : 0.0;
}

} // namespace vplgi
