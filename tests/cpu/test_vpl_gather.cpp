// The CPU VPL gather (smcir-rt's renderer) against the estimator written out by hand.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "core/scene/builtin_scenes.h"
#include "core/trace/ray_scene.h"
#include "core/vpl/vpl_gather.h"
#include "glsl/shared/vpl.h"
#include "measured.h"

using namespace vplgi;

namespace {

// A 4 x 4 m floor at y = 0 facing up (Lambert, albedo 0.5) and a small blocker quad at y = 1
// over x in [1, 1.5], facing down.
Scene floorScene()
{
    Scene scene;
    scene.name = "floor";
    Material m;
    m.baseColor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
    m.specular = 0.0f;
    scene.materials.push_back(m);
    auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 n) {
        Mesh mesh;
        for (glm::vec3 p : {a, b, c, d}) {
            Vertex v;
            v.position = p;
            v.normal = n;
            mesh.vertices.push_back(v);
        }
        mesh.indices = {0, 1, 2, 0, 2, 3};
        scene.meshes.push_back(mesh);
        scene.instances.push_back(Instance{static_cast<int>(scene.meshes.size()) - 1, glm::mat4(1.0f)});
    };
    quad({-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, {-2, 0, -2}, {0, 1, 0});
    quad({1, 1, -0.5f}, {1, 1, 0.5f}, {1.5f, 1, 0.5f}, {1.5f, 1, -0.5f}, {0, -1, 0});
    return scene;
}

SurfacePoint floorPoint(const Scene& scene, const RayScene& rays, glm::vec3 above)
{
    Ray ray;
    ray.origin = above;
    ray.direction = {0, -1, 0};
    Hit hit = rays.intersect(ray);
    REQUIRE(hit.valid());
    return surfaceAt(scene, hit, -ray.direction);
}

} // namespace

TEST_CASE("one VPL: (1/n) f G I(y), zero when occluded, clamped G", "[vpl]")
{
    Scene scene = floorScene();
    RayScene rays(scene);
    VPLSet set;
    set.slots.resize(4); // budget 4, one valid VPL: n = 1 (core/vpl/vpl.h)
    VPL& v = set.slots[0];
    v.valid = true;
    v.position = {0.0f, 2.0f, 0.0f};
    v.normal = glm::normalize(glm::vec3(0.2f, -1.0f, 0.0f));
    v.radiance = {3.0f, 2.0f, 1.0f};
    v.density = 0.25f;
    const SurfacePoint x = floorPoint(scene, rays, {-0.5f, 1.0f, 0.3f});
    const glm::vec3 wo(0.0f, 1.0f, 0.0f);
    const glm::vec3 d = v.position - x.position;
    const float d2 = glm::dot(d, d);
    const glm::vec3 wi = d / std::sqrt(d2);
    const float g = glm::dot(x.normal, wi) * glm::dot(v.normal, -wi) / d2;
    const glm::vec3 expected = (0.5f / 3.14159265f) * g * (v.radiance / v.density) / 1.0f;
    glm::vec3 value = gatherVPLs(rays, set, x, wo, VPLGatherParams{});
    for (int c = 0; c < 3; ++c) CHECK(value[c] == Approx(expected[c]).epsilon(1e-4));

    VPLGatherParams clamped;
    clamped.clampGeometry = 0.5f * g;
    value = gatherVPLs(rays, set, x, wo, clamped);
    CHECK(value.r == Approx(0.5f * expected.r).epsilon(1e-4));

    const SurfacePoint shadowed = floorPoint(scene, rays, {1.25f, 0.5f, 0.0f}); // under the blocker
    set.slots[0].position = {1.25f, 2.0f, 0.0f};
    set.slots[0].normal = {0, -1, 0};
    CHECK(gatherVPLs(rays, set, shadowed, wo, VPLGatherParams{}) == glm::vec3(0.0f));

    set.slots[0].normal = {0, 1, 0}; // facing away from the floor
    set.slots[0].position = {0.0f, 2.0f, 0.0f};
    CHECK(gatherVPLs(rays, set, x, wo, VPLGatherParams{}) == glm::vec3(0.0f));
}

TEST_CASE("furnace: uniform VPLs with the wall radiance give rho * L_all (MATH.md 3)", "[vpl]")
{
    FurnaceParams params;
    Scene scene = makeFurnace(params);
    RayScene rays(scene);
    // VPLs on a Fibonacci sphere: uniform, p = 1 / (4 pi R^2), L = L_all.
    const int count = 1024;
    VPLSet set;
    set.slots.resize(count);
    const double lAll = furnaceRadianceAll(params);
    for (int i = 0; i < count; ++i) {
        float z = 1.0f - (2.0f * i + 1.0f) / count;
        float r = std::sqrt(1.0f - z * z), phi = 2.39996323f * i;
        glm::vec3 dir(r * std::cos(phi), r * std::sin(phi), z);
        VPL& v = set.slots[i];
        v.valid = true;
        v.position = dir * params.radius * 0.999f; // just inside the tessellated wall
        v.normal = -dir;
        v.radiance = glm::vec3(static_cast<float>(lAll));
        v.density = 1.0f / (4.0f * 3.14159265f * params.radius * params.radius);
    }
    const ImageRGBA32F image = renderVPLGather(scene, rays, scene.cameras[0], 12, 8, set, VPLGatherParams{});
    double sum = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) sum += image.at(x, y)[1];
    const double mean = sum / (image.width * image.height);
    CHECK(mean == Approx(params.albedo * lAll).epsilon(0.02));
}

TEST_CASE("a VPL set short of its budget (n < I) is normalised by n: empty slots change nothing", "[vpl][numbers]")
{
    // The furnace set of 256 uniform VPLs (p normalised over those 256), once in 256 slots and once
    // spread over 1024 slots with 768 empty ones: the estimator must give the same image, and the
    // closed form rho L_all (a budget-normalised 1/I would give a quarter of it).
    FurnaceParams params;
    Scene scene = makeFurnace(params);
    RayScene rays(scene);
    const int count = 256;
    VPLSet full, sparse;
    full.slots.resize(count);
    sparse.slots.resize(4 * count);
    const double lAll = furnaceRadianceAll(params);
    for (int i = 0; i < count; ++i) {
        float z = 1.0f - (2.0f * i + 1.0f) / count;
        float r = std::sqrt(1.0f - z * z), phi = 2.39996323f * i;
        glm::vec3 dir(r * std::cos(phi), r * std::sin(phi), z);
        VPL v;
        v.valid = true;
        v.position = dir * params.radius * 0.999f;
        v.normal = -dir;
        v.radiance = glm::vec3(static_cast<float>(lAll));
        v.density = 1.0f / (4.0f * 3.14159265f * params.radius * params.radius);
        full.slots[i] = v;
        sparse.slots[4 * i + 3] = v; // slots 0, 1, 2 of every four stay empty
    }
    const ImageRGBA32F a = renderVPLGather(scene, rays, scene.cameras[0], 12, 8, full, VPLGatherParams{});
    const ImageRGBA32F b = renderVPLGather(scene, rays, scene.cameras[0], 12, 8, sparse, VPLGatherParams{});
    CHECK(a.pixels == b.pixels); // the same VPLs in the same order: bit-identical sums
    double sum = 0.0;
    for (int y = 0; y < b.height; ++y)
        for (int x = 0; x < b.width; ++x) sum += b.at(x, y)[1];
    // 256 Fibonacci VPLs: measured +0.03% from the closed form; 1% allows for the discretisation
    // (the budget-normalised 1/I would be -75%).
    MEASURED("VPL set with n < I: mean indirect " << sum / (b.width * b.height) << " vs closed form " << params.albedo * lAll);
    CHECK(sum / (b.width * b.height) == Approx(params.albedo * lAll).epsilon(0.01));
}

TEST_CASE("interleaving: every aligned 4x4 tile covers every VPL exactly once, and its mean is the full estimator",
          "[vpl]")
{
    // glsl/shared/vpl.h, shared by the GPU shading pass and the CPU gather.
    const int tile = 4, slots = 100; // 100 is not a multiple of 16: the subsets differ in size
    for (int tileY = 0; tileY < 3; ++tileY)
        for (int tileX = 0; tileX < 3; ++tileX) {
            std::vector<int> seen(slots, 0);
            for (int y = 0; y < tile; ++y)
                for (int x = 0; x < tile; ++x) {
                    const int c = shared::vplInterleaveClass(glm::ivec2(tileX * tile + x, tileY * tile + y), tile);
                    for (int i = c; i < slots; i += tile * tile)
                        ++seen[static_cast<std::size_t>(i)];
                }
            for (int count : seen)
                CHECK(count == 1);
        }
    // Values v_i: a pixel of class c estimates (16/n) sum_{i in S_c} v_i; the 16 pixels' mean is
    // (1/n) sum_i v_i (n = valid count, here all slots).
    std::vector<double> v(slots);
    double full = 0.0;
    for (int i = 0; i < slots; ++i) {
        v[static_cast<std::size_t>(i)] = std::sin(0.37 * i) + 1.5;
        full += v[static_cast<std::size_t>(i)] / slots;
    }
    double mean = 0.0;
    for (int c = 0; c < tile * tile; ++c) {
        double sum = 0.0;
        for (int i = c; i < slots; i += tile * tile)
            sum += v[static_cast<std::size_t>(i)];
        mean += sum * shared::vplEstimatorScale(slots, tile) / (tile * tile);
    }
    CHECK(mean == Approx(full).epsilon(1e-6)); // float scale factor: 1e-6 relative
    CHECK(shared::vplEstimatorScale(0, tile) == 0.0f);
    CHECK(shared::vplEstimatorScale(slots, 1) == 1.0f / slots);
}
