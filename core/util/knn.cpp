#include "core/util/knn.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
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

std::size_t bruteForceNearest(const std::vector<glm::vec3>& points, const glm::vec3& query, std::size_t k,
                              std::uint32_t* indices, float* distancesSquared)
{
    const std::size_t count = std::min(k, points.size());
    std::vector<std::pair<float, std::uint32_t>> all(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        // The same float operations in the same order as nanoflann's L2_Simple_Adaptor.
        float d = 0.0f;
        for (int c = 0; c < 3; ++c) {
            const float diff = query[c] - points[i][c];
            d += diff * diff;
        }
        all[i] = {d, static_cast<std::uint32_t>(i)};
    }
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
