// One live parameter set: the renderer owns its parameters and its technique's; changes between
// frames take effect (cheap ones at once, structural ones by rebuilding).
#include <catch2/catch.hpp>

#include "core/scene/builtin_scenes.h"
#include "core/util/error.h"
#include "gl/renderer.h"
#include "gl_test_context.h"

using namespace vplgi;

namespace {

double statOf(Technique& technique, const std::string& name)
{
    for (const auto& [key, value] : technique.frameStats())
        if (key == name) return value;
    FAIL("no frame stat " << name);
    return 0.0;
}

} // namespace

TEST_CASE("live parameters: smcir.vplCount and renderer.exposure changed between frames take effect", "[image][smcir]")
{
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("cornell");
    Renderer renderer(test::shaders(), scene, RendererParams{}, createTechnique("smcir-rt"));
    renderer.applySettings({{"smcir.vplCount", "64"}, {"smcir.warmupIterations", "1"}, {"smcir.synchronous", "true"}});
    renderer.renderFrame(scene.cameras[0], 32, 24);
    CHECK(statOf(renderer.technique(), "vpls") <= 64);
    const ImageRGBA8 before = renderer.readDisplay();
    const ImageRGBA32F radianceBefore = renderer.readRadiance();

    const std::set<std::string> changed = renderer.applySettings({{"smcir.vplCount", "200"}, {"renderer.exposure", "3"}});
    CHECK(changed == std::set<std::string>{"renderer.exposure", "smcir.vplCount"});
    renderer.renderFrame(scene.cameras[0], 32, 24);
    CHECK(statOf(renderer.technique(), "vpls") > 64); // the sampler was rebuilt with the new budget
    CHECK(statOf(renderer.technique(), "vpls") <= 200);
    CHECK(renderer.params().exposure == 3.0f);
    // The brighter exposure shows in the display bytes.
    long sumBefore = 0, sumAfter = 0;
    const ImageRGBA8 after = renderer.readDisplay();
    for (std::size_t i = 0; i < after.pixels.size(); ++i) {
        sumBefore += before.pixels[i];
        sumAfter += after.pixels[i];
    }
    CHECK(sumAfter > sumBefore);
    CHECK(renderer.readRadiance().pixels != radianceBefore.pixels); // other VPLs, other indirect light

    // Setting a value to what it is changes nothing; unknown keys are errors.
    CHECK(renderer.applySettings({{"renderer.exposure", "3"}}).empty());
    CHECK_THROWS_AS(renderer.applySettings({{"smcir.noSuchKey", "1"}}), Error);
}
