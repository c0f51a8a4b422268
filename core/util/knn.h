// k-nearest-neighbour queries over 3D points and the kNN density estimate of SMCIR eq. (7).
//
// Intro
// -----
// SMCIR (papers/000, 3.2.4) does not know the density p(y) of its VPLs in closed form: they are the
// survivors of many frames of sampling and discarding. It estimates p(y) like photon mapping does,
// from the distance r_k(y) to the k-th nearest VPL, assuming the neighbours lie on one plane:
//     p(y) ~= k / (I pi r_k(y)^2)            [1/m^2], integrates to 1 over the set   (eq. 7)
// MATH.md 2 gives the statistics: E[1/p] is exact for any k (so the intensity L/p is unbiased for
// uniform points), p itself is biased by k/(k-1), and the relative spread of p is about 1/sqrt(k-2).
//
// Overview
// --------
//  KNNIndex            a kd-tree (nanoflann) over a point set; thread-safe queries
//   nearest()          the k nearest points, nearest first
//   kthDistanceSquared r_k^2, the number eq. (7) needs
//   neighbourDistancesSquared  r_k^2 of every point of the set among the others, in parallel
//  NeighbourSearch     the same numbers from a uniform grid, O(n) on surfaces; reusable buffers
//  neighbourDistancesSquared(points, k)  the same, one-off
//  bruteForceNearest   the same answer by sorting every distance (for tests)
//  estimateKNNDensity  eq. (7)
//
// Details
// -------
//  Why nanoflann: for the SMCIR sizes (I = 2048 points, 2048 queries, k = 1..2) a nanoflann
//  kd-tree answered in 0.8-1.1 ms on this machine, Embree's rtcPointQuery in 1.1-1.7 ms and brute
//  force in 12-17 ms (ENVIRONMENT.md); it needs no Embree user geometry or callbacks, and the tree
//  is rebuilt every frame in well under a millisecond for 2048 points. test_knn.cpp measures
//  nanoflann against brute force again (k = 1, 2, 9) and prints the times.
//
//  Distances are squared Euclidean distances in float, summed as (dx^2 + dy^2) + dz^2 both by
//  nanoflann (L2_Simple_Adaptor) and by bruteForceNearest, so the two agree bit for bit. With equal
//  distances the order of the indices is unspecified; the distances are not.
//
//  The grid (SMCIR's line 6 weights: r_k of 16 I = 32768 raw candidates among themselves, every
//  frame): the kd-tree's serial build and 32k queries took 13.5 ms of a 54 ms Cornell frame. The
//  grid is dense over the points' box (cells sized for about max(2, k + 1) points if the points
//  covered the box's faces), filled by a counting sort with x fastest, so a row's three cells are
//  one range. Each point computes its distances to the points of the 27 cells around its own; a
//  point whose k-th distance is not proven by that block (it reaches further than the block's
//  nearest face) searches more shells. A crowded cell (its block
//  holds over 128 points: a dense cluster among sparse points, as near SMCIR's camera) is answered
//  by a finer grid over the points of the crowded blocks (up to three levels), where the answer is
//  proven inside the cell's own block; an unproven point searches up to four shells. What is left
//  (outliers outside the grid's quantile box, isolated points) gets brute force when a handful,
//  else the kd-tree. The distances are the same
//  float operations, so the k-th is the same number bit for bit (tested against the tree and brute
//  force); which structure answered changes only the time.
//
//  Excluding a point from its own neighbours: a point of the set is its own nearest neighbour at
//  distance 0, so the k-th neighbour among the others is the (k+1)-th of the whole set. That holds
//  even when other points coincide with it, which "skip the query's index" would get wrong.
//
// References
// ----------
//  J. L. Blanco, P. K. Rai: nanoflann, a C++ header-only library for nearest neighbour search with
//    kd-trees, 2014 (version 1.4.3, Debian libnanoflann-dev).
//  H. W. Jensen: Realistic Image Synthesis Using Photon Mapping, 2001 (the planar kNN density).
//  SMCIR (papers/000): 3.2.4, eq. (7) and (8).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

namespace vplgi {

class KNNIndex {
public:
    KNNIndex();
    // Builds the tree over a copy of `points`.
    explicit KNNIndex(std::vector<glm::vec3> points);
    ~KNNIndex();
    KNNIndex(KNNIndex&&) noexcept;
    KNNIndex& operator=(KNNIndex&&) noexcept;

    std::size_t size() const;
    const std::vector<glm::vec3>& points() const;

    // The min(k, size()) nearest points to `query`, nearest first: their indices into points() and
    // squared distances [m^2]. The arrays must hold k entries. Returns the number written.
    std::size_t nearest(const glm::vec3& query, std::size_t k, std::uint32_t* indices, float* distancesSquared) const;
    // Squared distance [m^2] to the k-th nearest point (k >= 1); +infinity when size() < k.
    float kthDistanceSquared(const glm::vec3& query, std::size_t k) const;
    // For every point of the set, the squared distance to its k-th nearest *other* point (entry i
    // for points()[i]; +infinity when size() <= k). Runs in parallel (TBB) and visits the points in
    // the tree's leaf order, which keeps neighbouring queries in cache (about 1.7x faster than
    // input order for 32k scattered points); the result does not depend on the thread count.
    std::vector<float> neighbourDistancesSquared(std::size_t k) const;

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

// What neighbourDistancesSquared(points, k) did: which structure answered how many points (grid ==
// false: no grid fits this set, e.g. collinear or coincident points; the rest answered them all).
struct NeighbourSearchStats {
    bool grid = false;
    std::size_t gridPoints = 0;       // answered by a grid
    std::size_t finerPoints = 0;      // of those, by a finer grid over crowded cells
    std::size_t bruteForcePoints = 0; // a handful left over (outliers, isolated points): every distance
    std::size_t treePoints = 0;       // more left over, or no grid: the kd-tree
    float cellSize = 0.0f; // [m]
    std::size_t cells = 0; // occupied
};

// For every point, the squared distance [m^2] to its k-th nearest other point: the same values as
// KNNIndex(points).neighbourDistancesSquared(k), bit for bit, from a uniform grid with brute force
// or the kd-tree as the fallback for points the grid cannot settle nearby (see Details). Parallel (TBB); the result
// does not depend on the thread count. The object keeps its buffers between calls: a per-frame
// caller (SMCIR's resampling) holds one, so the pages are not faulted in again every frame.
class NeighbourSearch {
public:
    static constexpr std::size_t kMaxK = 63; // larger k: the tree answers
    // The result lives until the next call.
    const std::vector<float>& distancesSquared(const std::vector<glm::vec3>& points, std::size_t k,
                                               NeighbourSearchStats* stats = nullptr);

private:
    const std::vector<float>& search(const std::vector<glm::vec3>& points, std::size_t k, int depth,
                                     NeighbourSearchStats* stats);
    bool bin(const std::vector<glm::vec3>& points, float cell);

    glm::vec3 mLower{0.0f}, mUpper{0.0f};
    float mCellSize = 0.0f;
    glm::ivec3 mDims{0};
    std::vector<std::uint32_t> mStart, mOccupiedCells, mCellOf, mFill, mSource, mRest; // cells (x fastest), points
    std::vector<glm::vec3> mSorted;                                   // the points, cell by cell
    std::vector<char> mState, mMark; // per point: answered, tree or crowded; per cell: near a crowded one
    std::vector<glm::vec3> mSubset;   // the points near crowded cells, for the finer grid
    std::vector<std::uint32_t> mSubsetAt;
    std::unique_ptr<NeighbourSearch> mFiner;
    std::vector<float> mResult;
};

// NeighbourSearch with buffers of its own, for one-off calls.
std::vector<float> neighbourDistancesSquared(const std::vector<glm::vec3>& points, std::size_t k,
                                             NeighbourSearchStats* stats = nullptr);

// KNNIndex::nearest by computing every distance (O(n log k)); ties broken by index.
std::size_t bruteForceNearest(const std::vector<glm::vec3>& points, const glm::vec3& query, std::size_t k,
                              std::uint32_t* indices, float* distancesSquared);

// Eq. (7): p ~= k / (count pi r_k^2) [1/m^2] from the squared k-th neighbour distance. 0 for an
// infinite distance (fewer than k neighbours); a zero distance is raised to 1e-20 m^2 so the density
// stays finite.
float estimateKNNDensity(std::size_t k, std::size_t count, float kthDistanceSquared);

} // namespace vplgi
