// Shadow-atlas timings on llvmpipe (or whatever EGL gives): renderDirty of N slots x 3 hemisphere
// faces of 128^2 on cornell and maze, as one instanced draw per mesh (the atlas) and, side by side,
// as one renderDirty call per slot (one draw per slot and mesh), plus which capacities allocate.
// Printed, never asserted (STYLE.md: benchmarks are not timed tests). glFinish + wall clock,
// because GL_TIME_ELAPSED is not trustworthy on llvmpipe (../shared/ENVIRONMENT.md).
//   build/tests/vplgi_bench_shadow_atlas [--repeats N] [--scene cornell|maze] [--tiles-per-row N]
// (about 2 minutes per repeat on a 2-core llvmpipe machine, most of it maze with 2048 slots).
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
#include "core/util/error.h"
#include "gl/api/context.h"
#include "gl/api/shader_loader.h"
#include "gl/gpu_scene.h"
#include "gl/passes/shadow_atlas.h"
#include "glsl/shared/light_view.h"

using namespace vplgi;

namespace {

// Hemisphere-cube faces of VPLs at seeded random points of the scene box, random normals.
std::vector<glm::mat4> randomHemisphereFaces(const Scene& scene, int slots, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const AABB box = scene.worldBounds();
    const float diagonal = glm::length(box.extent());
    std::vector<glm::mat4> matrices;
    for (int s = 0; s < slots; ++s) {
        const glm::vec3 p =
            box.lower + box.extent() * glm::vec3(0.1f + 0.8f * u(rng), 0.1f + 0.8f * u(rng), 0.1f + 0.8f * u(rng));
        const float z = 2.0f * u(rng) - 1.0f, phi = 6.2831853f * u(rng);
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const glm::mat3 basis = shared::lightViewHemisphereBasis(glm::vec3(r * std::cos(phi), r * std::sin(phi), z));
        for (int face = 0; face < 3; ++face)
            matrices.push_back(
                shared::lightViewHemisphereFaceClipFromWorld(p, basis, face, 0.01f * diagonal, 1.5f * diagonal));
    }
    return matrices;
}

template <typename F> double millisecondsOf(F&& work)
{
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    work();
    glFinish();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> values)
{
    std::sort(values.begin(), values.end());
    return values[values.size() / 2];
}

} // namespace

int main(int argc, char** argv)
{
    int repeats = 1, tilesPerRow = 0;
    std::vector<std::string> scenes = {"cornell", "maze"};
    for (int i = 1; i + 1 < argc; i += 2) {
        if (std::strcmp(argv[i], "--repeats") == 0)
            repeats = std::max(1, std::atoi(argv[i + 1]));
        else if (std::strcmp(argv[i], "--scene") == 0)
            scenes = {argv[i + 1]};
        else if (std::strcmp(argv[i], "--tiles-per-row") == 0)
            tilesPerRow = std::atoi(argv[i + 1]);
        else {
            std::fprintf(stderr, "error: unknown option %s\n", argv[i]);
            return 1;
        }
    }
    try {
        gl::ContextOptions options;
        options.debug = false; // a synchronous debug callback would slow the driver down
        auto context = gl::createHeadlessContext(options);
        const gl::ShaderLoader shaders;
        std::printf("shadow atlas bench on %s\n", context->description().c_str());
        std::printf("tilesPerRow %s, median of %d repeats\n",
                    tilesPerRow == 0 ? "automatic" : std::to_string(tilesPerRow).c_str(), repeats);
        std::printf("%-8s %9s %6s %6s %11s %14s %11s %15s\n", "scene", "triangles", "slots", "maps", "atlas [ms]",
                    "per map [ms]", "per slot [ms]", "per-slot/atlas");
        for (const std::string& name : scenes) {
            const Scene scene = makeBuiltinScene(name);
            const GpuScene gpuScene(scene);
            for (const int slots : {16, 2048}) {
                ShadowAtlasParams params;
                params.tileSize = 128;
                params.slots = slots;
                params.viewsPerSlot = 3;
                params.tilesPerRow = tilesPerRow;
                ShadowAtlas atlas(shaders, name, params);
                const std::vector<glm::mat4> matrices = randomHemisphereFaces(scene, slots, 1);
                std::vector<std::uint32_t> all(static_cast<std::size_t>(slots));
                for (int s = 0; s < slots; ++s)
                    all[static_cast<std::size_t>(s)] = static_cast<std::uint32_t>(s);
                atlas.renderDirty(gpuScene, all, matrices); // warm-up: shader variants, first touch of memory
                std::vector<double> atlasTimes, perSlotTimes;
                for (int r = 0; r < repeats; ++r) {
                    atlasTimes.push_back(millisecondsOf([&] { atlas.renderDirty(gpuScene, all, matrices); }));
                    perSlotTimes.push_back(millisecondsOf([&] {
                        for (int s = 0; s < slots; ++s)
                            atlas.renderDirty(gpuScene, {all[static_cast<std::size_t>(s)]},
                                              {matrices.begin() + 3 * s, matrices.begin() + 3 * s + 3});
                    }));
                }
                const double a = median(atlasTimes), p = median(perSlotTimes);
                std::printf("%-8s %9zu %6d %6d %11.1f %14.3f %11.1f %15.2f\n", name.c_str(), scene.triangleCount(),
                            slots, 3 * slots, a, a / (3.0 * slots), p, p / a);
                std::fflush(stdout);
            }
        }
        std::printf("\ncapacity (tileSize 128, budget 4096 MiB):\n");
        for (const int views : {1, 3}) {
            ShadowAtlasParams params;
            params.tileSize = 128;
            params.slots = 8192;
            params.viewsPerSlot = views;
            params.memoryBudgetMiB = 4096.0;
            try {
                double ms = 0.0;
                ShadowAtlasLayout layout;
                ms = millisecondsOf([&] { layout = ShadowAtlas(shaders, "capacity", params).layout(); });
                std::printf("  8192 slots x %d views: fits, %d tiles per row, %d layers of %d^2, %.0f MiB "
                            "(allocate + clear + free %.0f ms)\n",
                            views, layout.tilesPerRow, layout.layers, layout.layerSize, layout.memoryMiB, ms);
            } catch (const Error& e) {
                std::printf("  8192 slots x %d views: %s\n", views, e.what());
            }
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
