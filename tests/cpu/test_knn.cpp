// kNN (core/util/knn.h): nanoflann and the grid against brute force, the eq. (7) density of uniform points against
// N/area, and the timing of both (printed, not asserted).
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/util/knn.h"

using namespace vplgi;

namespace {

// Uniform floats in [0, 1) from mt19937's raw output (std:: distributions differ between libraries).
class Uniform {
public:
    explicit Uniform(std::uint32_t seed) : mEngine(seed) {}
    float operator()() { return static_cast<float>(mEngine() >> 8u) * 0x1p-24f; }

private:
    std::mt19937 mEngine;
};

std::vector<glm::vec3> randomPoints(std::size_t n, std::uint32_t seed, const glm::vec3& extent)
{
    Uniform u(seed);
    std::vector<glm::vec3> points(n);
    for (glm::vec3& p : points) {
        const float x = u(), y = u(), z = u();
        p = glm::vec3(x, y, z) * extent;
    }
    return points;
}

// n points uniform over the six faces of an axis-aligned box (by face area) and over a smaller box
// standing inside it: the walls an interior's raw SMCIR candidates land on.
std::vector<glm::vec3> boxSurfacePoints(std::size_t n, std::uint32_t seed)
{
    Uniform u(seed);
    std::vector<glm::vec3> points(n);
    for (std::size_t i = 0; i < n; ++i) {
        const bool inner = (i % 5) == 0;
        const glm::vec3 lower = inner ? glm::vec3(1.0f, 0.0f, 2.0f) : glm::vec3(0.0f);
        const glm::vec3 size = inner ? glm::vec3(1.6f, 3.3f, 1.6f) : glm::vec3(5.5f, 5.5f, 5.6f);
        const int face = static_cast<int>(u() * 6.0f) % 6, axis = face / 2;
        glm::vec3 p(u(), u(), u());
        p[axis] = static_cast<float>(face % 2);
        points[i] = lower + p * size;
    }
    return points;
}

double millisecondsSince(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

TEST_CASE("kNN: nanoflann finds the same distances as brute force for k = 1..16", "[knn]")
{
    const std::vector<glm::vec3> points = randomPoints(3000, 11u, glm::vec3(4.0f, 1.0f, 3.0f));
    // A few exact duplicates and a point repeated in the queries: ties must not change distances.
    std::vector<glm::vec3> withDuplicates = points;
    withDuplicates.push_back(points[5]);
    withDuplicates.push_back(points[5]);
    withDuplicates.push_back(points[17]);
    const KNNIndex index(withDuplicates);
    REQUIRE(index.size() == withDuplicates.size());

    std::vector<glm::vec3> queries = randomPoints(300, 12u, glm::vec3(5.0f, 1.5f, 4.0f)); // some outside the box
    queries.push_back(points[5]);
    queries.push_back(points[17]);
    int mismatches = 0;
    for (std::size_t k = 1; k <= 16; ++k) {
        for (const glm::vec3& q : queries) {
            std::uint32_t treeIndices[16], bruteIndices[16];
            float treeDistances[16], bruteDistances[16];
            REQUIRE(index.nearest(q, k, treeIndices, treeDistances) == k);
            REQUIRE(bruteForceNearest(withDuplicates, q, k, bruteIndices, bruteDistances) == k);
            for (std::size_t i = 0; i < k; ++i) {
                if (treeDistances[i] != bruteDistances[i]) ++mismatches; // bit-identical, not approximate
                // The index really points at a point at that distance.
                const glm::vec3 d = q - withDuplicates[treeIndices[i]];
                if (std::abs((d.x * d.x + d.y * d.y) + d.z * d.z - treeDistances[i]) > 1e-6f) ++mismatches;
            }
            if (index.kthDistanceSquared(q, k) != bruteDistances[k - 1]) ++mismatches;
        }
    }
    CHECK(mismatches == 0);

    // Neighbours among the others: the (k+1)-th of the whole set; a duplicate's are at distance 0.
    const std::vector<float> others = index.neighbourDistancesSquared(3);
    REQUIRE(others.size() == withDuplicates.size());
    for (std::size_t i = 0; i < withDuplicates.size(); i += 97)
        CHECK(others[i] == index.kthDistanceSquared(withDuplicates[i], 4));
    CHECK(index.neighbourDistancesSquared(1)[5] == 0.0f); // points[5] has two copies

    // Edge cases: fewer points than k, empty sets.
    const KNNIndex small(std::vector<glm::vec3>{glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f)});
    CHECK(small.kthDistanceSquared(glm::vec3(0.0f), 2) == 1.0f);
    CHECK(small.kthDistanceSquared(glm::vec3(0.0f), 3) == std::numeric_limits<float>::infinity());
    CHECK(small.neighbourDistancesSquared(2)[0] == std::numeric_limits<float>::infinity());
    const KNNIndex empty;
    CHECK(empty.size() == 0);
    CHECK(empty.kthDistanceSquared(glm::vec3(0.0f), 1) == std::numeric_limits<float>::infinity());
    CHECK(empty.neighbourDistancesSquared(1).empty());
}

TEST_CASE("kNN density of uniform points on a plane: mean of 1/p is the area (eq. 7, MATH.md 2)", "[knn][numbers]")
{
    // N uniform points on a 10 m x 10 m square in the plane y = 1: p = 1/area everywhere, and the
    // eq. (7) estimate p = k / (N pi r_k^2) has E[1/p] = area exactly (self excluded). Points within
    // 1.5 m of the border are not queried (their disc leaves the square).
    constexpr std::size_t kCount = 2048;
    constexpr float kSide = 10.0f, kBorder = 1.5f, kArea = kSide * kSide;
    Uniform u(2024u);
    std::vector<glm::vec3> points(kCount);
    for (glm::vec3& p : points) {
        const float x = u(), z = u();
        p = glm::vec3(x * kSide, 1.0f, z * kSide);
    }
    const KNNIndex index(points);
    // The interior holds a binomial share of the points (about +-2 %): 1/p measures the density
    // actually there, so the sharp reference is N * interior area / interior count.
    constexpr float kInteriorArea = (kSide - 2.0f * kBorder) * (kSide - 2.0f * kBorder);
    for (std::size_t k : {1, 4, 8, 16}) {
        const std::vector<float> r2 = index.neighbourDistancesSquared(k);
        double sumInverse = 0.0, sumDensity = 0.0;
        int interior = 0;
        for (std::size_t i = 0; i < kCount; ++i) {
            const glm::vec3& p = points[i];
            if (p.x < kBorder || p.x > kSide - kBorder || p.z < kBorder || p.z > kSide - kBorder) continue;
            const float density = estimateKNNDensity(k, kCount, r2[i]);
            REQUIRE(density > 0.0f);
            sumInverse += 1.0 / density;
            sumDensity += density;
            ++interior;
        }
        REQUIRE(interior > 900);
        const double meanInverse = sumInverse / interior; // -> area
        const double meanDensity = sumDensity / interior; // -> (1/area) k/(k-1), biased (MATH.md 2)
        const double local = static_cast<double>(kCount) * kInteriorArea / interior;
        std::printf("measured: kNN density, N = %zu on %.0f m^2, k = %2zu: mean 1/p = %.2f m^2 (area %.0f, from the interior"
                    " count %.2f), mean p * area = %.3f (k/(k-1) = %.3f)\n",
                    kCount, kArea, k, meanInverse, kArea, local, meanDensity * kArea,
                    k > 1 ? double(k) / double(k - 1) : 0.0);
        // The standard deviation of one 1/p is area/sqrt(k): the mean over ~1000 points is good to
        // about 3 % at k = 1 and 1 % at k = 16 (neighbouring estimates are correlated).
        CHECK(meanInverse == Approx(kArea).epsilon(k == 1 ? 0.08 : 0.04));
        CHECK(meanInverse == Approx(local).epsilon(k == 1 ? 0.06 : 0.025));
        if (k >= 4) CHECK(meanDensity * kArea == Approx(double(k) / double(k - 1)).epsilon(0.06));
    }
    // Eq. (7) itself.
    CHECK(estimateKNNDensity(8, 2048, 4.0f) == Approx(8.0 / (2048.0 * 3.14159265358979 * 4.0)));
    CHECK(estimateKNNDensity(8, 2048, std::numeric_limits<float>::infinity()) == 0.0f);
    CHECK(std::isfinite(estimateKNNDensity(8, 2048, 0.0f)));
}

TEST_CASE("kNN timing: nanoflann against brute force at SMCIR's sizes (printed)", "[knn][timing]")
{
    // Not a timed test: the numbers go to stdout so a run documents the choice of nanoflann
    // (ENVIRONMENT.md: 0.8-1.1 ms against 12-17 ms for brute force). Results must agree.
    const std::vector<glm::vec3> points = randomPoints(2048, 5u, glm::vec3(20.0f, 3.0f, 15.0f));
    for (std::size_t k : {1, 2, 9}) {
        auto start = std::chrono::steady_clock::now();
        const KNNIndex index(points);
        const double buildMs = millisecondsSince(start);
        start = std::chrono::steady_clock::now();
        std::vector<float> tree(points.size());
        for (std::size_t i = 0; i < points.size(); ++i)
            tree[i] = index.kthDistanceSquared(points[i], k);
        const double treeMs = millisecondsSince(start);
        start = std::chrono::steady_clock::now();
        std::vector<float> brute(points.size());
        std::vector<std::uint32_t> indices(k);
        std::vector<float> distances(k);
        for (std::size_t i = 0; i < points.size(); ++i) {
            bruteForceNearest(points, points[i], k, indices.data(), distances.data());
            brute[i] = distances[k - 1];
        }
        const double bruteMs = millisecondsSince(start);
        std::printf("kNN 2048 points x 2048 queries, k = %zu: nanoflann build %.2f ms + queries %.2f ms (one thread),"
                    " brute force %.2f ms\n",
                    k, buildMs, treeMs, bruteMs);
        CHECK(tree == brute);
    }
}

TEST_CASE("kNN grid: every point's k-th neighbour distance equals the kd-tree's bit for bit, on surfaces, volumes, "
          "clusters with outliers and degenerate sets", "[knn]")
{
    // neighbourDistancesSquared(points, k) is an optimisation of KNNIndex::neighbourDistancesSquared:
    // the values must be identical (SMCIR's resampling weights and so its VPLs stay bit-identical).
    // The stats show which structure answered, so each set checks the path it is meant to reach: the
    // grid, finer grids, brute force and the tree each answer some set here.
    struct Set {
        const char* name;
        std::vector<glm::vec3> points;
    };
    std::vector<Set> sets;
    sets.push_back({"box walls 32768", boxSurfacePoints(32768, 3u)});
    sets.push_back({"volume 3000", randomPoints(3000, 4u, glm::vec3(4.0f, 1.0f, 3.0f))});
    {
        // Three blobs a hundred times apart in spread, and far outliers the grid leaves to the tree.
        std::vector<glm::vec3> p = randomPoints(2000, 5u, glm::vec3(0.01f));
        for (const glm::vec3& q : randomPoints(2000, 6u, glm::vec3(1.0f))) p.push_back(q + glm::vec3(3.0f, 0.0f, 0.0f));
        for (const glm::vec3& q : boxSurfacePoints(4000, 7u)) p.push_back(q - glm::vec3(10.0f));
        for (int i = 0; i < 6; ++i) p.push_back(glm::vec3(40.0f + 7.0f * float(i), -30.0f, 25.0f * float(i % 2)));
        sets.push_back({"clusters + outliers", p});
    }
    {
        std::vector<glm::vec3> p = boxSurfacePoints(5000, 8u);
        for (std::size_t i = 0; i < 5000; i += 7) p.push_back(p[i]); // exact duplicates: distance 0
        sets.push_back({"walls with duplicates", p});
    }
    {
        Uniform u(9u);
        std::vector<glm::vec3> line(500), plane(800);
        for (glm::vec3& q : line) q = glm::vec3(u() * 3.0f, 1.0f, 2.0f);
        for (glm::vec3& q : plane) q = glm::vec3(u() * 3.0f, 1.0f, u() * 2.0f);
        sets.push_back({"collinear 500", line});
        sets.push_back({"plane 800", plane});
    }
    {
        // A flat ground (y = 0 exactly) and a few objects on it, 0.3% of the points: the vertical
        // quantile range is 0, yet the objects are not outliers to leave to brute force.
        Uniform u(15u);
        std::vector<glm::vec3> p(20000);
        for (glm::vec3& q : p) q = glm::vec3(u() * 100.0f, 0.0f, u() * 100.0f);
        for (int i = 0; i < 60; ++i) p.push_back(glm::vec3(40.0f + u(), 0.1f + 5.0f * u(), 60.0f + u()));
        sets.push_back({"ground + objects", p});
    }
    sets.push_back({"coincident 50", std::vector<glm::vec3>(50, glm::vec3(1.0f, 2.0f, 3.0f))});
    sets.push_back({"three points", {glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 2.0f)}});

    for (const Set& set : sets) {
        const KNNIndex tree(set.points);
        for (std::size_t k : {1, 2, 3, 9}) {
            NeighbourSearchStats stats;
            const std::vector<float> grid = neighbourDistancesSquared(set.points, k, &stats);
            const std::vector<float> reference = tree.neighbourDistancesSquared(k);
            REQUIRE(grid.size() == set.points.size());
            std::size_t mismatches = 0;
            for (std::size_t i = 0; i < grid.size(); ++i)
                if (!(grid[i] == reference[i] || (std::isinf(grid[i]) && std::isinf(reference[i])))) ++mismatches;
            std::printf("kNN grid, %-22s k = %zu: grid %s, %zu points by the grid (%zu by finer grids), %zu by brute force,"
                        " %zu by the tree, %zu cells of %.4f m; %zu mismatches\n",
                        set.name, k, stats.grid ? "used" : "declined", stats.gridPoints, stats.finerPoints,
                        stats.bruteForcePoints, stats.treePoints, stats.cells, double(stats.cellSize), mismatches);
            CHECK(mismatches == 0);
            CHECK(stats.gridPoints + stats.bruteForcePoints + stats.treePoints == set.points.size() * (set.points.size() > k ? 1 : 0));
            const std::string name = set.name;
            if (name == "box walls 32768" || name == "volume 3000" || name == "walls with duplicates" || name == "plane 800" ||
                name == "ground + objects") {
                // Spread sets: nearly everything answered by the grid (else this test would check the
                // tree); measured 98.6-100% (the rest: crowded corners at k = 9, duplicates).
                CHECK(stats.grid);
                CHECK(stats.gridPoints >= set.points.size() * 96 / 100);
            }
            if (name == "clusters + outliers") {
                // The 1 cm blob (10^6 times the walls' density) crowds its cell: a finer grid answers
                // it; the six outliers lie outside the grid's quantile box: brute force answers them.
                CHECK(stats.grid);
                CHECK(stats.bruteForcePoints >= 6);
                CHECK(stats.finerPoints >= 2000);
                CHECK(stats.gridPoints >= 7000);
            }
            if (name == "coincident 50") { // no box to grid: brute force (50 <= 64 points)
                CHECK_FALSE(stats.grid);
                CHECK(stats.bruteForcePoints == 50);
            }
            if (name == "collinear 500") { // no area: the tree answers all 500
                CHECK_FALSE(stats.grid);
                CHECK(stats.treePoints == 500);
            }
        }
    }
    // Brute force on a small set, to tie both to the definition, and n <= k.
    const std::vector<glm::vec3> small = boxSurfacePoints(600, 10u);
    const std::vector<float> grid = neighbourDistancesSquared(small, 3);
    int mismatches = 0;
    for (std::size_t i = 0; i < small.size(); ++i) {
        std::uint32_t indices[4];
        float distances[4];
        bruteForceNearest(small, small[i], 4, indices, distances);
        if (grid[i] != distances[3]) ++mismatches;
    }
    CHECK(mismatches == 0);
    CHECK(std::isinf(neighbourDistancesSquared(std::vector<glm::vec3>(3, glm::vec3(0.0f)), 3)[0]));
    // Large k: within the fixed arrays (k = 63 on 64 points), and beyond them (kMaxK = 63; SMCIR
    // allows k = 64): the tree.
    const std::vector<glm::vec3> few = randomPoints(64, 13u, glm::vec3(1.0f));
    NeighbourSearchStats large;
    CHECK(neighbourDistancesSquared(few, 63, &large) == KNNIndex(few).neighbourDistancesSquared(63));
    const std::vector<glm::vec3> more = randomPoints(100, 14u, glm::vec3(1.0f));
    CHECK(neighbourDistancesSquared(more, 64, &large) == KNNIndex(more).neighbourDistancesSquared(64));
    CHECK(large.treePoints == 100);
    CHECK(neighbourDistancesSquared({}, 1).empty());
}

TEST_CASE("kNN timing: the grid against the kd-tree for SMCIR's 16 I raw candidates (printed)", "[knn][timing]")
{
    // Not a timed test (the numbers go to stdout; #23 part 7 asked for <= 3 ms at I = 2048).
    const std::vector<glm::vec3> points = boxSurfacePoints(32768, 12u);
    for (std::size_t k : {1, 2}) {
        double treeMs = 1e30, gridMs = 1e30; // best of 5, each against the same input
        std::vector<float> tree, grid;
        NeighbourSearch search; // kept between calls, as the sampler keeps it between frames
        for (int rep = 0; rep < 5; ++rep) {
            auto start = std::chrono::steady_clock::now();
            tree = KNNIndex(points).neighbourDistancesSquared(k);
            treeMs = std::min(treeMs, millisecondsSince(start));
            start = std::chrono::steady_clock::now();
            grid = search.distancesSquared(points, k);
            gridMs = std::min(gridMs, millisecondsSince(start));
        }
        std::printf("kNN 32768 wall points, k-th other, k = %zu: kd-tree build + queries %.2f ms, grid %.2f ms (%.1fx),"
                    " best of 5\n",
                    k, treeMs, gridMs, treeMs / gridMs);
        CHECK(grid == tree);
    }
}
