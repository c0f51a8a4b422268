// The back-face rule in the rasterizer (issue 28 part 2; scene.h Material::doubleSided): a
// single-sided surface seen from behind is absent for the camera, the lights and every light view
// (shadow maps, the VPL shadow atlas, RSMs, imperfect shadow maps), as it is for the path tracer's
// rays. On the built-in one-sided scene (two single-sided panels before a spot light: "facing" turns
// its front to the light, "away", a mirrored instance, its back): `direct` against the path tracer's
// direct mode from in front and from behind; every technique's bounce with the away panel equals
// its bounce without it, as the path tracer's does, and turning that panel to the light changes the
// bounce as much as it changes the path tracer's. The CPU side is in tests/cpu/test_back_faces.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/scene/builtin_scenes.h"
#include "core/trace/path_tracer.h"
#include "core/trace/ray_scene.h"
#include "gl/renderer.h"
#include "gl_test_context.h"
#include "measured.h"
#include "test_scenes.h"

using namespace vplgi;

namespace {

constexpr std::size_t kAway = 2;

const Camera& cameraNamed(const Scene& scene, const std::string& name)
{
    const Camera* camera = scene.findCamera(name);
    REQUIRE(camera != nullptr);
    return *camera;
}

// "as is": the away panel's back to the light; "without": no away panel; "turned": its front to
// the light (the mirror taken off).
Scene oneSided(const std::string& variant)
{
    Scene scene = makeBuiltinScene("one-sided");
    if (variant == "without") scene.instances.erase(scene.instances.begin() + kAway);
    if (variant == "turned") scene.instances[kAway].worldFromObject = glm::mat4(1.0f);
    return scene;
}

double meanIndirect(const std::string& technique, const Scene& scene, const Camera& camera, int width, int height)
{
    Settings settings;
    if (technique.rfind("lightskin", 0) == 0) settings.emplace_back("rsm.size", "128"); // as test_alpha_masks
    if (technique == "mir") settings.emplace_back("mir.resamplingRate", "64"); // as test_alpha_masks
    std::unique_ptr<Renderer> renderer = test::makeTechniqueRenderer(scene, technique, settings);
    return test::meanLuminance(test::renderIndirect(*renderer, camera, width, height));
}

} // namespace

TEST_CASE("back faces: a single-sided panel seen from behind is absent in direct as in the path tracer",
          "[image][backfaces][numbers]")
{
    test::ensureGLContext();
    const int width = 96, height = 72;
    const Scene scene = oneSided("as is"), without = oneSided("without");
    for (const std::string view : {"default", "behind"}) {
        const Camera& camera = cameraNamed(scene, view);
        const ImageRGBA32F reference = test::directReference(scene, camera, width, height);
        // The path tracer itself: from in front the away panel is absent (its back to the camera and
        // the light), so the image is the one without it; from behind its front is seen.
        const double absent = test::relativeL1(reference, test::directReference(without, camera, width, height));
        if (view == "default") CHECK(absent == 0.0);
        else CHECK(absent > 0.05);
        // Cube maps at 2048 (shadow-edge error, as tests/image/test_alpha_masks.cpp measures it).
        std::unique_ptr<Renderer> renderer = test::makeTechniqueRenderer(scene, "direct", {{"shadow.cubeSize", "2048"}});
        renderer->renderFrame(camera, width, height);
        const ImageRGBA32F gpu = renderer->readDirect();
        const double error = test::relativeL1(gpu, reference);
        const double bias = test::meanLuminance(gpu) / test::meanLuminance(reference) - 1.0;
        MEASURED("one-sided '" << view << "' (96x72) direct: GPU vs path tracer mean |dY| " << error
                               << " of the mean, bias " << bias << "; path tracer with vs without the away panel "
                               << absent);
        if (error > 0.02) {
            test::saveTestImage("one-sided-" + view + "-direct-gl", gpu);
            test::saveTestImage("one-sided-" + view + "-direct-pathtraced", reference);
        }
        CHECK(std::abs(bias) < 0.01);
        CHECK(error < 0.03);
    }
}

TEST_CASE("back faces: every technique's bounce ignores a panel seen from behind and follows it turned, as the path "
          "tracer's", "[image][backfaces][numbers]")
{
    test::ensureGLContext();
    const int width = 48, height = 36;
    const Scene scene = oneSided("as is"), without = oneSided("without"), turned = oneSided("turned");
    const Camera& front = cameraNamed(scene, "front");
    const int spp = 1024;
    const double referenceWithout = test::meanLuminance(test::oneBounceReference(without, front, 32, 24, spp));
    const double referenceAbsent = test::meanLuminance(test::oneBounceReference(scene, front, 32, 24, spp)) / referenceWithout;
    const double referenceTurned = test::meanLuminance(test::oneBounceReference(turned, front, 32, 24, spp)) / referenceWithout;
    MEASURED("one-sided 'front' one-bounce path tracer: as is / without " << referenceAbsent << ", turned / without "
                                                                           << referenceTurned);
    CHECK(referenceAbsent == Approx(1.0).margin(0.03));
    CHECK(referenceTurned > 1.3);
    for (const std::string& technique : techniqueNames()) {
        if (technique == "direct") continue;
        const double base = meanIndirect(technique, without, front, width, height);
        const double absent = meanIndirect(technique, scene, front, width, height) / base;
        const double turnedRatio = meanIndirect(technique, turned, front, width, height) / base;
        MEASURED(technique << ": as is / without " << absent << ", turned / without " << turnedRatio
                           << " (path tracer's " << turnedRatio / referenceTurned << "x)");
        CHECK(base > 0.0);
        CHECK(std::abs(absent - 1.0) < 0.05);
        CHECK(std::abs(turnedRatio / referenceTurned - 1.0) < 0.1);
    }
}
