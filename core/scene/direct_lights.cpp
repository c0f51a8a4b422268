#include "core/scene/direct_lights.h"

#include <algorithm>
#include <cmath>

#include "core/util/error.h"
#include "glsl/shared/tonemap.h"

namespace vplgi {

namespace {

struct EmissiveTriangle {
    glm::vec3 p0, p1, p2;
    glm::vec3 normal;   // geometric, unit, on the emitting side
    glm::vec3 radiance; // [W/(m^2 sr)]
    float area;         // [m^2]
    float power;        // luminance-weighted, used for allocation
};

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
            tri.normal = instance.winding() * cross / twiceArea; // the emitting front (Instance::winding)
            tri.area = 0.5f * twiceArea;
            tri.radiance = material.emission;
            tri.power = shared::luminanceRec709(material.emission) * tri.area;
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

std::vector<shared::PointEmitter> groupCosineEmitters(const DirectLightSet& lights, int maxGroups)
{
    std::vector<const shared::PointEmitter*> samples;
    for (const shared::PointEmitter& e : lights.points)
        if (static_cast<int>(e.positionProfile.w + 0.5f) == shared::kProfileCosine) samples.push_back(&e);
    if (samples.empty() || maxGroups <= 0) return {};
    const std::size_t n = samples.size();
    std::vector<double> weight(n);
    glm::dvec3 lower(1e30), upper(-1e30);
    for (std::size_t i = 0; i < n; ++i) {
        weight[i] = std::max(1e-30, static_cast<double>(shared::luminanceRec709(glm::vec3(samples[i]->intensity))));
        lower = glm::min(lower, glm::dvec3(samples[i]->positionProfile));
        upper = glm::max(upper, glm::dvec3(samples[i]->positionProfile));
    }
    // Distance between samples: positions over the emitters' extent, plus the normals' difference
    // (half the weight of the whole extent for opposite normals), so that a lamp's faces part first.
    const double extent2 = std::max(1e-12, glm::dot(upper - lower, upper - lower));
    auto distance2 = [&](const glm::dvec3& p, const glm::dvec3& nrm, std::size_t i) {
        const glm::dvec3 dp = glm::dvec3(samples[i]->positionProfile) - p;
        const glm::dvec3 dn = glm::dvec3(samples[i]->axisCosOuter) - nrm;
        return glm::dot(dp, dp) / extent2 + 0.125 * glm::dot(dn, dn);
    };
    // Seeds: the most powerful sample, then each time the sample with the largest power x squared
    // distance to its nearest seed (ties to the lower index: deterministic).
    std::vector<glm::dvec3> centre, normal;
    const std::size_t k = std::min(n, static_cast<std::size_t>(maxGroups));
    std::size_t first = static_cast<std::size_t>(std::max_element(weight.begin(), weight.end()) - weight.begin());
    centre.push_back(glm::dvec3(samples[first]->positionProfile));
    normal.push_back(glm::dvec3(samples[first]->axisCosOuter));
    std::vector<double> nearest(n, 1e300);
    while (centre.size() < k) {
        std::size_t best = n;
        double bestScore = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
            nearest[i] = std::min(nearest[i], distance2(centre.back(), normal.back(), i));
            const double score = weight[i] * nearest[i];
            if (score > bestScore) bestScore = score, best = i;
        }
        if (best == n) break; // every sample coincides with a seed: fewer groups
        centre.push_back(glm::dvec3(samples[best]->positionProfile));
        normal.push_back(glm::dvec3(samples[best]->axisCosOuter));
    }
    std::vector<std::size_t> group(n, 0);
    for (int step = 0; step < 8; ++step) {
        for (std::size_t i = 0; i < n; ++i) {
            double bestD = 1e300;
            for (std::size_t g = 0; g < centre.size(); ++g) {
                const double d = distance2(centre[g], normal[g], i);
                if (d < bestD) bestD = d, group[i] = g;
            }
        }
        std::vector<glm::dvec3> sumP(centre.size(), glm::dvec3(0.0)), sumN(centre.size(), glm::dvec3(0.0));
        std::vector<double> sumW(centre.size(), 0.0);
        for (std::size_t i = 0; i < n; ++i) {
            sumP[group[i]] += weight[i] * glm::dvec3(samples[i]->positionProfile);
            sumN[group[i]] += weight[i] * glm::dvec3(samples[i]->axisCosOuter);
            sumW[group[i]] += weight[i];
        }
        for (std::size_t g = 0; g < centre.size(); ++g)
            if (sumW[g] > 0.0) {
                centre[g] = sumP[g] / sumW[g];
                normal[g] = sumN[g] / sumW[g];
            }
    }
    std::vector<shared::PointEmitter> groups;
    for (std::size_t g = 0; g < centre.size(); ++g) {
        glm::dvec3 intensity(0.0), axis(0.0);
        bool any = false;
        for (std::size_t i = 0; i < n; ++i) {
            if (group[i] != g) continue;
            intensity += glm::dvec3(samples[i]->intensity);
            axis += weight[i] * glm::dvec3(samples[i]->axisCosOuter);
            any = true;
        }
        if (!any) continue;
        shared::PointEmitter e;
        e.positionProfile = glm::vec4(glm::vec3(centre[g]), float(shared::kProfileCosine));
        e.intensity = glm::vec4(glm::vec3(intensity), -1.0f);
        const double length = glm::length(axis);
        e.axisCosOuter = glm::vec4(length > 0.0 ? glm::vec3(axis / length) : glm::vec3(0.0f, -1.0f, 0.0f), -1.0f);
        e.cosInner = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
        groups.push_back(e);
    }
    return groups;
}

} // namespace vplgi
