// The CPU twin of the importance sampler: tables and searches on maps small enough to work out by
// hand (../shared/MATH.md 9.7).
#include <catch2/catch.hpp>

#include <cmath>

#include "core/util/error.h"
#include "core/util/importance_table.h"

using namespace vplgi;

namespace {

shared::ImportanceSample draw(const ImportanceTable& t, float xi1, float xi2)
{
    return shared::sampleImportance(t, t.width, t.height, glm::vec2(xi1, xi2));
}

} // namespace

TEST_CASE("importance tables are column sums and a marginal of column totals", "[importance]")
{
    // 3 x 2, rows bottom to top: column totals 1, 0, 3.
    const ImportanceTable t = buildImportanceTable({0.25f, 0.0f, 2.0f, //
                                                    0.75f, 0.0f, 1.0f},
                                                   3, 2);
    CHECK(t.columns == std::vector<float>{0.25f, 0.0f, 2.0f, 1.0f, 0.0f, 3.0f});
    CHECK(t.marginal == std::vector<float>{1.0f, 1.0f, 4.0f});
    CHECK(t.total() == 4.0f);
}

TEST_CASE("the search inverts the CDFs and never stops on a zero texel", "[importance]")
{
    const ImportanceTable t = buildImportanceTable({0.25f, 0.0f, 2.0f, //
                                                    0.75f, 0.0f, 1.0f},
                                                   3, 2);
    const float below1 = 1.0f - 0x1p-24f; // the largest uniform the hash gives
    // xi1 * 4 < 1 -> column 0; at exactly 1 the strict '>' passes the zero column and lands on 2.
    CHECK(draw(t, 0.0f, 0.0f).x == 0);
    CHECK(draw(t, 0.2499f, 0.0f).x == 0);
    CHECK(draw(t, 0.25f, 0.0f).x == 2);
    CHECK(draw(t, below1, 0.0f).x == 2);
    // Column 0: C = 0.25, 1 -> row 0 below xi2 = 0.25, row 1 from there on.
    CHECK(draw(t, 0.0f, 0.2f).y == 0);
    CHECK(draw(t, 0.0f, 0.25f).y == 1);
    CHECK(draw(t, 0.0f, below1).y == 1);
    // Column 2: C = 2, 3 over a total of 3.
    CHECK(draw(t, 0.5f, 0.6f).y == 0);
    CHECK(draw(t, 0.5f, 0.7f).y == 1);

    const shared::ImportanceSample s = draw(t, 0.5f, 0.7f);
    CHECK(s.importance == 1.0f);
    CHECK(s.probability == 0.25f);
    // A sweep over both uniforms: every draw is a texel with importance > 0.
    int zero = 0;
    for (int i = 0; i <= 64; ++i)
        for (int j = 0; j <= 64; ++j) {
            const shared::ImportanceSample d = draw(t, std::min(i / 64.0f, below1), std::min(j / 64.0f, below1));
            zero += d.importance <= 0.0f;
        }
    CHECK(zero == 0);
}

TEST_CASE("an all-zero map draws no texel", "[importance]")
{
    const ImportanceTable t = buildImportanceTable(std::vector<float>(6, 0.0f), 3, 2);
    const shared::ImportanceSample s = draw(t, 0.5f, 0.5f);
    CHECK(s.x == -1);
    CHECK(s.y == -1);
    CHECK(s.probability == 0.0f);
}

TEST_CASE("the hash uniforms lie below 1 and depend on seed and index", "[importance]")
{
    const glm::vec2 a = shared::importanceUniforms(1u, 0u);
    const glm::vec2 b = shared::importanceUniforms(1u, 1u);
    const glm::vec2 c = shared::importanceUniforms(2u, 0u);
    CHECK(a != b);
    CHECK(a != c);
    double mean = 0.0;
    for (std::uint32_t i = 0; i < 100000; ++i) {
        const glm::vec2 u = shared::importanceUniforms(7u, i);
        REQUIRE(u.x >= 0.0f);
        REQUIRE(u.x < 1.0f);
        REQUIRE(u.y >= 0.0f);
        REQUIRE(u.y < 1.0f);
        mean += u.x + u.y;
    }
    // Mean of 2e5 uniforms: standard deviation sqrt(1/12 / 2e5) = 6.5e-4; the bound is 5 of those.
    CHECK(std::abs(mean / 200000.0 - 0.5) < 3.2e-3);
}

TEST_CASE("importance maps with a wrong size or negative values are errors", "[importance]")
{
    CHECK_THROWS_WITH(buildImportanceTable({1.0f, 2.0f}, 3, 2), Catch::Contains("2 values for 3 x 2"));
    CHECK_THROWS_WITH(buildImportanceTable({1.0f, -2.0f}, 2, 1), Catch::Contains(">= 0"));
}
