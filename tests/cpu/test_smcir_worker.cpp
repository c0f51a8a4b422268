// The VPL pipeline's worker thread (core/vpl/vpl_pipeline.h) running the SMCIR sampler and the IR
// baseline, against the same sampler run synchronously, with a light that the main thread moves
// while the worker runs (the race the frame snapshot removes). Tagged [threads]: the ThreadSanitizer
// build runs these (scripts/test --tsan).
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <tbb/global_control.h>

#include "core/scene/builtin_scenes.h"
#include "core/trace/ray_scene.h"
#include "core/vpl/ir_sampler.h"
#include "core/vpl/smcir_sampler.h"
#include "core/vpl/vpl_pipeline.h"
#include "core/vpl/vpl_gather.h"

using namespace vplgi;

namespace {

#if VPLGI_TSAN
// ThreadSanitizer build: no TBB worker threads (tests/sanitizers/tsan.supp says why); parallel loops
// run on the thread that calls them, so the render thread and the SMCIR worker are the two threads.
const tbb::global_control kOneTBBThreadPerCaller(tbb::global_control::max_allowed_parallelism, 1);
#endif

// The Cornell box plus a point light that circles under the ceiling, one step per frame.
Scene cornellWithMovingLight()
{
    Scene scene = makeBuiltinScene("cornell");
    Light light;
    light.name = "orbit";
    light.type = LightType::Point;
    light.intensity = 0.3f;
    scene.lights.push_back(light);
    return scene;
}

void placeLight(Scene& scene, int frame)
{
    const glm::vec3 centre = scene.worldBounds().center();
    const float angle = 0.4f * static_cast<float>(frame);
    scene.lights.back().position = centre + glm::vec3(0.15f * std::cos(angle), 0.1f, 0.15f * std::sin(angle));
}

SMCIRParams smallSMCIRParams()
{
    SMCIRParams params;
    params.vplCount = 128;
    params.warmupIterations = 2;
    params.cameraSamplesX = 16;
    params.cameraSamplesY = 9;
    params.radiositySamples = 4;
    return params;
}

IRParams smallIRParams()
{
    IRParams params;
    params.vplCount = 128;
    return params;
}

bool sameSet(const VPLSet& a, const VPLSet& b)
{
    if (a.slots.size() != b.slots.size() || a.changed != b.changed) return false;
    for (std::size_t i = 0; i < a.slots.size(); ++i) {
        const VPL& x = a.slots[i];
        const VPL& y = b.slots[i];
        if (x.valid != y.valid || x.position != y.position || x.normal != y.normal || x.radiance != y.radiance ||
            x.density != y.density)
            return false;
    }
    return true;
}

// Runs `frames` synchronous steps and the same steps through the worker; frame f + 1 of the
// asynchronous run must show exactly what frame f of the synchronous run showed.
// `checkSynchronous` is then called with the synchronous sampler.
template <class Sampler, class Params, class Check>
void checkWorkerEqualsSynchronous(const Params& params, Check checkSynchronous)
{
    const int frames = 24, width = 24, height = 18;
    const float aspect = static_cast<float>(width) / height;

    // Synchronous: frame f steps with the lights of frame f and shows that set.
    Scene syncScene = cornellWithMovingLight();
    const RayScene syncRays(syncScene);
    Sampler syncSampler(syncScene, syncRays, params);
    placeLight(syncScene, 0);
    syncSampler.initialize(FrameSnapshot::of(syncScene, syncScene.cameras[0], aspect));
    std::vector<VPLSet> syncSets{syncSampler.vpls()};
    std::vector<ImageRGBA32F> syncImages;
    for (int f = 1; f <= frames; ++f) {
        placeLight(syncScene, f);
        syncSampler.step(FrameSnapshot::of(syncScene, syncScene.cameras[0], aspect));
        syncSets.push_back(syncSampler.vpls());
    }
    for (const VPLSet& set : syncSets)
        syncImages.push_back(renderVPLGather(syncScene, syncRays, syncScene.cameras[0], width, height, set, {}));

    // Asynchronous, as the GPU techniques run it (VPLPipeline): frame f shows the set of step f-1 and
    // submits step f; while the worker runs, this thread moves the light on for the next frame and gathers.
    Scene scene = cornellWithMovingLight();
    const RayScene rays(scene);
    std::vector<VPLSet> shownSets;
    std::vector<ImageRGBA32F> shownImages;
    {
        VPLPipeline pipeline(std::make_unique<Sampler>(scene, rays, params));
        for (int f = 0; f <= frames + 1; ++f) {
            placeLight(scene, f);
            shownSets.push_back(pipeline.advance(FrameSnapshot::of(scene, scene.cameras[0], aspect), false));
            placeLight(scene, f + 1); // writes scene.lights while step f runs on the worker
            shownImages.push_back(renderVPLGather(scene, rays, scene.cameras[0], width, height, shownSets.back(), {}));
        }
    }

    REQUIRE(shownSets.size() == syncSets.size() + 1);
    int differentSets = 0, differentImages = 0, lit = 0, changedSets = 0;
    for (std::size_t f = 0; f < syncSets.size(); ++f) {
        if (!sameSet(shownSets[f + 1], syncSets[f])) ++differentSets;
        if (shownImages[f + 1].pixels != syncImages[f].pixels) ++differentImages;
        for (float v : shownImages[f + 1].pixels) lit += v > 0.0f && v != 1.0f ? 1 : 0;
        if (f > 0 && !sameSet(syncSets[f], syncSets[f - 1])) ++changedSets;
    }
    CHECK(differentSets == 0);
    CHECK(differentImages == 0);
    CHECK(lit > 0); // the gathers carry light
    // The light moved every frame, so every step changed the set (a frozen set would compare equal trivially).
    CHECK(changedSets == frames);
    checkSynchronous(syncSampler);
}

} // namespace

TEST_CASE("VPL pipeline: asynchronous smcir steps equal synchronous ones while the light moves", "[smcir][threads]")
{
    checkWorkerEqualsSynchronous<SMCIRSampler>(smallSMCIRParams(), [](const SMCIRSampler& sampler) {
        // The light moved every frame, so every step re-estimated the surviving VPLs' radiance.
        CHECK(sampler.lastTimes().radianceEstimates > sampler.lastTimes().candidates);
    });
}

TEST_CASE("VPL pipeline: asynchronous ir steps equal synchronous ones while the light moves", "[ir][threads]")
{
    checkWorkerEqualsSynchronous<IRSampler>(smallIRParams(), [](const IRSampler& sampler) {
        CHECK(sampler.lastStats().vpls > 0); // IR deposits a full new set every frame
    });
}
