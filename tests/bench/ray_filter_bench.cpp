// What the back-face rule's Embree filter costs rays (issue 28 part 2, ray_scene.cpp): the same rays
// through the same triangles, once as the scene is (its single-sided materials get the filter) and
// once with every material double-sided (no filter), side by side: closest hits from the camera
// (Looker::Origin), bounces (Looker::None: the filter is called and returns) and shadow rays to the
// scene's first light (Looker::End). Printed, never asserted (STYLE.md: benchmarks are not timed
// tests). Single-threaded, so the two cores do not add noise.
//   build/tests/vplgi_bench_ray_filter [--rays N] [--scene cornell|maze|...]  (default 400000, cornell and maze)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "core/scene/builtin_scenes.h"
#include "core/trace/ray_scene.h"

using namespace vplgi;

namespace {

struct Timing {
    double seconds = 0.0;
    long hits = 0;
};

// Rays from points spread over the scene box in uniform directions; shadow rays to the first light.
Timing trace(const RayScene& rays, const std::vector<Ray>& batch, Looker looker, bool shadow)
{
    Timing t;
    const auto start = std::chrono::steady_clock::now();
    for (const Ray& ray : batch) t.hits += shadow ? (rays.occluded(ray, looker) ? 1 : 0) : (rays.intersect(ray, looker).valid() ? 1 : 0);
    t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return t;
}

std::vector<Ray> randomRays(const Scene& scene, int count, bool toLight)
{
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const AABB box = scene.worldBounds();
    const glm::vec3 light = scene.lights.empty() ? box.upper : scene.lights[0].position;
    std::vector<Ray> batch(static_cast<std::size_t>(count));
    for (Ray& ray : batch) {
        ray.origin = box.lower + box.extent() * glm::vec3(0.05f + 0.9f * u(rng), 0.05f + 0.9f * u(rng), 0.05f + 0.9f * u(rng));
        if (toLight) {
            ray.direction = light - ray.origin;
            ray.tMin = 1e-4f;
            ray.tMax = 1.0f - 1e-4f;
        } else {
            const float z = 2.0f * u(rng) - 1.0f, phi = 6.2831853f * u(rng), r = std::sqrt(std::max(0.0f, 1.0f - z * z));
            ray.direction = glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
            ray.tMin = 1e-4f;
        }
    }
    return batch;
}

} // namespace

int main(int argc, char** argv)
{
    int count = 400000;
    std::vector<std::string> scenes = {"cornell", "maze"};
    for (int i = 1; i + 1 < argc; i += 2) {
        if (std::strcmp(argv[i], "--rays") == 0) count = std::atoi(argv[i + 1]);
        else if (std::strcmp(argv[i], "--scene") == 0) scenes = {argv[i + 1]};
    }
    std::printf("%-8s %-26s %12s %12s %14s\n", "scene", "rays", "filter Mr/s", "none Mr/s", "time x filter");
    for (const std::string& name : scenes) {
        const Scene scene = makeBuiltinScene(name);
        Scene twoSided = scene;
        for (Material& m : twoSided.materials) m.doubleSided = true;
        const RayScene filtered(scene), plain(twoSided);
        struct Kind {
            const char* name;
            Looker looker;
            bool shadow;
        };
        for (const Kind& k : {Kind{"closest hit, Looker::Origin", Looker::Origin, false},
                              Kind{"closest hit, Looker::None", Looker::None, false},
                              Kind{"shadow, Looker::End", Looker::End, true}}) {
            const std::vector<Ray> batch = randomRays(scene, count, k.shadow);
            trace(filtered, batch, k.looker, k.shadow); // warm caches
            const Timing a = trace(filtered, batch, k.looker, k.shadow);
            const Timing b = trace(plain, batch, k.looker, k.shadow);
            std::printf("%-8s %-26s %12.2f %12.2f %14.2f\n", name.c_str(), k.name, count / a.seconds * 1e-6,
                        count / b.seconds * 1e-6, a.seconds / b.seconds);
        }
    }
    return 0;
}
