// The smcir-rt technique inside the renderer: its indirect image is exactly the CPU gather of the
// VPL set the sampler produces for the same seed, camera and aspect (orientation, parameters and
// the pipelining are right), and the renderer adds it to the direct light.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/scene/builtin_scenes.h"
#include "core/util/params.h"
#include "core/trace/ray_scene.h"
#include "core/vpl/smcir_sampler.h"
#include "core/vpl/vpl_gather.h"
#include "gl/renderer.h"
#include "gl_test_context.h"
#include "test_scenes.h"

using namespace vplgi;

TEST_CASE("smcir-rt adds the CPU gather of the sampler's first VPL set", "[image][smcir]")
{
    test::ensureGLContext();
    Scene scene = makeBuiltinScene("cornell");
    const Camera& camera = scene.cameras[0];
    const int width = 40, height = 30;
    const Settings settings = {{"smcir.vplCount", "256"}, {"smcir.warmupIterations", "3"}, {"smcir.clampScale", "2"}};

    std::unique_ptr<Technique> technique = createTechnique("smcir-rt");
    ParamSetter setter(settings);
    technique->visitParams(setter);
    setter.finish();
    Renderer renderer(test::shaders(), scene, RendererParams{}, std::move(technique));
    renderer.renderFrame(camera, width, height);
    const ImageRGBA32F total = renderer.readRadiance();
    const ImageRGBA32F direct = renderer.readDirect();

    // The same sampler on the CPU.
    RayScene rays(scene);
    SMCIRParams params;
    ParamSetter cpuSetter(settings);
    params.visitParams(cpuSetter);
    SMCIRSampler sampler(scene, rays, params);
    sampler.initialize(camera, static_cast<float>(width) / height);
    VPLGatherParams gather;
    gather.clampGeometry = test::vplClampGeometry(rays, 256);
    const ImageRGBA32F indirect = renderVPLGather(scene, rays, camera, width, height, sampler.vpls(), gather);

    double worst = 0.0, indirectSum = 0.0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 3; ++c) {
                const double expected = direct.at(x, y)[c] + indirect.at(x, y)[c];
                worst = std::max(worst, std::abs(total.at(x, y)[c] - expected) / std::max(expected, 1e-3));
                indirectSum += indirect.at(x, y)[c];
            }
    INFO("worst relative difference " << worst);
    CHECK(indirectSum > 0.0); // the gather brought light
    CHECK(worst < 1e-5);
    CHECK(renderer.technique().frameStats().size() >= 3);
}
