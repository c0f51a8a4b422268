#include "core/trace/ray_scene.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <embree3/rtcore.h>

#include "core/scene/surface.h"
#include "core/util/error.h"

namespace vplgi {

namespace {

// What the filter of one instance's geometry reads (single-sided or alpha-masked ones have one).
struct FilteredGeometry {
    const Scene* scene = nullptr;
    const Mesh* mesh = nullptr;
    const Material* material = nullptr;
    float winding = 1.0f; // Instance::winding: -1 for a mirroring transform
};

} // namespace

struct RayScene::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<FilteredGeometry> filtered; // sized once, so the user pointers stay valid
    ~Impl()
    {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

namespace {

void throwOnDeviceError(RTCDevice device, const char* what)
{
    RTCError error = rtcGetDeviceError(device);
    require(error == RTC_ERROR_NONE, std::string("Embree: ") + what + " failed (error " + std::to_string(int(error)) + ")");
}

// The intersect context with the ray's Looker (Embree passes it to the filter).
struct LookerContext {
    RTCIntersectContext context; // first: Embree's pointer to it is a pointer to this
    Looker looker = Looker::None;
};

// Embree's intersection and occlusion filter, so closest hits, shadow rays and every sampler see the
// surfaces as the rasterizer draws them:
//  - the back-face rule (Material::doubleSided, Looker): a hit on the side of a single-sided surface
//    the looker does not see is rejected and the ray goes on (Embree's Ng is cross(p1 - p0, p2 - p0)
//    of the world corners; Instance::winding turns it to the front);
//  - alpha masks: a hit where the mask cuts the surface (glsl/shared/alpha_mask.h, at the hit's
//    texture coordinate) is rejected.
void surfaceFilter(const RTCFilterFunctionNArguments* args)
{
    const auto* geometry = static_cast<const FilteredGeometry*>(args->geometryUserPtr);
    const Looker looker = reinterpret_cast<const LookerContext*>(args->context)->looker;
    const bool singleSided = !geometry->material->doubleSided && looker != Looker::None;
    // The sign of dot(front normal, direction) whose hits are absent: > 0 (a back) for Origin.
    const float absentSign = looker == Looker::Origin ? 1.0f : -1.0f;
    const bool masked = geometry->material->isMasked();
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        if (singleSided) {
            const float facing = RTCHitN_Ng_x(args->hit, args->N, i) * RTCRayN_dir_x(args->ray, args->N, i) +
                                 RTCHitN_Ng_y(args->hit, args->N, i) * RTCRayN_dir_y(args->ray, args->N, i) +
                                 RTCHitN_Ng_z(args->hit, args->N, i) * RTCRayN_dir_z(args->ray, args->N, i);
            if (facing * geometry->winding * absentSign > 0.0f) { // the side the looker does not see
                args->valid[i] = 0;
                continue;
            }
        }
        if (!masked) continue;
        const unsigned triangle = RTCHitN_primID(args->hit, args->N, i);
        const glm::vec2 barycentric(RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i));
        if (!alphaMaskKeeps(*geometry->scene, *geometry->material, *geometry->mesh, static_cast<int>(triangle), barycentric))
            args->valid[i] = 0;
    }
}

} // namespace

RayScene::RayScene(const Scene& scene) : mScene(scene), mImpl(std::make_unique<Impl>())
{
    mImpl->device = rtcNewDevice(nullptr);
    require(mImpl->device != nullptr, "Embree: cannot create a device");
    mImpl->scene = rtcNewScene(mImpl->device);
    rtcSetSceneBuildQuality(mImpl->scene, RTC_BUILD_QUALITY_HIGH);
    mImpl->filtered.reserve(scene.instances.size());
    for (std::size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& instance = scene.instances[i];
        const Mesh& mesh = scene.meshes[instance.mesh];
        RTCGeometry geometry = rtcNewGeometry(mImpl->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), mesh.triangleCount()));
        throwOnDeviceError(mImpl->device, "allocating geometry buffers");
        for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
            glm::vec3 p = glm::vec3(instance.worldFromObject * glm::vec4(mesh.vertices[v].position, 1.0f));
            vertices[3 * v + 0] = p.x;
            vertices[3 * v + 1] = p.y;
            vertices[3 * v + 2] = p.z;
        }
        std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
        const Material& material = scene.materials[static_cast<std::size_t>(mesh.material)];
        if (!material.doubleSided || material.isMasked()) {
            mImpl->filtered.push_back({&scene, &mesh, &material, instance.winding()});
            rtcSetGeometryUserData(geometry, &mImpl->filtered.back());
            rtcSetGeometryIntersectFilterFunction(geometry, surfaceFilter);
            rtcSetGeometryOccludedFilterFunction(geometry, surfaceFilter);
        }
        rtcCommitGeometry(geometry);
        rtcAttachGeometryByID(mImpl->scene, geometry, static_cast<unsigned>(i));
        rtcReleaseGeometry(geometry);
    }
    rtcCommitScene(mImpl->scene);
    AABB bounds = scene.worldBounds();
    mSceneScale = bounds.empty() ? 1.0f : std::max(1e-3f, glm::length(bounds.extent()));
    throwOnDeviceError(mImpl->device, "building the scene");
}

RayScene::~RayScene() = default;

namespace {

void fillRay(RTCRay& r, const Ray& ray)
{
    r.org_x = ray.origin.x;
    r.org_y = ray.origin.y;
    r.org_z = ray.origin.z;
    r.dir_x = ray.direction.x;
    r.dir_y = ray.direction.y;
    r.dir_z = ray.direction.z;
    r.tnear = ray.tMin;
    r.tfar = ray.tMax;
    r.time = 0.0f;
    r.mask = 0xFFFFFFFFu;
    r.id = 0;
    r.flags = 0;
}

} // namespace

Hit RayScene::intersect(const Ray& ray, Looker looker) const
{
    if (RayRecorder* recorder = mRecorder.load(std::memory_order_relaxed)) recorder->add(ray, true, looker);
    LookerContext context;
    rtcInitIntersectContext(&context.context);
    context.looker = looker;
    RTCRayHit rayHit;
    fillRay(rayHit.ray, ray);
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(mImpl->scene, &context.context, &rayHit);
    Hit hit;
    if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.t = rayHit.ray.tfar;
    hit.instance = static_cast<int>(rayHit.hit.geomID);
    hit.triangle = static_cast<int>(rayHit.hit.primID);
    hit.barycentric = glm::vec2(rayHit.hit.u, rayHit.hit.v);
    hit.geometricNormal = glm::vec3(rayHit.hit.Ng_x, rayHit.hit.Ng_y, rayHit.hit.Ng_z);
    return hit;
}

bool RayScene::occluded(const Ray& ray, Looker looker) const
{
    if (RayRecorder* recorder = mRecorder.load(std::memory_order_relaxed)) recorder->add(ray, false, looker);
    LookerContext context;
    rtcInitIntersectContext(&context.context);
    context.looker = looker;
    RTCRay r;
    fillRay(r, ray);
    rtcOccluded1(mImpl->scene, &context.context, &r);
    return r.tfar < 0.0f; // Embree sets tfar to -inf on a hit
}

bool RayScene::visible(const glm::vec3& a, const glm::vec3& b, Looker looker) const
{
    Ray ray;
    ray.origin = a;
    ray.direction = b - a;
    ray.tMin = 1e-4f;
    ray.tMax = 1.0f - 1e-4f;
    return !occluded(ray, looker);
}

struct RayRecorder::Impl {
    struct Recorded {
        Ray ray;
        bool closestHit = false;
        Looker looker = Looker::None;
    };
    tbb::enumerable_thread_specific<std::vector<Recorded>> perThread;
};

RayRecorder::RayRecorder() : mImpl(std::make_unique<Impl>()) {}
RayRecorder::~RayRecorder() = default;

void RayRecorder::add(const Ray& ray, bool closestHit, Looker looker)
{
    mImpl->perThread.local().push_back({ray, closestHit, looker});
}

std::size_t RayRecorder::size() const
{
    std::size_t n = 0;
    for (const auto& v : mImpl->perThread) n += v.size();
    return n;
}

void RayRecorder::clear()
{
    for (auto& v : mImpl->perThread) v.clear();
}

double RayRecorder::replay(const RayScene& rays) const
{
    std::vector<Impl::Recorded> all;
    all.reserve(size());
    for (const auto& v : mImpl->perThread) all.insert(all.end(), v.begin(), v.end());
    std::atomic<std::uint64_t> sink{0}; // keeps the results alive
    const auto start = std::chrono::steady_clock::now();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, all.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
        std::uint64_t hits = 0;
        for (std::size_t i = r.begin(); i != r.end(); ++i)
            hits += all[i].closestHit ? (rays.intersect(all[i].ray, all[i].looker).valid() ? 1 : 0)
                                      : (rays.occluded(all[i].ray, all[i].looker) ? 1 : 0);
        sink.fetch_add(hits, std::memory_order_relaxed);
    });
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace vplgi
