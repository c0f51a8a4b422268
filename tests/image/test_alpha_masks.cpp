// Alpha masks in the rasterizer (issue 28 part 1; glsl/shared/alpha_mask.h): on the built-in cutout
// scene (a leaf cut out of a double-sided panel, 31% of it kept, a spot light in front), the leaf's
// shadow on the floor behind the panel matches the path tracer's direct mode, and the light the leaf
// bounces onto the floor in front scales from the solid panel's to the leaf's as the path tracer's
// does, in every technique. The CPU side (rays, surface samples, tables) is in
// tests/cpu/test_alpha_masks.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "core/scene/builtin_scenes.h"
#include "core/trace/path_tracer.h"
#include "core/trace/ray_scene.h"
#include "gl/renderer.h"
#include "gl_test_context.h"
#include "measured.h"
#include "test_scenes.h"

using namespace vplgi;

namespace {

constexpr int kLeafMaterial = 1;

const Camera& cameraNamed(const Scene& scene, const std::string& name)
{
    const Camera* camera = scene.findCamera(name);
    REQUIRE(camera != nullptr);
    return *camera;
}

Scene cutout(bool masked)
{
    Scene scene = makeBuiltinScene("cutout");
    if (!masked) scene.materials[kLeafMaterial].alphaMode = Material::AlphaMode::Opaque;
    return scene;
}

// The technique's indirect light (radiance minus direct), mean luminance over the image. RSM 128^2
// for LightSkin: lightskin-full's occlusion over every VAL of the default 1024^2 RSM takes a minute
// on llvmpipe here. MIR resamples 64:1 (its 256:1 casts 0.5 M light-path candidates: seconds per frame,
// the same code).
double meanIndirect(const std::string& technique, const Scene& scene, const Camera& camera, int width, int height)
{
    Settings settings;
    if (technique.rfind("lightskin", 0) == 0) settings.emplace_back("rsm.size", "128");
    if (technique == "mir") settings.emplace_back("mir.resamplingRate", "64");
    std::unique_ptr<Renderer> renderer = test::makeTechniqueRenderer(scene, technique, settings);
    return test::meanLuminance(test::renderIndirect(*renderer, camera, width, height));
}

// The cutout scene with its spot replaced by a directional light along the spot's axis.
Scene withSun(Scene scene)
{
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = scene.lights[0].direction;
    sun.intensity = 3.0f;
    scene.lights = {sun};
    return scene;
}

} // namespace

TEST_CASE("alpha masks: the leaf's shadow on the floor is the path tracer's, light passes the cut-away part",
          "[image][alpha][numbers]")
{
    // The direct light is one pass of the renderer for every technique (gl/renderer.h): `direct`
    // checks every technique's direct shadow. The view is all floor behind the panel; the spot's
    // cone puts the solid panel's shadow on every pixel of it (the sun's leaves a strip lit).
    test::ensureGLContext();
    const int width = 96, height = 72;
    for (const bool sun : {false, true}) {
        const Scene masked = sun ? withSun(cutout(true)) : cutout(true);
        const Scene solid = sun ? withSun(cutout(false)) : cutout(false);
        const Camera& behind = cameraNamed(masked, "behind");
        const ImageRGBA32F reference = test::directReference(masked, behind, width, height);
        const double solidMean = test::meanLuminance(test::directReference(solid, behind, width, height));
        if (!sun) CHECK(solidMean == 0.0);
        CHECK(test::meanLuminance(reference) > 0.05 + 1.3 * solidMean); // light passes the cut-away part
        // The shadow map's resolution dominates the error on this view, which is all shadow edges:
        // for the spot at shadow.cubeSize 256, 1024, 2048 (texels on the floor about 2.8, 0.7, 0.35 cm;
        // pixels 1.5 cm) `vplgi render` against `vplgi reference --mode direct` (jittered pixels) gives
        // a mean |dY| of 15.4%, 4.7%, 3.4% of the floor mean and a bias of +5.3%, +1.5%, +0.4%, as any
        // shadow edge would. At 2048 the mask's own error is what is left. The sun's map (2048^2 over
        // the scene, about 0.4 cm a texel) is the default.
        std::unique_ptr<Renderer> renderer =
            test::makeTechniqueRenderer(masked, "direct", {{"shadow.cubeSize", "2048"}});
        renderer->renderFrame(behind, width, height);
        const ImageRGBA32F gpu = renderer->readDirect();
        const double error = test::relativeL1(gpu, reference);
        const double bias = test::meanLuminance(gpu) / test::meanLuminance(reference) - 1.0;
        MEASURED("cutout 'behind' (96x72) direct, " << (sun ? "sun" : "spot, cube 2048")
                                                    << ": GPU vs path tracer mean |dY| " << error
                                                    << " of the floor mean, bias " << bias << "; solid panel "
                                                    << solidMean / test::meanLuminance(reference) << " of the leaf's");
        if (error > 0.02) {
            test::saveTestImage(std::string("cutout-behind-direct-gl-") + (sun ? "sun" : "spot"), gpu);
            test::saveTestImage(std::string("cutout-behind-direct-pathtraced-") + (sun ? "sun" : "spot"), reference);
        }
        // The bound on the bias is 2% of the floor mean. Measured (spot, pixel centres) 2.4% and
        // +0.36%: the tolerances are 2.5x and 2.8x that.
        CHECK(std::abs(bias) < 0.01);
        CHECK(error < 0.06); // edge pixels: the normal offset of 1.5 texels moves the edge
    }
}

TEST_CASE("alpha masks: every technique's bounce from the leaf scales from the solid panel's as the path tracer's",
          "[image][alpha][numbers]")
{
    test::ensureGLContext();
    const int width = 48, height = 36;
    const Scene masked = cutout(true), solid = cutout(false);
    const Camera& front = cameraNamed(masked, "front");
    const int spp = 1024;
    const double referenceRatio = test::meanLuminance(test::oneBounceReference(masked, front, 32, 24, spp)) /
                                  test::meanLuminance(test::oneBounceReference(solid, front, 32, 24, spp));
    MEASURED("cutout 'front' one-bounce path tracer: leaf / solid panel " << referenceRatio);
    CHECK(referenceRatio > 0.15);
    CHECK(referenceRatio < 0.6);
    for (const std::string& technique : techniqueNames()) {
        if (technique == "direct") continue;
        const double withLeaf = meanIndirect(technique, masked, front, width, height);
        const double withPanel = meanIndirect(technique, solid, front, width, height);
        const double ratio = withLeaf / withPanel;
        MEASURED(technique << ": leaf / solid panel " << ratio << " (" << withLeaf << " / " << withPanel
                           << "), against the path tracer's " << ratio / referenceRatio);
        CHECK(withPanel > 0.0);
        // The bound. Measured (default seeds) 0.962 (ir) to 1.013 (smcir); the path tracer's
        // ratio (1024 spp at 32x24) has a standard error near 1%. Over seeds 1-8
        // (scripts/alpha-mask-seeds) every mean is within 5%, but ir's seeds range 0.865-1.014: a
        // technique's seed change can cross this bound for ir alone, from its few VPLs on the leaf.
        CHECK(std::abs(ratio / referenceRatio - 1.0) < 0.1);
    }
    // The one scene-drawing program not used above, the VPL overhead view, builds and draws its masked
    // variant (plumbing only).
    std::unique_ptr<Renderer> overhead = test::makeTechniqueRenderer(masked, "ir", {});
    overhead->renderFrame(front, width, height);
    CHECK_NOTHROW(overhead->renderInset("ir.overhead"));
}
