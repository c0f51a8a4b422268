#include "core/util/knn.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <type_traits>
#include <utility>

#include <nanoflann.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace vplgi {

namespace {

constexpr float kPiFloat = 3.14159265358979f;

// nanoflann's dataset interface over a vector of glm points.
struct PointCloud {
    std::vector<glm::vec3> points;

    std::size_t kdtree_get_point_count() const { return points.size(); }
    float kdtree_get_pt(std::size_t index, std::size_t dimension) const { return points[index][static_cast<int>(dimension)]; }
    template <class BBox>
    bool kdtree_get_bbox(BBox&) const
    {
        return false; // let nanoflann compute the bounds
    }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointCloud>, PointCloud, 3,
                                                 std::uint32_t>;

} // namespace

// The cloud lives next to the tree that references it, on the heap, so moving a KNNIndex moves a
// pointer and the reference stays valid.
struct KNNIndex::Impl {
    PointCloud cloud;
    Tree tree;

    explicit Impl(std::vector<glm::vec3> points)
        : cloud{std::move(points)}, tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10))
    {
    }
};

KNNIndex::KNNIndex() : KNNIndex(std::vector<glm::vec3>{}) {}

KNNIndex::KNNIndex(std::vector<glm::vec3> points) : mImpl(std::make_unique<Impl>(std::move(points))) {}

KNNIndex::~KNNIndex() = default;
KNNIndex::KNNIndex(KNNIndex&&) noexcept = default;
KNNIndex& KNNIndex::operator=(KNNIndex&&) noexcept = default;

std::size_t KNNIndex::size() const
{
    return mImpl->cloud.points.size();
}

const std::vector<glm::vec3>& KNNIndex::points() const
{
    return mImpl->cloud.points;
}

std::size_t KNNIndex::nearest(const glm::vec3& query, std::size_t k, std::uint32_t* indices,
                              float* distancesSquared) const
{
    const std::size_t count = std::min(k, size());
    if (count == 0) return 0;
    const float q[3] = {query.x, query.y, query.z};
    nanoflann::KNNResultSet<float, std::uint32_t> result(count);
    result.init(indices, distancesSquared);
    mImpl->tree.findNeighbors(result, q, nanoflann::SearchParams());
    return result.size();
}

float KNNIndex::kthDistanceSquared(const glm::vec3& query, std::size_t k) const
{
    if (k == 0 || size() < k) return std::numeric_limits<float>::infinity();
    constexpr std::size_t kStack = 64; // SMCIR's k stay far below this; larger k use the heap
    std::uint32_t stackIndices[kStack];
    float stackDistances[kStack];
    std::vector<std::uint32_t> heapIndices;
    std::vector<float> heapDistances;
    std::uint32_t* indices = stackIndices;
    float* distances = stackDistances;
    if (k > kStack) {
        heapIndices.resize(k);
        heapDistances.resize(k);
        indices = heapIndices.data();
        distances = heapDistances.data();
    }
    const std::size_t found = nearest(query, k, indices, distances);
    return found == k ? distances[k - 1] : std::numeric_limits<float>::infinity();
}

std::vector<float> KNNIndex::neighbourDistancesSquared(std::size_t k) const
{
    const std::size_t n = size();
    std::vector<float> result(n, std::numeric_limits<float>::infinity());
    if (k == 0 || n <= k) return result;
    // The tree's permutation of the points (public in nanoflann 1.4.3): leaf by leaf.
    const std::vector<std::uint32_t>& order = mImpl->tree.vAcc;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i < r.end(); ++i) {
            const std::uint32_t point = order[i];
            // A point is its own nearest neighbour (distance 0): the k-th other is the (k+1)-th.
            result[point] = kthDistanceSquared(mImpl->cloud.points[point], k + 1);
        }
    });
    return result;
}

namespace {

// --- the grid behind NeighbourSearch ---------------------------------------------------------------

// Crowding: a cell whose 27-cell block holds more points than this is answered by a finer grid
// (a tree query costs about as much as 100 grid distances on this machine: 0.3 us against ~3 ns;
// 256 measured fastest on the maze's raw candidates, against 128 and 512).
constexpr std::uint32_t kMaxBlockPoints = 256; // or 32 (k + 1) for larger k
constexpr std::uint32_t kNoCell = ~std::uint32_t{0};
// Finer grids for crowded cells, at most this many levels below the first.
constexpr int kMaxDepth = 3;
// An unproven point searches shells up to this Chebyshev distance (its own cell is shell 0).
constexpr int kMaxShell = 4;
// Points left over after the grids: up to this many get brute force (n distances each), more the
// kd-tree (a build over all n points: 5-8 ms at n = 32768 on this machine).
constexpr std::size_t kMaxBruteForce = 64;
// A point's state in NeighbourSearch::mState.
constexpr char kAnswered = 0, kTree = 1, kCrowded = 2;
// At most this many cells per point (the dense grid's start array): a box's walls at k = 1 need
// about 4.3 per point at 32768 points; more means outliers stretch the box, and the cells grow.
constexpr double kMaxCellsPerPoint = 16.0;

// Keeps the m smallest of the distances offered, ascending (m <= NeighbourSearch::kMaxK + 1; M > 0
// fixes m at compile time so the loop unrolls, M = 0 takes it at run time). Branch-free (an
// insertion network of min/max): which candidate beats which is unpredictable, and mispredicted
// branches cost more than the m min/max pairs at SMCIR's m = 2.
template <std::size_t M>
struct Smallest {
    float d[M == 0 ? NeighbourSearch::kMaxK + 1 : M];
    std::size_t m;
    explicit Smallest(std::size_t count) : m(M == 0 ? count : M) { std::fill(d, d + size(), std::numeric_limits<float>::infinity()); }
    std::size_t size() const { return M == 0 ? m : M; }
    float last() const { return d[size() - 1]; }
    void offer(float x)
    {
        for (std::size_t i = 0; i < size(); ++i) {
            const float low = std::min(d[i], x);
            x = std::max(d[i], x);
            d[i] = low;
        }
    }
};

// The same float operations in the same order as nanoflann's L2_Simple_Adaptor.
inline float distanceSquared(const glm::vec3& a, const glm::vec3& b)
{
    float d = 0.0f;
    for (int c = 0; c < 3; ++c) {
        const float diff = a[c] - b[c];
        d += diff * diff;
    }
    return d;
}

} // namespace

bool NeighbourSearch::bin(const std::vector<glm::vec3>& points, float cell)
{
    mCellSize = cell;
    const glm::vec3 cellsPerAxis = (mUpper - mLower) / cell + 1.0f;
    const double total = double(cellsPerAxis.x) * double(cellsPerAxis.y) * double(cellsPerAxis.z);
    if (!(total <= kMaxCellsPerPoint * double(points.size()) + 64.0)) return false;
    mDims = glm::ivec3(cellsPerAxis);
    const std::size_t cells = std::size_t(mDims.x) * std::size_t(mDims.y) * std::size_t(mDims.z);
    // Counting sort by cell, x fastest, so the three cells x-1..x+1 of a row are one range. Points
    // outside the grid's box (outliers) get no cell.
    mStart.assign(cells + 1, 0);
    mCellOf.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        const glm::vec3& p = points[i];
        if (glm::any(glm::lessThan(p, mLower)) || glm::any(glm::greaterThan(p, mUpper))) {
            mCellOf[i] = kNoCell;
            continue;
        }
        const glm::ivec3 c = glm::clamp(glm::ivec3(glm::floor((p - mLower) / cell)), glm::ivec3(0), mDims - 1);
        const std::uint32_t index = static_cast<std::uint32_t>((std::size_t(c.z) * mDims.y + c.y) * mDims.x + c.x);
        mCellOf[i] = index;
        ++mStart[index + 1];
    }
    mOccupiedCells.clear();
    for (std::size_t c = 0; c < cells; ++c) {
        if (mStart[c + 1]) mOccupiedCells.push_back(static_cast<std::uint32_t>(c));
        mStart[c + 1] += mStart[c];
    }
    return true;
}

const std::vector<float>& NeighbourSearch::distancesSquared(const std::vector<glm::vec3>& points, std::size_t k,
                                                            NeighbourSearchStats* stats)
{
    return search(points, k, 0, stats);
}

const std::vector<float>& NeighbourSearch::search(const std::vector<glm::vec3>& points, std::size_t k, int depth,
                                                  NeighbourSearchStats* stats)
{
    const std::size_t n = points.size();
    mResult.assign(n, std::numeric_limits<float>::infinity());
    NeighbourSearchStats local;
    NeighbourSearchStats& s = stats ? *stats : local;
    s = NeighbourSearchStats{};
    if (k == 0 || n <= k) return mResult;
    const std::size_t m = k + 1; // a point is its own nearest neighbour: the k-th other is the (k+1)-th

    glm::vec3 allLower(std::numeric_limits<float>::infinity()), allUpper(-std::numeric_limits<float>::infinity());
    bool finite = true; // a NaN or infinite coordinate leaves everything to the tree
    for (const glm::vec3& p : points) {
        finite = finite && glm::all(glm::lessThan(glm::abs(p), glm::vec3(1e30f)));
        allLower = glm::min(allLower, p);
        allUpper = glm::max(allUpper, p);
    }
    // The grid's box: the 0.5% and 99.5% quantiles of a strided sample of up to 4096 points, widened
    // each side by a quarter of the widest axis's range (not the axis's own: on a flat ground with a
    // few objects the vertical range is 0, and every object point would be an outlier), within the
    // points' box. Outliers (a far hill seen through a window) would otherwise stretch the box and
    // crowd the rest into a few cells; brute force or the tree answers them.
    mLower = allLower;
    mUpper = allUpper;
    if (finite) {
        const std::size_t stride = std::max<std::size_t>(1, n / 4096);
        std::vector<float> sample;
        sample.reserve(n / stride + 1);
        glm::vec3 low(0.0f), high(0.0f);
        for (int a = 0; a < 3; ++a) {
            sample.clear();
            for (std::size_t i = 0; i < n; i += stride) sample.push_back(points[i][a]);
            const std::size_t cut = sample.size() / 200;
            std::nth_element(sample.begin(), sample.begin() + static_cast<std::ptrdiff_t>(cut), sample.end());
            low[a] = sample[cut];
            std::nth_element(sample.begin(), sample.end() - 1 - static_cast<std::ptrdiff_t>(cut), sample.end());
            high[a] = sample[sample.size() - 1 - cut];
        }
        const glm::vec3 range = high - low;
        const float pad = 0.25f * glm::max(range.x, glm::max(range.y, range.z));
        mLower = glm::max(allLower, low - pad);
        mUpper = glm::min(allUpper, high + pad);
    }
    const glm::bvec3 openLow = glm::greaterThan(mLower, allLower), openHigh = glm::lessThan(mUpper, allUpper);
    const glm::vec3 extent = mUpper - mLower;

    // Cell size: about max(2, m) points per cell if the points covered the box's six faces (an
    // interior's walls); one rescale by the occupancy actually found (volumes, open scenes), and
    // larger cells where the box would need too many.
    bool usable = false;
    if (finite && k <= kMaxK) {
        const double area = 2.0 * (double(extent.x) * extent.y + double(extent.y) * extent.z + double(extent.z) * extent.x);
        const double target = std::max<double>(2.0, static_cast<double>(m));
        double cell = std::sqrt(area * target / static_cast<double>(n));
        if (cell > 0.0 && std::isfinite(cell)) {
            const double volumeCell = std::cbrt(double(extent.x + 1e-30f) * double(extent.y + 1e-30f) *
                                                double(extent.z + 1e-30f) / (kMaxCellsPerPoint * 0.5 * double(n)));
            for (int attempt = 0; attempt < 4 && !usable; ++attempt) {
                usable = bin(points, static_cast<float>(cell));
                if (!usable) cell = std::max(cell * 1.5, volumeCell); // too many cells: larger ones
            }
            if (usable) {
                const double mean = static_cast<double>(n) / static_cast<double>(std::max<std::size_t>(1, mOccupiedCells.size()));
                if (mean > 4.0 * target || mean < 0.25 * target) {
                    const double scaled = cell * std::clamp(std::sqrt(target / mean), 0.125, 8.0);
                    if (!bin(points, static_cast<float>(scaled))) usable = bin(points, static_cast<float>(cell));
                }
            }
        }
    }

    mState.assign(n, usable ? kAnswered : kTree);
    if (usable) {
        s.grid = true;
        s.cellSize = mCellSize;
        s.cells = mOccupiedCells.size();
        mSorted.resize(n);
        mSource.resize(n);
        mFill.assign(mStart.begin(), mStart.end() - 1);
        for (std::size_t i = 0; i < n; ++i) {
            if (mCellOf[i] == kNoCell) { // outside the grid's box
                mState[i] = kTree;
                continue;
            }
            const std::uint32_t at = mFill[mCellOf[i]]++;
            mSorted[at] = points[i];
            mSource[at] = static_cast<std::uint32_t>(i);
        }
        // Binning and the cell faces are rounded: a point may sit a few ulps outside its cell. A
        // k-th distance counts as proven only below the block's nearest face minus this margin.
        const float maxAbs = glm::max(glm::max(glm::abs(mLower).x, glm::abs(mLower).y), glm::abs(mLower).z) +
                             glm::max(glm::max(extent.x, extent.y), extent.z);
        const float margin = 1e-5f * (maxAbs + mCellSize);
        const glm::ivec3 dims = mDims;
        auto cellCoordinates = [&](std::uint32_t index) {
            return glm::ivec3(int(index % std::uint32_t(dims.x)), int(index / std::uint32_t(dims.x) % std::uint32_t(dims.y)),
                              int(index / (std::uint32_t(dims.x) * std::uint32_t(dims.y))));
        };
        const std::uint32_t blockLimit = std::max<std::uint32_t>(kMaxBlockPoints, 32 * static_cast<std::uint32_t>(m));
        const float size = mCellSize;
        const glm::vec3 lower = mLower;
        // Offers q every point in the cells at Chebyshev distance exactly r from c, row by row.
        auto searchShell = [&](const glm::vec3& q, const glm::ivec3& c, int r, auto& best) {
            const int x0 = std::max(c.x - r, 0), x1 = std::min(c.x + r, dims.x - 1);
            for (int z = std::max(c.z - r, 0); z <= std::min(c.z + r, dims.z - 1); ++z)
                for (int y = std::max(c.y - r, 0); y <= std::min(c.y + r, dims.y - 1); ++y) {
                    const std::size_t row = (std::size_t(z) * dims.y + y) * dims.x;
                    auto offerRange = [&](int xa, int xb) {
                        for (std::uint32_t j = mStart[row + xa]; j < mStart[row + xb + 1]; ++j)
                            best.offer(distanceSquared(q, mSorted[j]));
                    };
                    if (std::abs(z - c.z) == r || std::abs(y - c.y) == r) offerRange(x0, x1);
                    else { // the shell's two end cells of this row
                        if (c.x - r >= 0) offerRange(c.x - r, c.x - r);
                        if (c.x + r < dims.x) offerRange(c.x + r, c.x + r);
                    }
                }
        };
        // Is everything outside the block within Chebyshev distance r of c provably farther from q
        // than `kth`, the m-th distance found? Faces at the grid's edge have nothing beyond them.
        auto provenBeyond = [&](const glm::vec3& q, const glm::ivec3& c, int r, float kth) {
            float gap = std::numeric_limits<float>::infinity();
            for (int a = 0; a < 3; ++a) {
                // The searched block's faces, clipped to the grid; a face at the grid's edge counts
                // only where outliers lie beyond it.
                if (c[a] - r > 0 || openLow[a])
                    gap = std::min(gap, q[a] - (lower[a] + static_cast<float>(std::max(c[a] - r, 0)) * size));
                if (c[a] + r < dims[a] - 1 || openHigh[a])
                    gap = std::min(gap, lower[a] + static_cast<float>(std::min(c[a] + r, dims[a] - 1) + 1) * size - q[a]);
            }
            if (gap == std::numeric_limits<float>::infinity()) return true; // the block holds every point
            const float safe = gap - margin;
            return safe > 0.0f && kth < safe * safe * (1.0f - 1e-5f);
        };
        // Cell by cell: the 3 x 3 rows of the block around a cell are found once for its points.
        auto scan = [&](auto fixedM) {
        constexpr std::size_t M = decltype(fixedM)::value;
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mOccupiedCells.size(), 64), [&](const tbb::blocked_range<std::size_t>& range) {
            std::pair<std::uint32_t, std::uint32_t> rows[9];
            for (std::size_t o = range.begin(); o < range.end(); ++o) {
                const std::uint32_t index = mOccupiedCells[o];
                const glm::ivec3 c = cellCoordinates(index);
                int rowCount = 0;
                const int x0 = std::max(c.x - 1, 0), x1 = std::min(c.x + 1, dims.x - 1);
                for (int z = std::max(c.z - 1, 0); z <= std::min(c.z + 1, dims.z - 1); ++z)
                    for (int y = std::max(c.y - 1, 0); y <= std::min(c.y + 1, dims.y - 1); ++y) {
                        const std::size_t row = (std::size_t(z) * dims.y + y) * dims.x;
                        if (mStart[row + x0] < mStart[row + x1 + 1]) rows[rowCount++] = {mStart[row + x0], mStart[row + x1 + 1]};
                    }
                std::uint32_t blockPoints = 0;
                for (int r = 0; r < rowCount; ++r) blockPoints += rows[r].second - rows[r].first;
                if (blockPoints > blockLimit) { // crowded: a finer grid or the tree answers this cell
                    for (std::uint32_t at = mStart[index]; at < mStart[index + 1]; ++at) mState[mSource[at]] = kCrowded;
                    continue;
                }
                for (std::uint32_t at = mStart[index]; at < mStart[index + 1]; ++at) {
                    const glm::vec3 q = mSorted[at];
                    Smallest<M> best(m);
                    for (int r = 0; r < rowCount; ++r)
                        for (std::uint32_t j = rows[r].first; j < rows[r].second; ++j) best.offer(distanceSquared(q, mSorted[j]));
                    // Proven by the block, or by up to kMaxShell - 1 more shells (sparse places).
                    bool done = provenBeyond(q, c, 1, best.last());
                    for (int r = 2; r <= kMaxShell && !done; ++r) {
                        searchShell(q, c, r, best);
                        done = provenBeyond(q, c, r, best.last());
                    }
                    if (done) mResult[mSource[at]] = best.last();
                    else mState[mSource[at]] = kTree;
                }
            }
        });
        };
        switch (m) { // SMCIR's k = 1..3 unrolled
        case 2: scan(std::integral_constant<std::size_t, 2>{}); break;
        case 3: scan(std::integral_constant<std::size_t, 3>{}); break;
        case 4: scan(std::integral_constant<std::size_t, 4>{}); break;
        default: scan(std::integral_constant<std::size_t, 0>{}); break;
        }

        // Crowded cells (a dense cluster among sparser points): a finer grid, one level deeper, over
        // the points of their blocks. Its k-th distance for a crowded point is the true one where it
        // is proven inside the point's own block, which the subset holds whole.
        mMark.assign(mStart.size() - 1, 0);
        bool crowded = false;
        for (const std::uint32_t index : mOccupiedCells) {
            if (mState[mSource[mStart[index]]] != kCrowded) continue;
            crowded = true;
            const glm::ivec3 c = cellCoordinates(index);
            for (int z = std::max(c.z - 1, 0); z <= std::min(c.z + 1, dims.z - 1); ++z)
                for (int y = std::max(c.y - 1, 0); y <= std::min(c.y + 1, dims.y - 1); ++y)
                    for (int x = std::max(c.x - 1, 0); x <= std::min(c.x + 1, dims.x - 1); ++x)
                        mMark[(std::size_t(z) * dims.y + y) * dims.x + x] = 1;
        }
        if (crowded && depth < kMaxDepth) {
            mSubset.clear();
            mSubsetAt.clear();
            for (const std::uint32_t index : mOccupiedCells)
                if (mMark[index])
                    for (std::uint32_t at = mStart[index]; at < mStart[index + 1]; ++at) {
                        mSubset.push_back(mSorted[at]);
                        mSubsetAt.push_back(at);
                    }
            if (!mFiner) mFiner = std::make_unique<NeighbourSearch>();
            NeighbourSearchStats finer;
            const std::vector<float>& sub = mFiner->search(mSubset, k, depth + 1, &finer);
            for (std::size_t j = 0; j < mSubset.size(); ++j) {
                const std::uint32_t point = mSource[mSubsetAt[j]];
                if (mState[point] != kCrowded) continue;
                if (provenBeyond(mSubset[j], cellCoordinates(mCellOf[point]), 1, sub[j])) {
                    mResult[point] = sub[j];
                    mState[point] = kAnswered;
                    ++s.finerPoints;
                }
            }
        }
    }
    mRest.clear();
    for (std::size_t i = 0; i < n; ++i)
        if (mState[i] != kAnswered) mRest.push_back(static_cast<std::uint32_t>(i));
    s.gridPoints = n - mRest.size();
    const bool bruteForce = mRest.size() <= kMaxBruteForce && m <= kMaxK + 1; // Smallest<0> holds kMaxK + 1
    (bruteForce ? s.bruteForcePoints : s.treePoints) = mRest.size();
    if (!mRest.empty() && bruteForce) {
        // A handful left (outliers, isolated points): every distance, cheaper than building the
        // tree over all n points. The same float operations, so the same k-th value.
        auto scanAll = [&](auto fixedM) {
            tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mRest.size(), 4), [&](const tbb::blocked_range<std::size_t>& r) {
                for (std::size_t i = r.begin(); i < r.end(); ++i) {
                    const glm::vec3 q = points[mRest[i]];
                    Smallest<decltype(fixedM)::value> best(m);
                    for (const glm::vec3& p : points) best.offer(distanceSquared(q, p));
                    mResult[mRest[i]] = best.last();
                }
            });
        };
        if (m == 2) scanAll(std::integral_constant<std::size_t, 2>{});
        else scanAll(std::integral_constant<std::size_t, 0>{});
    } else if (!mRest.empty()) {
        const KNNIndex index(points);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mRest.size(), 64), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i < r.end(); ++i)
                mResult[mRest[i]] = index.kthDistanceSquared(points[mRest[i]], m);
        });
    }
    return mResult;
}

std::vector<float> neighbourDistancesSquared(const std::vector<glm::vec3>& points, std::size_t k,
                                             NeighbourSearchStats* stats)
{
    NeighbourSearch search;
    return search.distancesSquared(points, k, stats);
}

std::size_t bruteForceNearest(const std::vector<glm::vec3>& points, const glm::vec3& query, std::size_t k,
                              std::uint32_t* indices, float* distancesSquared)
{
    const std::size_t count = std::min(k, points.size());
    std::vector<std::pair<float, std::uint32_t>> all(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
        all[i] = {distanceSquared(query, points[i]), static_cast<std::uint32_t>(i)};
    std::partial_sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(count), all.end());
    for (std::size_t i = 0; i < count; ++i) {
        distancesSquared[i] = all[i].first;
        indices[i] = all[i].second;
    }
    return count;
}

float estimateKNNDensity(std::size_t k, std::size_t count, float kthDistanceSquared)
{
    if (!(kthDistanceSquared < std::numeric_limits<float>::infinity()) || count == 0) return 0.0f;
    const float r2 = std::max(kthDistanceSquared, 1e-20f);
    return static_cast<float>(static_cast<double>(k) / (static_cast<double>(count) * kPiFloat * r2));
}

} // namespace vplgi
