// TCAS's Metropolis-Hastings chains (gl/passes/metropolis_chains.h): the chains' stationary
// distribution is the importance map's I / total (chi-square from a start far from it), zero
// texels hold no chain, the draw records they write match their texels, and zero iterations move
// nothing. The chains are independent of each other (each has its own uniforms), so their states at
// one step are a multinomial sample: Pearson's statistic applies directly.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <vector>

#include "buffer_readback.h"
#include "gl/api/debug.h"
#include "gl/passes/importance_sampler.h"
#include "gl/passes/metropolis_chains.h"
#include "gl_test_context.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/importance.h"

using namespace vplgi;
using test::readBuffer;

namespace {

constexpr int kWidth = 24; // two "layers" of 12 x 12 side by side, as the RSM importance maps sit
constexpr int kHeight = 12;

// A map with a 1:40 range, a zero stripe between two lit islands (a chain must cross it by a
// uniform proposal: a local step of radius 2 cannot) and zero texels inside the islands.
std::vector<float> islandsMap()
{
    std::vector<float> map(static_cast<std::size_t>(kWidth * kHeight), 0.0f);
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth; ++x) {
            const bool stripe = x >= 9 && x < 15;
            const bool hole = (x * 7 + y * 3) % 11 == 0;
            if (stripe || hole) continue;
            const float s = std::sin(0.5f * static_cast<float>(x + 2 * y));
            map[static_cast<std::size_t>(y * kWidth + x)] = (x < 9 ? 4.0f : 1.0f) * (0.1f + s * s);
        }
    return map;
}

gl::Texture upload(const std::vector<float>& map)
{
    return test::uploadR32F("chain test importance", map, kWidth, kHeight);
}

struct ChiSquare {
    double statistic = 0.0;
    int cells = 0;      // texels with I > 0
    int onZero = 0;     // chains on texels with I = 0
};

ChiSquare chiSquare(const std::vector<std::uint32_t>& states, const std::vector<float>& map)
{
    double total = 0.0;
    for (float m : map)
        total += m;
    std::vector<int> counts(map.size(), 0);
    ChiSquare c;
    for (std::uint32_t s : states) {
        if (s >= map.size() || map[s] == 0.0f) {
            ++c.onZero;
            continue;
        }
        ++counts[s];
    }
    for (std::size_t i = 0; i < map.size(); ++i) {
        if (map[i] == 0.0f) continue;
        const double expected = static_cast<double>(states.size()) * map[i] / total;
        c.statistic += (counts[i] - expected) * (counts[i] - expected) / expected;
        ++c.cells;
    }
    return c;
}

// The chi-square's upper 1e-6 tail for `cells - 1` degrees of freedom (normal approximation, as
// tests/gl/test_importance_sampler.cpp): the seeds are fixed, so each statistic is one number, and a
// correct sampler exceeds this bound once in a million seeds.
double chiSquareBound(int cells)
{
    const double dof = cells - 1;
    return dof + 4.75 * std::sqrt(2.0 * dof);
}

} // namespace

TEST_CASE("Metropolis chains started on one texel reach the importance map's distribution (chi-square)",
          "[gl][importance][tcas][numbers]")
{
    test::ensureGLContext();
    const std::vector<float> map = islandsMap();
    gl::Texture texture = upload(map);
    ImportanceSampler tables(test::shaders());
    tables.build(texture, NextRead::StorageBuffer);
    MetropolisChains chains(test::shaders());
    const int count = 1 << 15;
    // Every chain starts on texel (20, 5) of the dimmer island: as far from the target as a start gets.
    const std::uint32_t start = 5 * kWidth + 20;
    REQUIRE(map[start] > 0.0f);
    chains.setStates(std::vector<std::uint32_t>(static_cast<std::size_t>(count), start));
    const ChiSquare atStart = chiSquare(readBuffer<std::uint32_t>(chains.states(), static_cast<std::size_t>(count)), map);
    const MetropolisProposal proposal; // the defaults tcas uses
    std::vector<double> statistic;
    for (int frame = 0; frame < 80; ++frame) {
        chains.step(texture, tables, 16, shared::hashPcg(77u + static_cast<std::uint32_t>(frame)), proposal,
                    NextRead::BufferReadback);
        if (frame == 1 || frame == 9 || frame == 79)
            statistic.push_back(chiSquare(readBuffer<std::uint32_t>(chains.states(), static_cast<std::size_t>(count)), map).statistic);
    }
    const std::vector<std::uint32_t> states = readBuffer<std::uint32_t>(chains.states(), static_cast<std::size_t>(count));
    const ChiSquare end = chiSquare(states, map);
    gl::checkDebugMessages();
    const double bound = chiSquareBound(end.cells);
    std::cout << "Metropolis chains (2^15, 16 iterations per frame, default proposal) from one texel on a 24x12 map "
              << "of two islands: chi-square at the start " << atStart.statistic << ", after 2/10/80 frames "
              << statistic[0] << " / " << statistic[1] << " / " << statistic[2] << " for " << end.cells - 1
              << " degrees of freedom (bound " << bound << "); chains on zero texels " << end.onZero << "\n";
    CHECK(atStart.statistic > 100.0 * bound); // the start is far from the target: the test can fail
    CHECK(end.statistic < bound);
    CHECK(end.onZero == 0);

    // The draw records: chain i's texel, probability I / total, its importance.
    double total = 0.0;
    for (float m : map)
        total += m;
    const std::vector<shared::ImportanceSample> samples = readBuffer<shared::ImportanceSample>(chains.samples(), static_cast<std::size_t>(count));
    int wrong = 0;
    for (int i = 0; i < count; ++i) {
        const shared::ImportanceSample& s = samples[static_cast<std::size_t>(i)];
        const std::uint32_t texel = states[static_cast<std::size_t>(i)];
        const float value = map[texel];
        wrong += s.x != static_cast<int>(texel % kWidth) || s.y != static_cast<int>(texel / kWidth) ||
                 s.importance != value || std::abs(s.probability * total / value - 1.0) > 1e-5;
    }
    CHECK(wrong == 0);
}

TEST_CASE("Metropolis chains started from the importance sampler's draws stay in the distribution, and zero "
          "iterations move nothing",
          "[gl][importance][tcas][numbers]")
{
    test::ensureGLContext();
    const std::vector<float> map = islandsMap();
    gl::Texture texture = upload(map);
    ImportanceSampler tables(test::shaders());
    tables.build(texture, NextRead::StorageBuffer);
    const int count = 1 << 15;
    tables.sample(texture, count, 5u, NextRead::StorageBuffer);
    MetropolisChains chains(test::shaders());
    chains.start(texture, tables, count, NextRead::BufferReadback);
    const std::vector<std::uint32_t> started = readBuffer<std::uint32_t>(chains.states(), static_cast<std::size_t>(count));
    const std::vector<shared::ImportanceSample> draws = readBuffer<shared::ImportanceSample>(tables.samples(), static_cast<std::size_t>(count));
    int mismatched = 0;
    for (int i = 0; i < count; ++i)
        mismatched += started[static_cast<std::size_t>(i)] !=
                      static_cast<std::uint32_t>(draws[static_cast<std::size_t>(i)].y * kWidth +
                                                 draws[static_cast<std::size_t>(i)].x);
    CHECK(mismatched == 0);
    const MetropolisProposal proposal;
    chains.step(texture, tables, 0, 1u, proposal, NextRead::BufferReadback);
    CHECK(chains.movedInLastStep() == 0);
    CHECK(readBuffer<std::uint32_t>(chains.states(), static_cast<std::size_t>(count)) == started);
    chains.step(texture, tables, 16, 2u, proposal, NextRead::BufferReadback);
    const ChiSquare after = chiSquare(readBuffer<std::uint32_t>(chains.states(), static_cast<std::size_t>(count)), map);
    const int moved = chains.movedInLastStep();
    std::cout << "Metropolis chains started from 2^15 draws: chi-square " << chiSquare(started, map).statistic
              << " at the start, " << after.statistic << " after one frame of 16 iterations (bound "
              << chiSquareBound(after.cells) << "); " << moved << " chains moved\n";
    CHECK(after.statistic < chiSquareBound(after.cells));
    CHECK(after.onZero == 0);
    CHECK(moved > 0);
    gl::checkDebugMessages();
}

TEST_CASE("Metropolis chains on an all-zero map write no draws", "[gl][importance][tcas]")
{
    test::ensureGLContext();
    const std::vector<float> map(static_cast<std::size_t>(kWidth * kHeight), 0.0f);
    gl::Texture texture = upload(map);
    ImportanceSampler tables(test::shaders());
    tables.build(texture, NextRead::StorageBuffer);
    MetropolisChains chains(test::shaders());
    chains.setStates(std::vector<std::uint32_t>(64, 3u));
    chains.step(texture, tables, 16, 9u, MetropolisProposal{}, NextRead::BufferReadback);
    int valid = 0;
    for (const shared::ImportanceSample& s : readBuffer<shared::ImportanceSample>(chains.samples(), 64))
        valid += s.x >= 0 || s.probability > 0.0f;
    CHECK(valid == 0);
    MetropolisChains unstarted(test::shaders());
    CHECK_THROWS_WITH(unstarted.step(texture, tables, 1, 1u, MetropolisProposal{}, NextRead::None),
                      Catch::Contains("before start()"));
}
