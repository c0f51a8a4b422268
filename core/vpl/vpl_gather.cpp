#include "core/vpl/vpl_gather.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "glsl/shared/vpl.h"

namespace vplgi {

float clampGeometryFor(float clampScale, int vplCount, float sceneDiagonal)
{
    if (!(clampScale > 0.0f) || !(sceneDiagonal > 0.0f) || vplCount < 1) return 0.0f;
    const float d = clampScale * sceneDiagonal / std::sqrt(static_cast<float>(vplCount));
    return 1.0f / (d * d);
}

void configureVPLReference(bool texturedVPLs, float clampGeometry, int vplBounces, int diffuseVertices,
                           PathTracerParams& reference, const std::set<std::string>& explicitKeys)
{
    if (!explicitKeys.count("reference.diffuseVertices")) reference.diffuseVertices = diffuseVertices;
    if (!explicitKeys.count("reference.untexturedBounces")) reference.untexturedBounces = !texturedVPLs;
    if (!explicitKeys.count("reference.clampGeometry") && clampGeometry > 0.0f) reference.clampGeometry = clampGeometry;
    if (!explicitKeys.count("reference.maxDepth")) reference.maxDepth = 1 + vplBounces;
}

glm::vec3 gatherVPLs(const RayScene& rays, const VPLSet& vpls, const SurfacePoint& point, const glm::vec3& wo,
                     const VPLGatherParams& params, int subset)
{
    // 1/n with n the number of valid VPLs, the same n the densities are normalised by (core/vpl/vpl.h).
    const std::size_t n = vpls.validCount();
    if (n == 0) return glm::vec3(0.0f);
    const float offset = 1e-4f * rays.sceneScale();
    const glm::vec3 origin = point.position + point.geometricNormal * offset;
    const int tile = std::max(params.interleaveTile, 1);
    const std::size_t classes = static_cast<std::size_t>(tile) * static_cast<std::size_t>(tile);
    glm::vec3 sum(0.0f);
    for (std::size_t i = static_cast<std::size_t>(subset); i < vpls.slots.size(); i += classes) {
        const VPL& vpl = vpls.slots[i];
        if (!vpl.valid || !(vpl.density > 0.0f)) continue;
        const glm::vec3 toVPL = vpl.position - point.position;
        const float distance2 = glm::dot(toVPL, toVPL);
        if (!(distance2 > 0.0f)) continue;
        const glm::vec3 wi = toVPL / std::sqrt(distance2);
        // Below the shading point's triangle: nothing, as the path tracer and the GPU shading
        // (glsl/passes/vpl_shading.frag, the G-buffer's geometric normal) drop it.
        if (glm::dot(point.geometricNormal, wi) <= 0.0f) continue;
        const float cosX = glm::dot(point.normal, wi);
        const float cosY = -glm::dot(vpl.normal, wi);
        if (cosX <= 0.0f || cosY <= 0.0f) continue;
        float geometry = cosX * cosY / distance2;
        if (params.clampGeometry > 0.0f) geometry = std::min(geometry, params.clampGeometry);
        // Visibility between the shading point and the VPL, both ends lifted off their surfaces.
        if (!rays.visible(origin, vpl.position + vpl.normal * offset, Looker::End)) continue; // the VPL looks
        sum += shared::evaluateBRDF(point.material, point.normal, wo, wi) * geometry * vpl.intensity();
    }
    // tile^2 / n (glsl/shared/vpl.h); the division keeps tile = 1 bit-identical to earlier releases.
    return tile == 1 ? sum / static_cast<float>(n) : sum * shared::vplEstimatorScale(static_cast<int>(n), tile);
}

ImageRGBA32F renderVPLGather(const Scene& scene, const RayScene& rays, const Camera& camera, int width, int height,
                             const VPLSet& vpls, const VPLGatherParams& params)
{
    ImageRGBA32F image;
    image.width = width;
    image.height = height;
    image.pixels.assign(static_cast<std::size_t>(width) * height * 4, 0.0f);
    const glm::mat4 worldFromClip =
        glm::inverse(camera.clipFromView(static_cast<float>(width) / static_cast<float>(height)) * camera.viewFromWorld());
    tbb::parallel_for(0, height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            // The pixel centre, as the rasterizer samples it.
            const glm::vec2 ndc((x + 0.5f) / width * 2.0f - 1.0f, 1.0f - (y + 0.5f) / height * 2.0f);
            const glm::vec4 nearPoint = worldFromClip * glm::vec4(ndc, -1.0f, 1.0f);
            const glm::vec4 farPoint = worldFromClip * glm::vec4(ndc, 1.0f, 1.0f);
            Ray ray;
            ray.origin = glm::vec3(nearPoint) / nearPoint.w;
            ray.direction = glm::normalize(glm::vec3(farPoint) / farPoint.w - ray.origin);
            float* out = image.at(x, y);
            out[3] = 1.0f;
            const Hit hit = rays.intersect(ray, Looker::Origin); // the camera
            if (!hit.valid()) continue;
            const SurfacePoint s = surfaceAt(scene, hit, -ray.direction);
            const int tile = std::max(params.interleaveTile, 1);
            const int subset = shared::vplInterleaveClass(glm::ivec2(x, height - 1 - y), tile);
            const glm::vec3 value = gatherVPLs(rays, vpls, s, -ray.direction, params, subset);
            out[0] = value.r;
            out[1] = value.g;
            out[2] = value.b;
        }
    });
    return image;
}

} // namespace vplgi
