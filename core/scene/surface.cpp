#include "core/scene/surface.h"

#include <algorithm>
#include <cmath>

#include "glsl/shared/alpha_mask.h"

namespace vplgi {

namespace {

float srgbToLinear(float c)
{
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

glm::vec4 texel(const Image& image, int x, int y, bool srgb)
{
    x = ((x % image.width) + image.width) % image.width;
    y = ((y % image.height) + image.height) % image.height;
    const std::uint8_t* p = &image.rgba[(static_cast<std::size_t>(y) * image.width + x) * 4];
    glm::vec4 c(p[0], p[1], p[2], p[3]);
    c /= 255.0f;
    if (srgb) c = glm::vec4(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b), c.a);
    return c;
}

// Whether the alpha mask of `m` keeps texel (x, y) of its base colour texture `image`.
bool texelKept(const Material& m, const Image& image, int x, int y)
{
    return shared::alphaMaskKeeps(m.baseColor.a * texel(image, x, y, false).a, m.alphaCutoff);
}

} // namespace

glm::vec4 sampleImage(const Image& image, glm::vec2 uv, bool srgb)
{
    // Texel centres at (i + 0.5) / size, as GL_LINEAR with GL_REPEAT (decode before filtering, as GL
    // does for sRGB textures).
    float x = uv.x * image.width - 0.5f;
    float y = uv.y * image.height - 0.5f;
    int x0 = static_cast<int>(std::floor(x));
    int y0 = static_cast<int>(std::floor(y));
    float fx = x - x0, fy = y - y0;
    glm::vec4 a = glm::mix(texel(image, x0, y0, srgb), texel(image, x0 + 1, y0, srgb), fx);
    glm::vec4 b = glm::mix(texel(image, x0, y0 + 1, srgb), texel(image, x0 + 1, y0 + 1, srgb), fx);
    return glm::mix(a, b, fy);
}

bool alphaMaskKeeps(const Scene& scene, const Material& m, glm::vec2 baseColorUV, float vertexAlpha)
{
    if (!m.isMasked()) return true;
    float alpha = m.baseColor.a * vertexAlpha;
    if (m.baseColorTexture.valid())
        alpha *= sampleImage(scene.images[static_cast<std::size_t>(m.baseColorTexture.image)], baseColorUV, false).a;
    return shared::alphaMaskKeeps(alpha, m.alphaCutoff);
}

bool alphaMaskKeeps(const Scene& scene, const Material& m, const Mesh& mesh, int triangle, glm::vec2 barycentric)
{
    if (!m.isMasked()) return true;
    const std::size_t first = 3 * static_cast<std::size_t>(triangle);
    const Vertex& a = mesh.vertices[mesh.indices[first]];
    const Vertex& b = mesh.vertices[mesh.indices[first + 1]];
    const Vertex& c = mesh.vertices[mesh.indices[first + 2]];
    const float w0 = 1.0f - barycentric.x - barycentric.y, w1 = barycentric.x, w2 = barycentric.y;
    const glm::vec2 uv0 = w0 * a.texcoord + w1 * b.texcoord + w2 * c.texcoord;
    const glm::vec2 uv1 = w0 * a.texcoord1 + w1 * b.texcoord1 + w2 * c.texcoord1;
    return alphaMaskKeeps(scene, m, m.baseColorTexture.uv(uv0, uv1), w0 * a.color.a + w1 * b.color.a + w2 * c.color.a);
}

float alphaCoverage(const Scene& scene, const Material& m)
{
    if (!m.isMasked()) return 1.0f;
    if (!m.baseColorTexture.valid()) return shared::alphaMaskKeeps(m.baseColor.a, m.alphaCutoff) ? 1.0f : 0.0f;
    const Image& image = scene.images[static_cast<std::size_t>(m.baseColorTexture.image)];
    std::size_t kept = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            kept += texelKept(m, image, x, y) ? 1 : 0;
    return static_cast<float>(static_cast<double>(kept) / std::max(1.0, static_cast<double>(image.width) * image.height));
}

UntexturedMaterials computeUntexturedMaterials(const Scene& scene)
{
    UntexturedMaterials table;
    // Mean of a texture's texels (no filtering needed: the mean of a bilinear repeat-wrapped
    // reconstruction is the mean of its texels).
    // (Alpha-masked materials: over the texels of the base colour texture their mask keeps, when the
    // texture has the base colour texture's size; else over all.)
    auto mean = [&](const Material& m, const TextureRef& ref, bool srgb) {
        const Image& image = scene.images[static_cast<std::size_t>(ref.image)];
        const Image* mask = m.isMasked() && m.baseColorTexture.valid()
                                ? &scene.images[static_cast<std::size_t>(m.baseColorTexture.image)]
                                : nullptr;
        if (mask && (mask->width != image.width || mask->height != image.height)) mask = nullptr;
        glm::dvec4 sum(0.0);
        double count = 0.0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x) {
                if (mask && !texelKept(m, *mask, x, y)) continue;
                sum += glm::dvec4(texel(image, x, y, srgb));
                count += 1.0;
            }
        return glm::vec4(sum / std::max(1.0, count));
    };
    // COLOR_0: each material's mean vertex colour, weighted by object-space triangle area (exact
    // for instances without non-uniform scale).
    std::vector<glm::dvec3> colorSum(scene.materials.size(), glm::dvec3(0.0));
    std::vector<double> areaSum(scene.materials.size(), 0.0);
    for (const Mesh& mesh : scene.meshes) {
        const auto k = static_cast<std::size_t>(mesh.material);
        for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            const Vertex& a = mesh.vertices[mesh.indices[t]];
            const Vertex& b = mesh.vertices[mesh.indices[t + 1]];
            const Vertex& c = mesh.vertices[mesh.indices[t + 2]];
            const double area = 0.5 * glm::length(glm::cross(glm::dvec3(b.position - a.position),
                                                              glm::dvec3(c.position - a.position)));
            colorSum[k] += area * glm::dvec3(a.color + b.color + c.color) / 3.0;
            areaSum[k] += area;
        }
    }
    for (const Material& m : scene.materials) {
        const auto k = static_cast<std::size_t>(&m - scene.materials.data());
        glm::vec3 base(m.baseColor);
        if (areaSum[k] > 0.0) base *= glm::vec3(colorSum[k] / areaSum[k]);
        if (m.baseColorTexture.valid()) base *= glm::vec3(mean(m, m.baseColorTexture, true));
        float metallic = m.metallic, roughness = m.roughness;
        if (m.metallicRoughnessTexture.valid()) {
            const glm::vec4 mr = mean(m, m.metallicRoughnessTexture, false);
            roughness *= mr.g;
            metallic *= mr.b;
        }
        table.baseColor.push_back(base);
        table.metallic.push_back(metallic);
        table.roughness.push_back(roughness);
    }
    return table;
}

SurfacePoint surfaceAt(const Scene& scene, const Hit& hit, const glm::vec3& towardsViewer,
                       const UntexturedMaterials* untextured)
{
    const Instance& instance = scene.instances[hit.instance];
    const Mesh& mesh = scene.meshes[instance.mesh];
    const Material& m = scene.materials[mesh.material];
    const Vertex& v0 = mesh.vertices[mesh.indices[3 * hit.triangle]];
    const Vertex& v1 = mesh.vertices[mesh.indices[3 * hit.triangle + 1]];
    const Vertex& v2 = mesh.vertices[mesh.indices[3 * hit.triangle + 2]];
    const float w0 = 1.0f - hit.barycentric.x - hit.barycentric.y;
    const float w1 = hit.barycentric.x, w2 = hit.barycentric.y;
    const glm::mat3 normalFromObject = glm::transpose(glm::inverse(glm::mat3(instance.worldFromObject)));

    SurfacePoint s;
    s.materialIndex = mesh.material;
    glm::vec3 pObject = w0 * v0.position + w1 * v1.position + w2 * v2.position;
    s.position = glm::vec3(instance.worldFromObject * glm::vec4(pObject, 1.0f));
    s.texcoord = w0 * v0.texcoord + w1 * v1.texcoord + w2 * v2.texcoord;
    s.texcoord1 = w0 * v0.texcoord1 + w1 * v1.texcoord1 + w2 * v2.texcoord1;
    const glm::vec4 vertexColor = w0 * v0.color + w1 * v1.color + w2 * v2.color;
    auto sample = [&](const TextureRef& ref, bool srgb) {
        return sampleImage(scene.images[static_cast<std::size_t>(ref.image)], ref.uv(s.texcoord, s.texcoord1), srgb);
    };
    s.geometricNormal = glm::normalize(hit.geometricNormal);
    glm::vec3 n = glm::normalize(normalFromObject * (w0 * v0.normal + w1 * v1.normal + w2 * v2.normal));

    if (m.normalTexture.valid() && mesh.hasTangents && !untextured) {
        glm::vec4 t4 = w0 * v0.tangent + w1 * v1.tangent + w2 * v2.tangent;
        glm::vec3 t = glm::normalize(glm::mat3(instance.worldFromObject) * glm::vec3(t4));
        t = glm::normalize(t - n * glm::dot(n, t));
        glm::vec3 b = glm::cross(n, t) * (t4.w < 0.0f ? -1.0f : 1.0f);
        glm::vec3 tn = glm::vec3(sample(m.normalTexture, false)) * 2.0f - 1.0f;
        tn.x *= m.normalScale;
        tn.y *= m.normalScale;
        n = glm::normalize(t * tn.x + b * tn.y + n * tn.z);
    }
    // Double-sided materials are shaded on the side the viewer sees (as the G-buffer pass does).
    if (m.doubleSided && glm::dot(s.geometricNormal, towardsViewer) < 0.0f) {
        s.geometricNormal = -s.geometricNormal;
        n = -n;
    }
    // Keep the geometric normal on the shading normal's side.
    if (glm::dot(s.geometricNormal, n) < 0.0f) s.geometricNormal = -s.geometricNormal;
    s.normal = n;

    if (untextured) {
        const auto index = static_cast<std::size_t>(mesh.material);
        s.material.baseColor = untextured->baseColor[index];
        s.material.metallic = untextured->metallic[index];
        s.material.roughness = untextured->roughness[index];
    } else {
        glm::vec4 base = m.baseColor * vertexColor;
        if (m.baseColorTexture.valid()) base *= sample(m.baseColorTexture, true);
        float metallic = m.metallic, roughness = m.roughness;
        if (m.metallicRoughnessTexture.valid()) {
            glm::vec4 mr = sample(m.metallicRoughnessTexture, false);
            roughness *= mr.g;
            metallic *= mr.b;
        }
        s.material.baseColor = glm::vec3(base);
        s.material.metallic = metallic;
        s.material.roughness = roughness;
    }
    s.material.specular = m.specular;
    s.emission = m.emission;
    if (m.emissionTexture.valid())
        s.emission *= glm::vec3(sample(m.emissionTexture, true));
    return s;
}

glm::vec3 evaluateDirectLight(const RayScene& rays, const DirectLightSet& lights, const SurfacePoint& point,
                              const glm::vec3& wo, std::uint64_t* shadowRays)
{
    std::uint64_t cast = 0;
    const glm::vec3 origin = point.position + point.geometricNormal * (1e-4f * rays.sceneScale());
    glm::vec3 radiance(0.0f);
    for (const shared::PointEmitter& e : lights.points) {
        glm::vec3 toLight = glm::vec3(e.positionProfile) - point.position;
        float distance2 = glm::dot(toLight, toLight);
        if (!(distance2 > 0.0f)) continue;
        glm::vec3 wi = toLight / std::sqrt(distance2);
        float cosine = glm::dot(point.normal, wi);
        if (cosine <= 0.0f) continue;
        float profile = shared::emitterProfile(e, -wi);
        if (profile <= 0.0f) continue;
        ++cast;
        if (!rays.visible(origin, glm::vec3(e.positionProfile), Looker::End)) continue; // the light looks
        glm::vec3 f = shared::evaluateBRDF(point.material, point.normal, wo, wi);
        radiance += f * glm::vec3(e.intensity) * profile * cosine / distance2;
    }
    for (const shared::DirectionalEmitter& d : lights.directionals) {
        glm::vec3 wi = -glm::vec3(d.direction);
        float cosine = glm::dot(point.normal, wi);
        if (cosine <= 0.0f) continue;
        Ray shadow;
        shadow.origin = origin;
        shadow.direction = wi;
        shadow.tMin = 0.0f;
        ++cast;
        if (rays.occluded(shadow, Looker::End)) continue; // the light looks
        glm::vec3 f = shared::evaluateBRDF(point.material, point.normal, wo, wi);
        radiance += f * glm::vec3(d.irradiance) * cosine;
    }
    if (shadowRays) *shadowRays += cast;
    return radiance;
}

} // namespace vplgi
