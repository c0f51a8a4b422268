// Small scenes the image tests build in code (no files): quads with one material each, and the
// unoccluded corner the RSM-based techniques are checked on against the path tracer.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/scene/scene.h"
#include "core/scene/surface.h"
#include "core/trace/path_tracer.h"
#include "core/trace/ray_scene.h"
#include "core/util/image_io.h"

namespace vplgi::test {

// Adds a material of this albedo (specular factor, perceptual roughness) and returns its index.
inline int addTestMaterial(Scene& scene, const std::string& name, glm::vec3 albedo, float specular = 0.0f,
                           float roughness = 1.0f)
{
    Material m;
    m.name = name;
    m.baseColor = glm::vec4(albedo, 1.0f);
    m.specular = specular;
    m.roughness = roughness;
    scene.materials.push_back(m);
    return static_cast<int>(scene.materials.size()) - 1;
}

// Adds the quad origin + [0,1] edgeU + [0,1] edgeV (two triangles, one instance), facing edgeU x edgeV.
inline void addTestQuad(Scene& scene, int material, glm::vec3 origin, glm::vec3 edgeU, glm::vec3 edgeV)
{
    Mesh mesh;
    const glm::vec3 n = glm::normalize(glm::cross(edgeU, edgeV));
    for (glm::vec3 corner : {origin, origin + edgeU, origin + edgeU + edgeV, origin + edgeV}) {
        Vertex v;
        v.position = corner;
        v.normal = n;
        mesh.vertices.push_back(v);
    }
    mesh.indices = {0, 1, 2, 0, 2, 3};
    mesh.material = material;
    scene.meshes.push_back(mesh);
    scene.instances.push_back(Instance{static_cast<int>(scene.meshes.size()) - 1, glm::mat4(1.0f)});
}

// A spot light; cone angles in radians.
inline Light makeTestSpot(const std::string& name, glm::vec3 position, glm::vec3 direction, float intensity,
                          float innerConeAngle, float outerConeAngle)
{
    Light spot;
    spot.name = name;
    spot.type = LightType::Spot;
    spot.position = position;
    spot.direction = glm::normalize(direction);
    spot.intensity = intensity;
    spot.innerConeAngle = innerConeAngle;
    spot.outerConeAngle = outerConeAngle;
    return spot;
}

// Adds a camera at `position` looking at `target` (the Camera defaults otherwise).
inline void addTestCamera(Scene& scene, const std::string& name, glm::vec3 position, glm::vec3 target)
{
    Camera camera;
    camera.name = name;
    camera.position = position;
    camera.target = target;
    scene.cameras.push_back(camera);
}

// An unoccluded L: a floor and a wall meeting at x = -1, and a spot light on the floor near the
// wall; every surface point sees every other unoccluded, so visibility can be off. `specular` and
// `roughness` are both materials' (0 and 1: Lambertian).
inline Scene cornerScene(float specular, float roughness)
{
    Scene scene;
    scene.name = "corner";
    addTestQuad(scene, addTestMaterial(scene, "floor", glm::vec3(0.7f, 0.7f, 0.7f), specular, roughness),
                {-1.0f, 0.0f, 1.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -2.0f});
    addTestQuad(scene, addTestMaterial(scene, "wall", glm::vec3(0.8f, 0.4f, 0.3f), specular, roughness),
                {-1.0f, 0.0f, -1.0f}, {0.0f, 2.0f, 0.0f}, {0.0f, 0.0f, 2.0f});
    scene.lights.push_back(makeTestSpot("spot", {0.6f, 1.6f, 0.0f}, {-0.9f, -1.6f, 0.0f}, 6.0f, 0.3f, 0.45f));
    addTestCamera(scene, "corner", {2.0f, 1.3f, 2.0f}, {-0.4f, 0.5f, 0.0f});
    scene.validate();
    return scene;
}

// Glossy indirect light with diffuse senders: a Lambertian wall lit by a spot that misses the floor,
// and a glossy metal floor (GGX, roughness 0.3) that reflects the lit wall towards the camera. Only the
// wall sends one-bounce light, so the techniques whose virtual lights are diffuse emitters (VPLs from
// SMCIR, IR or a BRSM) estimate the same one-bounce transport as the path tracer; the floor's glossy
// BRDF is evaluated at the receiver, where every technique uses the full material. Unoccluded.
inline Scene glossyFloorScene()
{
    Scene scene;
    scene.name = "glossy floor";
    const int floor = addTestMaterial(scene, "floor", glm::vec3(0.6f, 0.6f, 0.6f), 1.0f, 0.3f);
    scene.materials[static_cast<std::size_t>(floor)].metallic = 1.0f; // all glossy: F0 = 0.6, no diffuse lobe
    addTestQuad(scene, floor, {-1.0f, 0.0f, 1.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -2.0f});
    addTestQuad(scene, addTestMaterial(scene, "wall", glm::vec3(0.8f, 0.4f, 0.3f)),
                {-1.0f, 0.0f, -1.0f}, {0.0f, 2.0f, 0.0f}, {0.0f, 0.0f, 2.0f});
    // Aimed across at the wall: its cone (0.45 rad) reaches the wall above y = 0.2 and never the floor.
    scene.lights.push_back(makeTestSpot("spot", {0.8f, 1.0f, 0.0f}, {-1.0f, 0.05f, 0.0f}, 6.0f, 0.3f, 0.45f));
    addTestCamera(scene, "glossy floor", {1.8f, 0.9f, 0.6f}, {-0.6f, 0.15f, 0.0f});
    scene.validate();
    return scene;
}

// The path tracer's direct light at pixel centres, as the rasteriser samples them. For punctual
// lights every sample through a pixel centre gives the same value: 4 spp.
inline ImageRGBA32F directReference(const Scene& scene, const Camera& camera, int width, int height)
{
    RayScene rays(scene);
    PathTracerParams params;
    params.mode = PathTracerParams::Mode::Direct;
    params.spp = 4;
    params.jitterPixels = false;
    return renderReference(scene, rays, camera, width, height, params).image;
}

// The one-bounce path tracer (what RSM techniques estimate) at pixel centres, as the rasteriser.
inline ImageRGBA32F oneBounceReference(const Scene& scene, const Camera& camera, int width, int height, int spp,
                                       std::uint32_t seed = 1)
{
    RayScene rays(scene);
    PathTracerParams params;
    params.mode = PathTracerParams::Mode::OneBounce;
    params.spp = spp;
    params.seed = seed;
    params.jitterPixels = false;
    return renderReference(scene, rays, camera, width, height, params).image;
}

// The pixels whose primary hit (through the pixel centre) is a downward-facing surface that does not
// emit: a box's ceiling, which sees no light but bounced light when the lights hang below it or are
// the ceiling's own emitter.
inline std::vector<glm::ivec2> ceilingPixels(const Scene& scene, const Camera& camera, int width, int height)
{
    RayScene rays(scene);
    const CameraRays cameraRays(camera, width, height);
    std::vector<glm::ivec2> pixels;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const Ray ray = cameraRays.at(x + 0.5, y + 0.5);
            const Hit hit = rays.intersect(ray);
            if (!hit.valid()) continue;
            const SurfacePoint s = surfaceAt(scene, hit, -ray.direction);
            if (s.normal.y > -0.9f || glm::dot(s.emission, glm::vec3(1.0f)) > 0.0f) continue;
            pixels.emplace_back(x, y);
        }
    return pixels;
}

// Luminance (Rec. 709) of one RGB(A) pixel.
inline double pixelLuminance(const float* p)
{
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// G_max = 1/d^2, d = clampScale D / sqrt(I) with the default clampScale 2 (smcir's and ir's rule,
// written out here rather than read from the technique: a test of the GPU side against the CPU
// gather then also checks that the technique uses this rule).
inline float vplClampGeometry(const RayScene& rays, int vplCount)
{
    const float d = 2.0f * rays.sceneScale() / std::sqrt(static_cast<float>(vplCount));
    return 1.0f / (d * d);
}

// Mean luminance (Rec. 709) over the pixels of an image; 0 for an empty one.
inline double meanLuminance(const ImageRGBA32F& image)
{
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i + 3 < image.pixels.size(); i += 4, ++n)
        sum += 0.2126 * image.pixels[i] + 0.7152 * image.pixels[i + 1] + 0.0722 * image.pixels[i + 2];
    return n ? sum / static_cast<double>(n) : 0.0;
}

// Mean over pixels of |a - b| (luminance) relative to the mean luminance of b.
inline double relativeL1(const ImageRGBA32F& a, const ImageRGBA32F& b)
{
    double sum = 0.0, sumB = 0.0;
    for (std::size_t i = 0; i + 3 < a.pixels.size(); i += 4) {
        sum += std::abs(pixelLuminance(&a.pixels[i]) - pixelLuminance(&b.pixels[i]));
        sumB += pixelLuminance(&b.pixels[i]);
    }
    return sumB > 0.0 ? sum / sumB : 0.0;
}

} // namespace vplgi::test
