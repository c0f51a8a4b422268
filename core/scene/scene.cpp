#include "core/scene/scene.h"

#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/util/error.h"

namespace vplgi {

glm::mat4 Camera::viewFromWorld() const
{
    return glm::lookAt(position, target, up);
}

glm::mat4 Camera::clipFromView(float aspect) const
{
    return glm::perspective(fovY, aspect, zNear, zFar);
}

std::size_t Scene::triangleCount() const
{
    std::size_t count = 0;
    for (const Instance& instance : instances) count += meshes[instance.mesh].triangleCount();
    return count;
}

AABB Scene::worldBounds() const
{
    AABB bounds;
    for (const Instance& instance : instances) {
        for (const Vertex& v : meshes[instance.mesh].vertices)
            bounds.extend(glm::vec3(instance.worldFromObject * glm::vec4(v.position, 1.0f)));
    }
    return bounds;
}

const Camera* Scene::findCamera(const std::string& cameraName) const
{
    for (const Camera& c : cameras)
        if (c.name == cameraName) return &c;
    return nullptr;
}

const Light* Scene::findLight(const std::string& lightName) const
{
    for (const Light& l : lights)
        if (l.name == lightName) return &l;
    return nullptr;
}

namespace {

bool finite3(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void checkTexture(const Scene& scene, const TextureRef& ref, const std::string& what)
{
    require(ref.image < static_cast<int>(scene.images.size()),
            what + ": image index " + std::to_string(ref.image) + " out of range");
    require(ref.texCoord == 0 || ref.texCoord == 1, what + ": texture coordinate set " + std::to_string(ref.texCoord) +
                                                        " is not 0 or 1");
}

} // namespace

void Scene::validate() const
{
    const std::string prefix = (source.empty() ? name : source) + ": ";
    for (std::size_t i = 0; i < images.size(); ++i) {
        const Image& img = images[i];
        require(img.width > 0 && img.height > 0 &&
                    img.rgba.size() == static_cast<std::size_t>(img.width) * img.height * 4,
                prefix + "image " + std::to_string(i) + " has inconsistent size");
    }
    for (std::size_t i = 0; i < materials.size(); ++i) {
        const Material& m = materials[i];
        const std::string what = prefix + "material " + std::to_string(i) + " (" + m.name + ")";
        require(m.metallic >= 0.0f && m.metallic <= 1.0f, what + ": metallic must be in [0,1]");
        require(m.roughness >= 0.0f && m.roughness <= 1.0f, what + ": roughness must be in [0,1]");
        require(finite3(m.emission) && m.emission.r >= 0.0f && m.emission.g >= 0.0f && m.emission.b >= 0.0f,
                what + ": emission must be finite and >= 0");
        checkTexture(*this, m.baseColorTexture, what);
        checkTexture(*this, m.metallicRoughnessTexture, what);
        checkTexture(*this, m.emissionTexture, what);
        checkTexture(*this, m.normalTexture, what);
    }
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        const Mesh& mesh = meshes[i];
        const std::string what = prefix + "mesh " + std::to_string(i) + " (" + mesh.name + ")";
        require(mesh.indices.size() % 3 == 0, what + ": index count is not a multiple of 3");
        require(mesh.material >= 0 && mesh.material < static_cast<int>(materials.size()),
                what + ": material index out of range");
        // Per element: the message is built only on failure (require() would build it per vertex,
        // which made validate() the bulk of loading a large scene).
        for (std::uint32_t index : mesh.indices)
            if (index >= mesh.vertices.size()) throw Error(what + ": vertex index out of range");
        for (const Vertex& v : mesh.vertices)
            if (!(finite3(v.position) && finite3(v.normal))) throw Error(what + ": non-finite vertex");
    }
    for (std::size_t i = 0; i < instances.size(); ++i)
        require(instances[i].mesh >= 0 && instances[i].mesh < static_cast<int>(meshes.size()),
                prefix + "instance " + std::to_string(i) + ": mesh index out of range");
    for (std::size_t i = 0; i < lights.size(); ++i) {
        const Light& l = lights[i];
        const std::string what = prefix + "light " + std::to_string(i) + " (" + l.name + ")";
        require(std::isfinite(l.intensity) && l.intensity >= 0.0f, what + ": intensity must be >= 0");
        require(finite3(l.color) && l.color.r >= 0.0f && l.color.g >= 0.0f && l.color.b >= 0.0f,
                what + ": color must be >= 0");
        require(finite3(l.position) && finite3(l.direction), what + ": non-finite position or direction");
        if (l.type != LightType::Point)
            require(glm::length(l.direction) > 0.0f, what + ": direction must not be zero");
        if (l.type == LightType::Spot)
            require(l.innerConeAngle >= 0.0f && l.innerConeAngle <= l.outerConeAngle &&
                        l.outerConeAngle <= 1.5707964f,
                    what + ": need 0 <= innerConeAngle <= outerConeAngle <= pi/2");
    }
    for (std::size_t i = 0; i < cameras.size(); ++i) {
        const Camera& c = cameras[i];
        const std::string what = prefix + "camera " + std::to_string(i) + " (" + c.name + ")";
        require(finite3(c.position) && finite3(c.target) && glm::length(c.target - c.position) > 0.0f,
                what + ": position and target must be finite and distinct");
        require(c.fovY > 0.0f && c.fovY < 3.1f, what + ": fovY must be in (0, pi)");
        require(c.zNear > 0.0f && c.zFar > c.zNear, what + ": need 0 < zNear < zFar");
    }
    for (const Animation& a : animations) {
        const std::string what = prefix + "animation " + a.name;
        require(!a.keys.empty(), what + ": needs at least one key");
        for (std::size_t k = 1; k < a.keys.size(); ++k)
            require(a.keys[k].time > a.keys[k - 1].time, what + ": key times must increase");
        if (a.targetKind == Animation::Target::Camera)
            require(findCamera(a.targetName) != nullptr, what + ": no camera named " + a.targetName);
        else
            require(findLight(a.targetName) != nullptr, what + ": no light named " + a.targetName);
    }
}

void generateNormals(Mesh& mesh)
{
    for (Vertex& v : mesh.vertices) v.normal = glm::vec3(0.0f);
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        Vertex& a = mesh.vertices[mesh.indices[t]];
        Vertex& b = mesh.vertices[mesh.indices[t + 1]];
        Vertex& c = mesh.vertices[mesh.indices[t + 2]];
        // The cross product's length is twice the area: area-weighted accumulation.
        glm::vec3 n = glm::cross(b.position - a.position, c.position - a.position);
        a.normal += n;
        b.normal += n;
        c.normal += n;
    }
    for (Vertex& v : mesh.vertices) {
        float len = glm::length(v.normal);
        v.normal = len > 0.0f ? v.normal / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

void generateTangents(Mesh& mesh, const TextureRef& normalTexture)
{
    std::vector<glm::vec3> tan(mesh.vertices.size(), glm::vec3(0.0f));
    std::vector<glm::vec3> bitan(mesh.vertices.size(), glm::vec3(0.0f));
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
        const Vertex &a = mesh.vertices[i0], &b = mesh.vertices[i1], &c = mesh.vertices[i2];
        glm::vec3 e1 = b.position - a.position, e2 = c.position - a.position;
        // In the normal texture's UVs (its set and transform), so that a rotated or scaled normal map
        // gets the frame it was painted in.
        const glm::vec2 ta = normalTexture.uv(a.texcoord, a.texcoord1);
        glm::vec2 d1 = normalTexture.uv(b.texcoord, b.texcoord1) - ta, d2 = normalTexture.uv(c.texcoord, c.texcoord1) - ta;
        float det = d1.x * d2.y - d2.x * d1.y;
        if (std::abs(det) < 1e-20f) continue;
        float r = 1.0f / det;
        glm::vec3 sdir = (e1 * d2.y - e2 * d1.y) * r;
        glm::vec3 tdir = (e2 * d1.x - e1 * d2.x) * r;
        for (std::uint32_t i : {i0, i1, i2}) {
            tan[i] += sdir;
            bitan[i] += tdir;
        }
    }
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
        Vertex& v = mesh.vertices[i];
        // Gram-Schmidt against the normal; fall back to any perpendicular vector.
        glm::vec3 t = tan[i] - v.normal * glm::dot(v.normal, tan[i]);
        if (glm::length(t) < 1e-12f) {
            glm::vec3 helper = std::abs(v.normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
            t = glm::cross(helper, v.normal);
        }
        t = glm::normalize(t);
        float sign = glm::dot(glm::cross(v.normal, t), bitan[i]) < 0.0f ? -1.0f : 1.0f;
        v.tangent = glm::vec4(t, sign);
    }
    mesh.hasTangents = true;
}

double instanceSurfaceArea(const Scene& scene, const Instance& instance)
{
    double area = 0.0;
    const Mesh& mesh = scene.meshes[static_cast<std::size_t>(instance.mesh)];
    const glm::dmat4 m(instance.worldFromObject);
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        glm::dvec3 p[3];
        for (int k = 0; k < 3; ++k)
            p[k] = glm::dvec3(
                m * glm::dvec4(glm::dvec3(mesh.vertices[mesh.indices[t + static_cast<std::size_t>(k)]].position), 1.0));
        area += 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
    }
    return area;
}

double sceneSurfaceArea(const Scene& scene)
{
    double area = 0.0;
    for (const Instance& instance : scene.instances) area += instanceSurfaceArea(scene, instance);
    return area;
}

Camera makeDefaultCamera(const AABB& bounds)
{
    Camera camera;
    camera.name = "default";
    glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
    float radius = bounds.empty() ? 1.0f : 0.5f * glm::length(bounds.extent());
    radius = std::max(radius, 1e-3f);
    camera.fovY = 0.8f;
    float distance = radius / std::sin(0.5f * camera.fovY);
    camera.target = center;
    camera.position = center + glm::normalize(glm::vec3(0.3f, 0.35f, 1.0f)) * distance;
    camera.zNear = std::max(1e-3f, distance - 2.0f * radius) * 0.5f;
    camera.zFar = distance + 2.0f * radius;
    return camera;
}

void applyAnimation(Scene& scene, const Animation& animation, float time)
{
    if (animation.keys.empty()) return;
    const std::vector<Keyframe>& keys = animation.keys;
    Keyframe k = keys.front();
    if (time >= keys.back().time) {
        k = keys.back();
    } else if (time > keys.front().time) {
        std::size_t i = 1;
        while (keys[i].time < time) ++i;
        const Keyframe& a = keys[i - 1];
        const Keyframe& b = keys[i];
        float s = (time - a.time) / (b.time - a.time);
        k.position = glm::mix(a.position, b.position, s);
        k.target = glm::mix(a.target, b.target, s);
    }
    if (animation.targetKind == Animation::Target::Camera) {
        for (Camera& c : scene.cameras)
            if (c.name == animation.targetName) {
                c.position = k.position;
                c.target = k.target;
            }
    } else {
        for (Light& l : scene.lights)
            if (l.name == animation.targetName) {
                l.position = k.position;
                glm::vec3 aim = k.target - k.position;
                if (l.type != LightType::Point && glm::length(aim) > 0.0f) l.direction = glm::normalize(aim);
            }
    }
}

} // namespace vplgi
