// renderer.display: the tone-map pass shows the chosen view (final, direct, indirect, albedo,
// normal, depth), checked against what the G-buffer must hold for the Cornell box, and the EXR
// radiance stays the final image whatever the view.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/scene/builtin_scenes.h"
#include "core/util/error.h"
#include "core/util/params.h"
#include "gl/renderer.h"
#include "gl_test_context.h"

using namespace vplgi;

namespace {

struct Views {
    ImageRGBA8 display;
    ImageRGBA32F radiance;
};

Views renderView(const Scene& scene, const std::string& view)
{
    RendererParams params;
    ParamSetter setter(Settings{{"renderer.display", view}});
    params.visitParams(setter);
    setter.finish();
    Renderer renderer(test::shaders(), scene, params, createTechnique("direct"));
    renderer.renderFrame(scene.cameras[0], 48, 48);
    return {renderer.readDisplay(), renderer.readRadiance()};
}

const std::uint8_t* pixel(const ImageRGBA8& image, int x, int y)
{
    return &image.pixels[(static_cast<std::size_t>(y) * image.width + x) * 4];
}

} // namespace

TEST_CASE("renderer.display shows the chosen view; the radiance output stays final", "[image]")
{
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("cornell");
    const Views final = renderView(scene, "final");
    const Views normal = renderView(scene, "normal");
    const Views albedo = renderView(scene, "albedo");
    const Views depth = renderView(scene, "depth");
    const Views direct = renderView(scene, "direct");

    // The back wall above the boxes faces the camera (+z): normal * 0.5 + 0.5 = (0.5, 0.5, 1).
    const std::uint8_t* n = pixel(normal.display, 24, 12);
    CHECK(std::abs(n[0] - 128) <= 2);
    CHECK(std::abs(n[1] - 128) <= 2);
    CHECK(n[2] >= 253);
    // The left wall is red, the right wall green (measured Cornell albedos), whatever the light.
    const std::uint8_t* left = pixel(albedo.display, 2, 24);
    const std::uint8_t* right = pixel(albedo.display, 45, 24);
    CHECK(left[0] > 2 * left[1]);
    CHECK(right[1] > 2 * right[0]);
    // Depth d / (1 + d) grows with distance: the back wall is farther than the near floor edge.
    CHECK(pixel(depth.display, 24, 12)[0] > pixel(depth.display, 24, 47)[0]);
    // `direct` with the direct technique is the final image (its indirect is zero).
    CHECK(direct.display.pixels == final.display.pixels);
    // Whatever the view, the linear radiance output is the final radiance.
    CHECK(normal.radiance.pixels == final.radiance.pixels);
    CHECK(normal.display.pixels != final.display.pixels);

    RendererParams params;
    ParamSetter bad(Settings{{"renderer.display", "bogus"}});
    CHECK_THROWS_WITH(params.visitParams(bad), Catch::Contains("renderer.display") && Catch::Contains("normal"));
}
