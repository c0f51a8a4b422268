// renderer.display: the tone-map pass shows the chosen view (final, direct, indirect, albedo,
// normal, depth), checked against what the G-buffer must hold for the Cornell box, and the EXR
// radiance stays the final image whatever the view. Texture views (the renderer's shadow maps, a
// test technique's views): the display read back equals the texture read back, through a CPU twin
// of the tone-map pass's addressing and value mapping.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include "core/scene/builtin_scenes.h"
#include "core/util/error.h"
#include "core/util/params.h"
#include "gl/renderer.h"
#include "gl_test_context.h"
#include "glsl/shared/tonemap.h"
#include "measured.h"

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

TEST_CASE("renderer.display shows the chosen view, and the radiance output stays final", "[image]")
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
    // The left wall is red, the right wall green (measured Cornell albedos), whatever the light;
    // compared in linear values (the view is sRGB-encoded: green 180 vs red 105 is 3.3x linear).
    const auto linear = [](std::uint8_t v) { return std::pow(v / 255.0, 2.2); };
    const std::uint8_t* left = pixel(albedo.display, 2, 24);
    const std::uint8_t* right = pixel(albedo.display, 45, 24);
    CHECK(linear(left[0]) > 2 * linear(left[1]));
    CHECK(linear(right[1]) > 2 * linear(right[0]));
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

// --- Texture views (gl/debug_view.h): what the display shows equals the texture, read back ------

namespace {

// Reads `layers` layers from `first` of level 0 of a texture as one float per texel (depth, or red).
std::vector<float> readLayers(const gl::Texture& texture, GLenum format, int first, int layers)
{
    const int w = texture.width(), h = texture.height();
    const int channels = format == GL_RGBA ? 4 : 1;
    std::vector<float> texels(static_cast<std::size_t>(w) * h * layers * channels);
    glGetTextureSubImage(texture.id(), 0, 0, 0, first, w, h, layers, format, GL_FLOAT,
                         static_cast<GLsizei>(texels.size() * sizeof(float)), texels.data());
    return texels;
}

// CPU twin of textureViewValue's addressing in passes/tonemap.frag: output pixel (x, y from the
// top) of a width x height image -> (layer, texel x, texel y from the bottom) of `rect`; layer -1
// where the grid has no layer.
glm::ivec3 viewTexel(int x, int yTop, int width, int height, int layers, glm::ivec4 rect)
{
    int columns = 1;
    while (columns * columns < layers)
        ++columns;
    const int rows = (layers + columns - 1) / columns;
    const int gx = (2 * x + 1) * columns, gy = (2 * yTop + 1) * rows; // pixel centres in half pixels
    const int layer = (gy / (2 * height)) * columns + gx / (2 * width);
    if (layer >= layers) return {-1, 0, 0};
    const int tx = ((gx % (2 * width)) * rect.z) / (2 * width);
    const int tTop = ((gy % (2 * height)) * rect.w) / (2 * height);
    return {layer, rect.x + tx, rect.y + rect.w - 1 - tTop};
}

std::uint8_t toByte(float v)
{
    return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

// The display of `renderer` against `expected(layer, tx, ty)` (display bytes rgb); returns the
// worst byte difference and counts the pixels that show a layer.
int compareDisplay(const Renderer& renderer, int layers, glm::ivec4 rect,
                   const std::function<glm::ivec3(int, int, int)>& expected, int& shown)
{
    const ImageRGBA8 display = renderer.readDisplay();
    int worst = 0;
    shown = 0;
    for (int y = 0; y < display.height; ++y)
        for (int x = 0; x < display.width; ++x) {
            const glm::ivec3 t = viewTexel(x, y, display.width, display.height, layers, rect);
            const glm::ivec3 want = t.x < 0 ? glm::ivec3(0) : expected(t.x, t.y, t.z);
            shown += t.x >= 0;
            for (int c = 0; c < 3; ++c)
                worst = std::max(worst, std::abs(pixel(display, x, y)[c] - want[c]));
        }
    return worst;
}

const DebugView& findView(const std::vector<DebugView>& views, const std::string& name)
{
    for (const DebugView& view : views)
        if (view.name == name) return view;
    throw Error("no view " + name);
}

// A technique with one RGBA32F 2D array (2 layers, 8 x 6) of known values and three views of it.
class ViewTechnique final : public Technique {
public:
    static constexpr int kWidth = 8, kHeight = 6, kLayers = 2;
    std::string_view name() const override { return "viewtest"; }
    void setScene(const SceneContext&) override
    {
        gl::TextureDesc desc;
        desc.target = GL_TEXTURE_2D_ARRAY;
        desc.format = GL_RGBA32F;
        desc.width = kWidth;
        desc.height = kHeight;
        desc.layers = kLayers;
        mTexture = gl::Texture("viewtest texture", desc);
        std::vector<float> data(static_cast<std::size_t>(kWidth) * kHeight * kLayers * 4);
        for (std::size_t i = 0; i < data.size(); ++i) // HDR values in [0, 6), signed-ish normals, counts
            data[i] = static_cast<float>((i * 7919u) % 600u) / 100.0f - (i % 4 == 1 ? 3.0f : 0.0f);
        glTextureSubImage3D(mTexture.id(), 0, 0, 0, 0, kWidth, kHeight, kLayers, GL_RGBA, GL_FLOAT, data.data());
    }
    void update(const FrameContext&) override {}
    void render(const FrameContext&, const GBuffer&, const IndirectTarget&) override {}
    void visitParams(ParamVisitor&) override {}
    std::vector<DebugView> debugViews() const override
    {
        const gl::Texture* texture = mTexture ? &mTexture : nullptr;
        DebugView color{"viewtest.color", "layer 1, texels (2..6, 1..4), HDR colour", texture, shared::kDebugViewColor};
        color.layer = 1;
        color.rect = glm::ivec4(2, 1, 5, 4);
        DebugView normal{"viewtest.normal", "both layers as normals", texture, shared::kDebugViewNormal};
        normal.layerCount = 0;
        DebugView count{"viewtest.count", "layer 0 as counts up to 100", texture, shared::kDebugViewCount};
        count.range = glm::vec2(0.0f, 100.0f);
        return {color, normal, count};
    }
    const gl::Texture& texture() const { return mTexture; }

private:
    gl::Texture mTexture;
};

} // namespace

TEST_CASE("renderer.display shows the shadow maps as texture views, texel for texel", "[image][views][numbers]")
{
    test::ensureGLContext();
    Scene scene = makeBuiltinScene("cornell");
    Light sun;
    sun.name = "sun";
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.4f));
    sun.intensity = 1.0f;
    scene.lights.push_back(sun);
    scene.validate();

    struct Case {
        std::string view;
        int layer;
        int width, height;
    };
    // One cube face upscaled to a non-square image, every face of 3 cubes tiled (18 layers, 5 x 4
    // grid, downscaled), the directional map downscaled.
    for (const Case& c :
         {Case{"shadow.point", 4, 48, 40}, Case{"shadow.point", -1, 70, 52}, Case{"shadow.directional", -1, 40, 40}}) {
        RendererParams params;
        ParamSetter setter(Settings{{"renderer.display", c.view},
                                    {"renderer.displayLayer", std::to_string(c.layer)},
                                    {"lights.emitterSamples", "3"},
                                    {"shadow.cubeSize", "32"},
                                    {"shadow.mapSize", "64"}});
        params.visitParams(setter);
        setter.finish();
        Renderer renderer(test::shaders(), scene, params, createTechnique("direct"));
        renderer.renderFrame(scene.cameras[0], c.width, c.height);
        const DebugView& view = findView(renderer.debugViews(), c.view);
        REQUIRE(view.texture);
        const int total = view.texture->desc().layers;
        CHECK(total == (c.view == "shadow.point" ? 18 : 1));
        const int first = c.layer < 0 ? 0 : c.layer;
        const int layers = c.layer < 0 ? total : 1;
        const std::vector<float> depth = readLayers(*view.texture, GL_DEPTH_COMPONENT, first, layers);
        const int w = view.texture->width(), h = view.texture->height();
        float lo = 1.0f, hi = 0.0f;
        for (float d : depth)
            lo = std::min(lo, d), hi = std::max(hi, d);
        // The maps hold a range of depths (a view of a constant would hide addressing errors).
        CHECK(hi - lo > 0.2f);
        int shown = 0;
        const int worst = compareDisplay(
            renderer, layers, glm::ivec4(0, 0, w, h),
            [&](int layer, int tx, int ty) {
                const float d = depth[(static_cast<std::size_t>(layer) * h + ty) * w + tx];
                return glm::ivec3(toByte(d)); // range [0, 1]
            },
            shown);
        MEASURED(c.view << " layer " << c.layer << " at " << c.width << "x" << c.height << ": worst byte difference "
                        << worst << ", " << shown << " pixels show a layer, depths " << lo << ".." << hi);
        // Measured 0: the same texel, and one float -> unorm rounding; 1 allows a driver that
        // rounds the conversion differently.
        CHECK(worst <= 1);
        // 18 layers in a 5 x 4 grid of 14 x 13 pixel cells: two cells stay black.
        CHECK(shown == (c.layer < 0 && c.view == "shadow.point" ? 18 * 14 * 13 : c.width * c.height));
    }

    // A layer past the view's last is an error naming the parameter.
    RendererParams params;
    ParamSetter setter(Settings{{"renderer.display", "shadow.point"},
                                {"renderer.displayLayer", "6"},
                                {"lights.emitterSamples", "1"},
                                {"shadow.cubeSize", "8"}});
    params.visitParams(setter);
    setter.finish();
    Renderer renderer(test::shaders(), scene, params, createTechnique("direct"));
    CHECK_THROWS_WITH(renderer.renderFrame(scene.cameras[0], 16, 16),
                      Catch::Contains("renderer.displayLayer") && Catch::Contains("shadow.point"));
}

TEST_CASE("a technique's texture views: rectangle, layer, colour, normal and count kinds", "[image][views][numbers]")
{
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("cornell");
    auto technique = std::make_unique<ViewTechnique>();
    const ViewTechnique& views = *technique;
    Renderer renderer(test::shaders(), scene, RendererParams{}, std::move(technique));
    const std::vector<float> rgba = readLayers(views.texture(), GL_RGBA, 0, ViewTechnique::kLayers);
    auto texel = [&](int layer, int tx, int ty) {
        const std::size_t i =
            ((static_cast<std::size_t>(layer) * ViewTechnique::kHeight + ty) * ViewTechnique::kWidth + tx) * 4;
        return glm::vec4(rgba[i], rgba[i + 1], rgba[i + 2], rgba[i + 3]);
    };
    const float exposure = 1.5f;
    renderer.applySettings(Settings{{"renderer.exposure", "1.5"}});

    struct Case {
        std::string view;
        int layers;
        glm::ivec4 rect;
        int layerOffset;
        std::function<glm::ivec3(glm::vec4)> expected;
    };
    const Case cases[] = {
        {"viewtest.color",
         1,
         {2, 1, 5, 4},
         1,
         [&](glm::vec4 v) {
             const glm::vec3 t = shared::toneMapReinhard(glm::vec3(v), exposure);
             return glm::ivec3(toByte(shared::encodeSRGB(t.r)), toByte(shared::encodeSRGB(t.g)),
                               toByte(shared::encodeSRGB(t.b)));
         }},
        {"viewtest.normal",
         2,
         {0, 0, 8, 6},
         0,
         [](glm::vec4 v) {
             return glm::ivec3(toByte(v.x * 0.5f + 0.5f), toByte(v.y * 0.5f + 0.5f), toByte(v.z * 0.5f + 0.5f));
         }},
        {"viewtest.count",
         1,
         {0, 0, 8, 6},
         0,
         [](glm::vec4 v) { return glm::ivec3(toByte(std::log2(1.0f + std::max(v.r, 0.0f)) / std::log2(101.0f))); }},
    };
    for (const Case& c : cases) {
        const std::set<std::string> changed = renderer.applySettings(Settings{{"renderer.display", c.view}});
        CHECK(changed.count("renderer.display") == 1);
        renderer.renderFrame(scene.cameras[0], 37, 29);
        int shown = 0;
        const int worst = compareDisplay(
            renderer, c.layers, c.rect,
            [&](int layer, int tx, int ty) { return c.expected(texel(layer + c.layerOffset, tx, ty)); }, shown);
        MEASURED(c.view << " at 37x29: worst byte difference " << worst << ", " << shown << " pixels show a layer");
        // Measured 0 for all three; 1 allows another driver's float -> unorm rounding and its
        // pow and log2 (GLSL's precision for them is looser than the CPU's).
        CHECK(worst <= 1);
        CHECK(shown > 0);
    }
    // Names are checked against the technique's views too; the error lists them.
    CHECK_THROWS_WITH(renderer.applySettings(Settings{{"renderer.display", "viewtest.bogus"}}),
                      Catch::Contains("viewtest.count") && Catch::Contains("shadow.point"));
}

TEST_CASE("renderer.antialias: FXAA leaves flat pixels byte for byte and moves edges towards a supersampled image",
          "[image][antialias][numbers]")
{
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("cutout"); // the leaf's outline, its holes and its shadow
    const int width = 96, height = 72, factor = 4;
    auto render = [&](const std::string& antialias, int w, int h) {
        RendererParams params;
        // Shadow cubes at 2048^2: the shadow's own staircase (256^2 texels are larger than the
        // supersampled image's pixels) is not the rasterizer's aliasing that FXAA is for.
        ParamSetter setter(Settings{{"renderer.antialias", antialias}, {"shadow.cubeSize", "2048"}});
        params.visitParams(setter);
        setter.finish();
        Renderer renderer(test::shaders(), scene, params, createTechnique("direct"));
        renderer.renderFrame(scene.cameras[0], w, h);
        return renderer.readDisplay();
    };
    const ImageRGBA8 plain = render("none", width, height);
    const ImageRGBA8 smoothed = render("fxaa", width, height);
    const ImageRGBA8 fine = render("none", factor * width, factor * height);
    auto luma = [](const ImageRGBA8& image, int x, int y) {
        x = std::clamp(x, 0, image.width - 1);
        y = std::clamp(y, 0, image.height - 1);
        const std::uint8_t* p = &image.pixels[(static_cast<std::size_t>(y) * image.width + x) * 4];
        return (0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2]) / 255.0;
    };
    // The supersampled image, box-filtered to the output size (in the encoded values FXAA works on).
    auto reference = [&](int x, int y, int c) {
        double sum = 0.0;
        for (int j = 0; j < factor; ++j)
            for (int i = 0; i < factor; ++i)
                sum += fine.pixels[(static_cast<std::size_t>(factor * y + j) * fine.width + factor * x + i) * 4 + c];
        return sum / (factor * factor);
    };
    int flat = 0, flatChanged = 0, edges = 0, aliased = 0;
    double plainError = 0.0, smoothedError = 0.0, plainAliased = 0.0, smoothedAliased = 0.0;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            // FXAA's own test (passes/fxaa.frag step 1) on the unfiltered image.
            const double c = luma(plain, x, y), n = luma(plain, x, y - 1), s = luma(plain, x, y + 1);
            const double e = luma(plain, x + 1, y), w = luma(plain, x - 1, y);
            const double lowest = std::min({c, n, s, e, w}), highest = std::max({c, n, s, e, w});
            const std::size_t at = (static_cast<std::size_t>(y) * width + x) * 4;
            if (highest - lowest < std::max(0.0625, highest * 0.125)) {
                ++flat;
                for (int k = 0; k < 4; ++k) flatChanged += plain.pixels[at + k] != smoothed.pixels[at + k] ? 1 : 0;
                continue;
            }
            ++edges;
            double plainHere = 0.0, smoothedHere = 0.0;
            for (int k = 0; k < 3; ++k) {
                plainHere += std::abs(plain.pixels[at + k] - reference(x, y, k));
                smoothedHere += std::abs(smoothed.pixels[at + k] - reference(x, y, k));
            }
            plainError += plainHere;
            smoothedError += smoothedHere;
            // Aliased: the unfiltered pixel is off the supersampled one by over 16 levels a channel.
            if (plainHere > 3 * 16.0) {
                ++aliased;
                plainAliased += plainHere;
                smoothedAliased += smoothedHere;
            }
        }
    MEASURED("FXAA on cutout (96x72, direct): " << flat << " flat pixels, " << flatChanged << " bytes of them changed; "
                                                << edges << " edge pixels, mean |error| against 4x4 supersampling "
                                                << plainError / (3 * edges) << " without, "
                                                << smoothedError / (3 * edges) << " with FXAA; over the " << aliased
                                                << " aliased ones " << plainAliased / (3 * aliased) << " and "
                                                << smoothedAliased / (3 * aliased));
    CHECK(flatChanged == 0);            // interiors unchanged, byte for byte
    REQUIRE(edges > width * height / 50); // the scene has edges to smooth
    // Edges move towards the supersampled image: measured 0.85x the error over every pixel FXAA
    // treats (soft gradients such as the spot's cone edge included) and 0.43x over the aliased ones.
    CHECK(smoothedError < 0.93 * plainError);
    REQUIRE(aliased > 50);
    CHECK(smoothedAliased < 0.6 * plainAliased);
}
