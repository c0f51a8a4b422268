// Embree 3 scene built from the same core::Scene the GL renderer draws: one triangle geometry per
// instance (vertices transformed to world space), geometry ID = instance index, primitive ID =
// triangle index within the mesh. Thread-safe queries (Embree's rtcIntersect1/rtcOccluded1).
#pragma once

#include <atomic>
#include <cstdint>
#include <limits>
#include <memory>

#include <glm/glm.hpp>

#include "core/scene/scene.h"

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

class RayScene;

// Who looks along a ray decides which single-sided surfaces it meets (the back-face rule, scene.h
// Material::doubleSided; docs/back-faces.md): the looker does not see their backs, as the rasterizer
// culls them in the camera's and in every light's and VPL's view.
enum class Looker {
    Origin, // the ray's origin looks (camera rays, rays leaving a light or a VPL): backs are absent
    End,    // the far end looks (a shadow ray from a receiver to a light or a VPL): a surface whose
            // front the ray reaches turns its back to the end, and is absent
    None,   // both sides stop the ray (a path tracer's bounce, whose back is black; distances)
};

// The yardstick of "ray efficiency" (SMCIR Table 2's goal: at most a third of a CPU stage's time
// goes to anything but rays): while a RayScene records into it, every ray cast (closest hit or
// occlusion, with its origin, direction and interval) is kept in a per-thread buffer; replay() then
// traces exactly those rays again on the same TBB threads with no other work. Replay time over the
// stage's wall time is the efficiency. Recording costs one vector append per ray.
class RayRecorder {
public:
    RayRecorder();
    ~RayRecorder();
    RayRecorder(const RayRecorder&) = delete;
    RayRecorder& operator=(const RayRecorder&) = delete;

    void add(const Ray& ray, bool closestHit, Looker looker); // thread-safe
    std::size_t size() const;                  // rays recorded (call when no ray is being cast)
    void clear();
    // Casts every recorded ray again, in parallel; returns the wall time [s].
    double replay(const RayScene& rays) const;

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

class RayScene {
public:
    explicit RayScene(const Scene& scene);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    Hit intersect(const Ray& ray, Looker looker = Looker::None) const;
    bool occluded(const Ray& ray, Looker looker = Looker::None) const;
    // True when nothing blocks the open segment from a to b (ends excluded by relative epsilon);
    // Looker::Origin: a looks, Looker::End: b looks.
    bool visible(const glm::vec3& a, const glm::vec3& b, Looker looker = Looker::None) const;

    // While set, every ray cast is also recorded (measurements only: set it when no other thread
    // casts rays that should not be counted; nullptr stops).
    void setRecorder(RayRecorder* recorder) const { mRecorder.store(recorder, std::memory_order_relaxed); }

    const Scene& scene() const { return mScene; }
    // Diagonal of the world bounds [m]: the scale for ray offsets (computed once).
    float sceneScale() const { return mSceneScale; }

private:
    struct Impl;
    const Scene& mScene;
    float mSceneScale = 1.0f;
    std::unique_ptr<Impl> mImpl;
    mutable std::atomic<RayRecorder*> mRecorder{nullptr}; // measurement state, not scene state
};

} // namespace vplgi
