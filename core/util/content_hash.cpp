#include "core/util/content_hash.h"

#include <cstdio>
#include <cstdlib>

namespace vplgi {

void Hasher::bytes(const void* data, std::size_t size)
{
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
        mState ^= p[i];
        mState *= 0x100000001b3ull;
    }
}

std::string Hasher::hex() const
{
    char buffer[17];
    std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(mState));
    return buffer;
}

std::string cacheDirectory(const std::string& fallback)
{
    const char* dir = std::getenv("VPLGI_CACHE_DIR");
    return dir && *dir ? std::string(dir) : fallback;
}

std::uint64_t hashSceneContent(const Scene& scene)
{
    Hasher h;
    h.value(scene.meshes.size());
    for (const Mesh& m : scene.meshes) {
        h.value(m.material);
        h.value(m.vertices.size());
        h.bytes(m.vertices.data(), m.vertices.size() * sizeof(Vertex));
        h.value(m.indices.size());
        h.bytes(m.indices.data(), m.indices.size() * sizeof(std::uint32_t));
    }
    h.value(scene.instances.size());
    for (const Instance& i : scene.instances) {
        h.value(i.mesh);
        h.value(i.worldFromObject);
    }
    h.value(scene.materials.size());
    auto texture = [&h](const TextureRef& t) {
        h.value(t.image);
        h.value(t.texCoord);
        h.value(t.offset);
        h.value(t.rotation);
        h.value(t.scale);
    };
    for (const Material& m : scene.materials) {
        h.value(m.baseColor);
        texture(m.baseColorTexture);
        h.value(m.metallic);
        h.value(m.roughness);
        texture(m.metallicRoughnessTexture);
        h.value(m.specular);
        h.value(m.emission);
        texture(m.emissionTexture);
        texture(m.normalTexture);
        h.value(m.normalScale);
        h.value(m.doubleSided);
        h.value(m.alphaMode);
        h.value(m.alphaCutoff);
    }
    h.value(scene.images.size());
    for (const Image& img : scene.images) {
        h.value(img.width);
        h.value(img.height);
        h.bytes(img.rgba.data(), img.rgba.size());
    }
    hashLights(h, scene.lights);
    return h.digest();
}

void hashLights(Hasher& h, const std::vector<Light>& lights)
{
    h.value(lights.size());
    for (const Light& l : lights) {
        h.value(l.type);
        h.value(l.position);
        h.value(l.direction);
        h.value(l.color);
        h.value(l.intensity);
        h.value(l.innerConeAngle);
        h.value(l.outerConeAngle);
    }
}

std::uint64_t hashLights(const std::vector<Light>& lights)
{
    Hasher h;
    hashLights(h, lights);
    return h.digest();
}

void hashCamera(Hasher& h, const Camera& c)
{
    h.value(c.position);
    h.value(c.target);
    h.value(c.up);
    h.value(c.fovY);
}

} // namespace vplgi
