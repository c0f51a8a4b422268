// The GPU importance sampler (gl/passes/importance_sampler.h) against its CPU twin
// (core/util/importance_table.h): tables bit for bit, the same texels, probabilities I / total, and a
// chi-square test of the GPU's draw frequencies against the map.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <vector>

#include "buffer_readback.h"
#include "core/util/importance_table.h"
#include "core/util/random.h"
#include "gl/api/debug.h"
#include "gl/passes/importance_sampler.h"
#include "gl_test_context.h"
#include "prefix_sum_twin.h"

using namespace vplgi;
using test::firstBitDifference;
using test::readBuffer;

namespace {

constexpr int kWidth = 64;
constexpr int kHeight = 32;

// A synthetic importance map with a range of 1:16 between non-zero texels and zeros where the
// search is easiest to get wrong: the first and last columns, a whole inner column and row, and a
// checkerboard of 8 x 8 blocks (a third of them).
std::vector<float> syntheticImportance()
{
    std::vector<float> map(kWidth * kHeight);
    for (int v = 0; v < kHeight; ++v)
        for (int u = 0; u < kWidth; ++u) {
            const bool zero = u == 0 || u == kWidth - 1 || u == 21 || v == 7 || (u / 8 + v / 8) % 3 == 0;
            const float s = std::sin(0.3f * static_cast<float>(u));
            map[static_cast<std::size_t>(v * kWidth + u)] =
                zero ? 0.0f : (0.5f + 1.5f * s * s) * (1.0f + 3.0f * static_cast<float>(v) / kHeight);
        }
    return map;
}

gl::Texture uploadImportance(const std::vector<float>& map, int width, int height)
{
    return test::uploadR32F("importance map", map, width, height);
}

// Distance in units in the last place between two positive floats.
std::int64_t ulpDistance(float a, float b)
{
    std::int32_t ia = 0, ib = 0;
    std::memcpy(&ia, &a, sizeof a);
    std::memcpy(&ib, &b, sizeof b);
    return std::abs(static_cast<std::int64_t>(ia) - static_cast<std::int64_t>(ib));
}

// Pearson's chi-square of `counts` against `draws` * map / total over the texels with non-zero
// expectation; `cells` receives their number.
double chiSquare(const std::vector<int>& counts, const std::vector<float>& map, int draws, int& cells)
{
    double total = 0.0;
    for (float m : map)
        total += m;
    double chi2 = 0.0;
    cells = 0;
    for (std::size_t i = 0; i < map.size(); ++i) {
        if (map[i] <= 0.0f) continue;
        const double expected = draws * map[i] / total;
        chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
        ++cells;
    }
    return chi2;
}

} // namespace

TEST_CASE("the importance tables built on the GPU equal the CPU twin's bit for bit", "[gl][importance][determinism]")
{
    test::ensureGLContext();
    // The synthetic map and a larger random one whose column sums run over 512 rows.
    Pcg32 rng(3, 7);
    std::vector<float> large(300 * 512);
    for (float& v : large)
        v = rng.uniform() < 0.2f ? 0.0f : rng.uniform() * std::ldexp(1.0f, static_cast<int>(rng.below(16)) - 8);
    struct Map {
        std::vector<float> values;
        int width, height;
    };
    const Map maps[] = {{syntheticImportance(), kWidth, kHeight}, {large, 300, 512}};
    ImportanceSampler sampler(test::shaders());
    for (const Map& m : maps) {
        INFO(m.width << " x " << m.height);
        const ImportanceTable cpu = buildImportanceTable(m.values, m.width, m.height);
        gl::Texture texture = uploadImportance(m.values, m.width, m.height);
        for (int run = 0; run < 2; ++run) { // and again: the same bits
            sampler.build(texture, NextRead::BufferReadback);
            CHECK(firstBitDifference(readBuffer<float>(sampler.columns(), cpu.columns.size()), cpu.columns) == -1);
            CHECK(firstBitDifference(readBuffer<float>(sampler.marginal(), cpu.marginal.size()), cpu.marginal) == -1);
        }
        gl::checkDebugMessages();
    }
}

TEST_CASE("the GPU draws the CPU twin's texels with probability importance / total",
          "[gl][importance][determinism][numbers]")
{
    test::ensureGLContext();
    const std::vector<float> map = syntheticImportance();
    const ImportanceTable cpu = buildImportanceTable(map, kWidth, kHeight);
    gl::Texture texture = uploadImportance(map, kWidth, kHeight);
    ImportanceSampler sampler(test::shaders());
    sampler.build(texture, NextRead::StorageBuffer);
    const int draws = 1 << 18;
    const std::uint32_t seed = 1234;
    sampler.sample(texture, draws, seed, NextRead::BufferReadback);
    const std::vector<shared::ImportanceSample> gpu =
        readBuffer<shared::ImportanceSample>(sampler.samples(), static_cast<std::size_t>(draws));
    gl::checkDebugMessages();
    const std::vector<shared::ImportanceSample> twin = sampleImportanceTable(cpu, draws, seed);

    int differentTexels = 0, outside = 0, zeroDrawn = 0, wrongImportance = 0;
    std::int64_t maxUlps = 0;
    std::vector<int> counts(map.size(), 0);
    for (int i = 0; i < draws; ++i) {
        const shared::ImportanceSample& s = gpu[static_cast<std::size_t>(i)];
        differentTexels += s.x != twin[static_cast<std::size_t>(i)].x || s.y != twin[static_cast<std::size_t>(i)].y;
        if (s.x < 0 || s.x >= kWidth || s.y < 0 || s.y >= kHeight) {
            ++outside;
            continue;
        }
        const float value = map[static_cast<std::size_t>(s.y * kWidth + s.x)];
        zeroDrawn += value == 0.0f;
        wrongImportance += s.importance != value;
        maxUlps = std::max(maxUlps, ulpDistance(s.probability, value / cpu.total()));
        ++counts[static_cast<std::size_t>(s.y * kWidth + s.x)];
    }
    CHECK(differentTexels == 0);
    CHECK(outside == 0);
    CHECK(zeroDrawn == 0);
    CHECK(wrongImportance == 0);
    // GLSL 4.50 (section 4.7.1) allows 2.5 ulp for a division; the same float division on the CPU.
    CHECK(maxUlps <= 3);

    int cells = 0;
    const double chi2 = chiSquare(counts, map, draws, cells);
    const double dof = cells - 1;
    // Fixed seed, so the statistic is one deterministic number; the bound is the chi-square's upper
    // 1e-6 tail (normal approximation for this many degrees of freedom: mean dof, sd sqrt(2 dof)).
    const double bound = dof + 4.75 * std::sqrt(2.0 * dof);
    // The same counts against the map shifted by one column (an off-by-one in the search) must fail.
    std::vector<float> shifted(map.size(), 0.0f);
    for (int v = 0; v < kHeight; ++v)
        for (int u = 1; u < kWidth; ++u)
            shifted[static_cast<std::size_t>(v * kWidth + u)] = map[static_cast<std::size_t>(v * kWidth + u - 1)];
    int shiftedCells = 0;
    std::vector<int> shiftedCounts(counts);
    const double chi2Shifted = chiSquare(shiftedCounts, shifted, draws, shiftedCells);
    std::cout << "importance sampler, 64x32 map, 2^18 GPU draws: chi-square " << chi2 << " for " << dof
              << " degrees of freedom (bound " << bound << "); against the map shifted one column: " << chi2Shifted
              << "; probability vs importance/total: max " << maxUlps << " ulp\n";
    CHECK(chi2 < bound);
    CHECK(chi2Shifted > 10 * bound);
}

TEST_CASE("the importance sampler rejects a map that is not R32F", "[gl][importance]")
{
    test::ensureGLContext();
    gl::TextureDesc desc;
    desc.format = GL_RGBA32F;
    desc.width = 4;
    desc.height = 4;
    gl::Texture texture("not an importance map", desc);
    ImportanceSampler sampler(test::shaders());
    CHECK_THROWS_WITH(sampler.build(texture, NextRead::None), Catch::Contains("GL_R32F"));
}

TEST_CASE("why the marginal is a serial sum: a log-step scan moves past zero terms", "[gl][importance][numbers]")
{
    // The design evidence for gl/passes/importance_sampler.h (1): over column totals with zeros, the
    // serial recurrence keeps R(u) == R(u-1) bit for bit where T(u) = 0, so the search can never stop
    // on a zero column; the block scan of PrefixSumPass (its twin, bit-identical to the GPU) does not.
    Pcg32 rng(9, 3);
    std::vector<float> totals(2048);
    for (float& t : totals)
        t = rng.uniform() < 0.3f ? 0.0f : (0.5f + rng.uniform()) * std::ldexp(1.0f, static_cast<int>(rng.below(9)) - 4);
    std::vector<float> logStep = totals;
    test::prefixSumTwin(logStep, 256);
    std::vector<float> serial = totals;
    for (std::size_t u = 1; u < serial.size(); ++u)
        serial[u] += serial[u - 1];
    int logStepMoves = 0, serialMoves = 0, zeros = 0;
    for (std::size_t u = 1; u < totals.size(); ++u) {
        if (totals[u] != 0.0f) continue;
        ++zeros;
        logStepMoves += logStep[u] != logStep[u - 1];
        serialMoves += serial[u] != serial[u - 1];
    }
    std::cout << "prefix sums over 2048 column totals with " << zeros << " zeros: the log-step scan changes at "
              << logStepMoves << " of them, the serial sum at " << serialMoves << "\n";
    CHECK(serialMoves == 0);
    CHECK(logStepMoves > 0);
}

TEST_CASE("the importance map's box mips equal the CPU twin's bit for bit, six layers side by side",
          "[gl][importance][determinism]")
{
    // VSGL's cell footprints read a cell's probability as 4^l times its level-l texel
    // (passes/vsgl_generate.comp), so the mips must be exact box means: the pass sums each 2x2 in a
    // fixed order, which a float loop on the CPU repeats bit for bit. The width 6 x 16 (a point
    // light's cube faces) is not a power of two, where glGenerateTextureMipmap may filter otherwise.
    test::ensureGLContext();
    const int size = 16, layers = 6, width = size * layers, levels = 5;
    Pcg32 rng(5, 11);
    std::vector<float> level(static_cast<std::size_t>(width * size));
    for (float& v : level)
        v = rng.uniform() < 0.3f ? 0.0f : rng.uniform() * std::ldexp(1.0f, static_cast<int>(rng.below(20)) - 10);
    gl::Texture texture = test::uploadR32F("importance map with mips", level, width, size, levels);
    ImportanceSampler sampler(test::shaders());
    sampler.buildMips(texture, NextRead::TextureReadback);
    int w = width, h = size;
    for (int l = 1; l < levels; ++l) {
        const int fineWidth = w;
        w /= 2;
        h /= 2;
        std::vector<float> coarse(static_cast<std::size_t>(w * h));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                auto at = [&](int i, int j) { return level[static_cast<std::size_t>(j * fineWidth + i)]; };
                const float top = at(2 * x, 2 * y) + at(2 * x + 1, 2 * y);
                const float bottom = at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1);
                coarse[static_cast<std::size_t>(y * w + x)] = (top + bottom) * 0.25f;
            }
        std::vector<float> gpu(coarse.size());
        glGetTextureImage(texture.id(), l, GL_RED, GL_FLOAT, static_cast<GLsizei>(gpu.size() * sizeof(float)), gpu.data());
        INFO("level " << l << " (" << w << " x " << h << ")");
        CHECK(firstBitDifference(gpu, coarse) == -1);
        level = std::move(coarse);
    }
    gl::checkDebugMessages();

    // Sides that do not halve exactly at every level: one clear error.
    gl::TextureDesc odd;
    odd.format = GL_R32F;
    odd.width = 24;
    odd.height = 8;
    odd.levels = 4; // 24 -> 12 -> 6 -> 3 but 8 -> 4 -> 2 -> 1: fine; a fifth level would not be
    gl::Texture fine("importance map 24 x 8", odd);
    CHECK_NOTHROW(sampler.buildMips(fine, NextRead::None));
    odd.width = 20; // 20 -> 10 -> 5 -> 2: 5 does not halve exactly
    gl::Texture bad("importance map 20 x 8", odd);
    CHECK_THROWS_WITH(sampler.buildMips(bad, NextRead::None), Catch::Contains("halve exactly"));
}
