// Embree 3 scene built from the same core::Scene the GL renderer draws: one triangle geometry per
// instance (vertices transformed to world space), geometry ID = instance index, primitive ID =
// triangle index within the mesh. Thread-safe queries (Embree's rtcIntersect1/rtcOccluded1).
#pragma once

#include <cstdint>
#include <limits>
#include <memory>

#include <glm/glm.hpp>

#include "scene.h"

namespace vplgi {

struct Ray {
    glm::vec3 origin{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f}; // need not be unit; t is in units of its length
    float tMin = 0.0f;
    float tMax = std::numeric_limits<float>::infinity();
};

struct Hit {
    float t = std::numeric_limits<float>::infinity();
    int instance = -1;   // index into Scene::instances; -1 = miss
    int triangle = -1;   // triangle index within the instance's mesh
    glm::vec2 barycentric{0.0f}; // Embree (u, v): p = (1-u-v) p0 + u p1 + v p2
    glm::vec3 geometricNormal{0.0f}; // world space, unnormalized, from the triangle winding
    bool valid() const { return instance >= 0; }
};

struct RayThroughput {
    double intersectPerSecond = 0.0; // closest-hit rays per second (rtcIntersect1)
    double occludedPerSecond = 0.0;  // any-hit rays per second (rtcOccluded1)
};

class RayScene;
// Casts `count` random rays of each kind (origins uniform in the scene bounds, directions uniform)
// on all TBB threads and measures the rate: the yardstick for "ray efficiency" of CPU stages.
RayThroughput measureRayThroughput(const RayScene& rays, int count, std::uint32_t seed = 1);

class RayScene {
public:
    explicit RayScene(const Scene& scene);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    Hit intersect(const Ray& ray) const;
    bool occluded(const Ray& ray) const;
    // True when nothing blocks the open segment between a and b (ends excluded by relative epsilon).
    bool visible(const glm::vec3& a, const glm::vec3& b) const;

    const Scene& scene() const { return mScene; }
    // Diagonal of the world bounds [m]: the scale for ray offsets (computed once).
    float sceneScale() const { return mSceneScale; }

private:
    struct Impl;
    const Scene& mScene;
    float mSceneScale = 1.0f;
    std::unique_ptr<Impl> mImpl;
};

} // namespace vplgi
