#include "core/scene/direct_lights.h"

#include <algorithm>
#include <cmath>

#include "core/util/error.h"

namespace vplgi {

namespace {

struct EmissiveTriangle {
    glm::vec3 p0, p1, p2;
    glm::vec3 normal;   // geometric, unit, on the emitting side
    glm::vec3 radiance; // [W/(m^2 sr)]
    float area;         // [m^2]
    float power;        // luminance-weighted, used for allocation
};

float luminance(const glm::vec3& c)
{
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

std::vector<EmissiveTriangle> collectEmissiveTriangles(const Scene& scene)
{
    std::vector<EmissiveTriangle> triangles;
    for (const Instance& instance : scene.instances) {
        const Mesh& mesh = scene.meshes[instance.mesh];
        const Material& material = scene.materials[mesh.material];
        if (!material.isEmissive()) continue;
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            EmissiveTriangle tri;
            auto world = [&](std::uint32_t i) {
                return glm::vec3(instance.worldFromObject * glm::vec4(mesh.vertices[i].position, 1.0f));
            };
            tri.p0 = world(mesh.indices[t]);
            tri.p1 = world(mesh.indices[t + 1]);
            tri.p2 = world(mesh.indices[t + 2]);
            glm::vec3 cross = glm::cross(tri.p1 - tri.p0, tri.p2 - tri.p0);
            float twiceArea = glm::length(cross);
            if (!(twiceArea > 0.0f)) continue;
            tri.normal = cross / twiceArea;
            tri.area = 0.5f * twiceArea;
            tri.radiance = material.emission;
            tri.power = luminance(material.emission) * tri.area;
            if (tri.power > 0.0f) triangles.push_back(tri);
        }
    }
    return triangles;
}

// Radical inverse in base 2 with a scramble: a stratified 1D sequence per sample index.
float radicalInverse2(std::uint32_t i, std::uint32_t scramble)
{
    i = (i << 16u) | (i >> 16u);
    i = ((i & 0x55555555u) << 1u) | ((i & 0xAAAAAAAAu) >> 1u);
    i = ((i & 0x33333333u) << 2u) | ((i & 0xCCCCCCCCu) >> 2u);
    i = ((i & 0x0F0F0F0Fu) << 4u) | ((i & 0xF0F0F0F0u) >> 4u);
    i = ((i & 0x00FF00FFu) << 8u) | ((i & 0xFF00FF00u) >> 8u);
    i ^= scramble;
    return static_cast<float>(i) * 2.3283064365386963e-10f;
}

std::uint32_t hash32(std::uint32_t x)
{
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

} // namespace

DirectLightSet buildDirectLights(const Scene& scene, const DirectLightParams& params)
{
    return buildDirectLights(scene, scene.lights, params);
}

DirectLightSet buildDirectLights(const Scene& scene, const std::vector<Light>& lights, const DirectLightParams& params)
{
    require(params.emitterSamples >= 1, "direct.emitterSamples must be >= 1");
    DirectLightSet set;
    for (const Light& light : lights) {
        glm::vec3 intensity = light.radiantIntensity();
        if (light.type == LightType::Directional) {
            shared::DirectionalEmitter e;
            e.direction = glm::vec4(glm::normalize(light.direction), -1.0f);
            e.irradiance = glm::vec4(intensity, 0.0f);
            set.directionals.push_back(e);
            continue;
        }
        shared::PointEmitter e;
        bool spot = light.type == LightType::Spot;
        e.positionProfile = glm::vec4(light.position, float(spot ? shared::kProfileSpot : shared::kProfileIsotropic));
        e.intensity = glm::vec4(intensity, -1.0f);
        glm::vec3 axis = spot ? glm::normalize(light.direction) : glm::vec3(0.0f, -1.0f, 0.0f);
        e.axisCosOuter = glm::vec4(axis, std::cos(light.outerConeAngle));
        e.cosInner = glm::vec4(std::cos(light.innerConeAngle), 0.0f, 0.0f, 0.0f);
        set.points.push_back(e);
    }

    // Emissive triangles: N cosine-emitting point samples. Triangles are chosen by systematic
    // sampling of the power CDF (stratified), positions inside a triangle by a scrambled (i/N, radical
    // inverse) pair; each sample carries Le * area / (N * P_triangle) so that the set's total flux
    // equals the emitters' flux pi * sum(Le * area).
    std::vector<EmissiveTriangle> triangles = collectEmissiveTriangles(scene);
    if (triangles.empty()) return set;
    std::vector<double> cdf(triangles.size());
    double total = 0.0;
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        total += triangles[i].power;
        cdf[i] = total;
    }
    AABB bounds = scene.worldBounds();
    float offset = 1e-4f * std::max(1e-3f, glm::length(bounds.extent())); // lift samples off their surface
    const int n = params.emitterSamples;
    const std::uint32_t scramble = hash32(params.seed * 0x9E3779B9u + 17u);
    const double jitter = hash32(params.seed) * 2.3283064365386963e-10;
    std::vector<std::size_t> chosen(static_cast<std::size_t>(n));
    for (int s = 0; s < n; ++s) {
        double u = (s + jitter) / n * total;
        std::size_t index = static_cast<std::size_t>(std::lower_bound(cdf.begin(), cdf.end(), u) - cdf.begin());
        chosen[s] = std::min(index, triangles.size() - 1);
    }
    // Samples of one triangle are contiguous in s: stratify them inside the triangle by local index.
    for (int first = 0; first < n;) {
        int last = first;
        while (last < n && chosen[last] == chosen[first]) ++last;
        const EmissiveTriangle& tri = triangles[chosen[first]];
        const int count = last - first;
        float probability = tri.power / static_cast<float>(total);
        for (int j = 0; j < count; ++j) {
            float a = (j + 0.5f) / count;
            float b = radicalInverse2(static_cast<std::uint32_t>(j), scramble);
            float sa = std::sqrt(a); // uniform point on the triangle from (a, b) in the unit square
            glm::vec3 p = (1.0f - sa) * tri.p0 + sa * (1.0f - b) * tri.p1 + sa * b * tri.p2;
            shared::PointEmitter e;
            e.positionProfile = glm::vec4(p + offset * tri.normal, float(shared::kProfileCosine));
            e.intensity = glm::vec4(tri.radiance * (tri.area / (n * probability)), -1.0f);
            e.axisCosOuter = glm::vec4(tri.normal, -1.0f);
            e.cosInner = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
            set.points.push_back(e);
        }
        first = last;
    }
    return set;
}

} // namespace vplgi
