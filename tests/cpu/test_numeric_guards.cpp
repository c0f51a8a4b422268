// Numeric guards (issue 13 part 6) on the CPU side: the display transform shared with the tone-map
// shader (glsl/shared/tonemap.h), the VPL intensity I = L / p (core/vpl/vpl.h) and the SMCIR
// sampler's published set; and large textures downscaled on load. Each case feeds what the guard is for and fails without it.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "core/scene/builtin_scenes.h"
#include "core/scene/image_downscale.h"
#include "core/scene/scene_loader.h"
#include "core/trace/ray_scene.h"
#include "core/vpl/smcir_sampler.h"
#include "core/vpl/vpl.h"
#include "glsl/shared/tonemap.h"

using namespace vplgi;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

bool isFinite(const glm::vec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

} // namespace

TEST_CASE("tone map: NaN and infinite radiance show black, finite values are unchanged", "[guards]")
{
    const float nan = std::nanf("");
    // Without the guard: inf -> inf * (1 / inf) = NaN, NaN -> NaN (clamp does not define either).
    for (const glm::vec3& bad : {glm::vec3(nan, 0.1f, 0.1f), glm::vec3(kInf, 0.0f, 0.0f), glm::vec3(kInf),
                                 glm::vec3(0.5f, kInf, -kInf), glm::vec3(-kInf)}) {
        const glm::vec3 shown = shared::toneMapReinhard(bad, 1.0f);
        INFO(bad.x << " " << bad.y << " " << bad.z);
        CHECK(shown == glm::vec3(0.0f));
    }
    // The guard changes nothing else: Reinhard on luminance, L_d = L / (1 + L), hue kept.
    const glm::vec3 c(1.0f, 0.5f, 0.25f);
    const float l = shared::luminanceRec709(c);
    const glm::vec3 shown = shared::toneMapReinhard(c, 1.0f);
    CHECK(shared::luminanceRec709(shown) == Approx(l / (1.0f + l)).epsilon(1e-6));
    CHECK(shown.x / shown.z == Approx(4.0f).epsilon(1e-6));
    // A huge but finite radiance is white, not black: the guard is for NaN and inf only.
    const glm::vec3 bright = shared::toneMapReinhard(glm::vec3(1e30f), 1.0f);
    CHECK(bright.x == Approx(1.0f).epsilon(1e-6));
}

TEST_CASE("VPL intensity: a zero, tiny or NaN density or radiance gives no infinite light", "[guards]")
{
    VPL vpl;
    vpl.valid = true;
    vpl.radiance = glm::vec3(1.0f);
    vpl.density = 0.0f; // no density estimate: no light, not 1/0
    CHECK(vpl.intensity() == glm::vec3(0.0f));
    vpl.density = 1e-39f; // a denormal density: 1 / 1e-39 overflows float (max 3.4e38)
    CHECK(vpl.intensity() == glm::vec3(0.0f));
    vpl.density = std::nanf("");
    CHECK(vpl.intensity() == glm::vec3(0.0f));
    vpl.density = 2.0f;
    vpl.radiance = glm::vec3(std::nanf(""), 1.0f, 1.0f);
    CHECK(vpl.intensity() == glm::vec3(0.0f));
    vpl.radiance = glm::vec3(1.0f, 2.0f, 4.0f); // the ordinary case: L / p
    CHECK(vpl.intensity() == glm::vec3(0.5f, 1.0f, 2.0f));
}

TEST_CASE("smcir: an overflowing radiance estimate publishes no infinite intensity", "[guards][smcir]")
{
    // The furnace with I0 = FLT_MAX: L_all = I0 / pi = 1.1e38 is still a float, but I = L / p with
    // p ~ 1 / (4 pi R^2) = 0.08 m^-2 is 1.4e39, past float's range, for every VPL.
    FurnaceParams furnace;
    furnace.intensity = std::numeric_limits<float>::max();
    furnace.rings = 24;
    furnace.segments = 48;
    const Scene scene = makeFurnace(furnace);
    const RayScene rays(scene);
    SMCIRParams params;
    params.vplCount = 64;
    params.warmupIterations = 1;
    SMCIRSampler sampler(scene, rays, params);
    sampler.initialize(scene.cameras[0]);
    sampler.step(scene.cameras[0]);
    int valid = 0, nonFinite = 0;
    for (const VPL& v : sampler.vpls().slots) {
        if (!v.valid) continue;
        ++valid;
        // What the CPU gather and the GPU upload compute; without the guard every one is +inf.
        if (!isFinite(v.radiance) || !std::isfinite(v.density) || (v.density > 0.0f && !isFinite(v.radiance / v.density)))
            ++nonFinite;
    }
    CHECK(valid == 64);
    CHECK(nonFinite == 0);
}

// --- Large textures are downscaled on load (core/scene/image_downscale.h) -------------------------

namespace {

std::string base64(const std::string& bytes)
{
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const std::uint32_t v = static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes[i])) << 16 |
                                static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes[i + 1])) << 8 |
                                static_cast<std::uint8_t>(bytes[i + 2]);
        for (int s = 18; s >= 0; s -= 6) out += kAlphabet[(v >> s) & 63u];
    }
    if (i < bytes.size()) {
        std::uint32_t v = static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes[i])) << 16;
        if (i + 1 < bytes.size()) v |= static_cast<std::uint32_t>(static_cast<std::uint8_t>(bytes[i + 1])) << 8;
        out += kAlphabet[(v >> 18) & 63u];
        out += kAlphabet[(v >> 12) & 63u];
        out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63u] : '=';
        out += '=';
    }
    return out;
}

void appendLE(std::string& s, std::uint32_t v, int bytes)
{
    for (int b = 0; b < bytes; ++b) s += static_cast<char>((v >> (8 * b)) & 0xffu);
}

// A 24-bit BMP of width x 1 whose texels alternate black and white (a 2:1 average is mid grey).
std::string stripeBmp(int width)
{
    const int row = (3 * width + 3) / 4 * 4;
    std::string bmp = "BM";
    appendLE(bmp, static_cast<std::uint32_t>(54 + row), 4);
    appendLE(bmp, 0, 4);
    appendLE(bmp, 54, 4);
    appendLE(bmp, 40, 4);
    appendLE(bmp, static_cast<std::uint32_t>(width), 4);
    appendLE(bmp, 1, 4);
    appendLE(bmp, 1, 2);
    appendLE(bmp, 24, 2);
    for (std::uint32_t v : {0u, static_cast<std::uint32_t>(row), 2835u, 2835u, 0u, 0u}) appendLE(bmp, v, 4);
    std::string pixels(static_cast<std::size_t>(row), '\0');
    for (int x = 0; x < width; x += 2)
        for (int c = 0; c < 3; ++c) pixels[static_cast<std::size_t>(3 * x + c)] = static_cast<char>(0xff);
    return bmp + pixels;
}

} // namespace

TEST_CASE("downscaleToFit halves with a 2x2 box until both edges fit", "[guards]")
{
    Image image;
    image.width = 9;
    image.height = 5;
    image.rgba.assign(9 * 5 * 4, 0);
    for (int x = 0; x < 9; x += 2) // white columns 0, 2, 4, 6, 8
        for (int y = 0; y < 5; ++y)
            for (int c = 0; c < 4; ++c) image.rgba[static_cast<std::size_t>((y * 9 + x) * 4 + c)] = 255;
    CHECK(downscaleToFit(image, 4, "test image", "a cap of 4"));
    // 9 x 5 -> 5 x 3 -> 3 x 2 (odd edges round up; the last texel is averaged with itself).
    CHECK(image.width == 3);
    CHECK(image.height == 2);
    REQUIRE(image.rgba.size() == 3u * 2u * 4u);
    // Column pairs (0,1), (2,3) average to 128, and again (128+128)/2: mid grey; the last column
    // (8, with itself) is white twice: 255.
    CHECK(static_cast<int>(image.rgba[0]) == 128);
    CHECK(static_cast<int>(image.rgba[2 * 4]) == 255);
    const Image before = image;
    CHECK_FALSE(downscaleToFit(image, 4, "test image", "a cap of 4")); // fits: untouched
    CHECK(image.rgba == before.rgba);
}

TEST_CASE("glTF: an image wider than kMaxImageEdge is downscaled on load", "[guards][scene_loader]")
{
    const int width = kMaxImageEdge + 2; // 8194 x 1: one halving gives 4097
    const float geometry[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, /* uv */ 0, 0, 1, 0, 0, 1};
    const std::string bin(reinterpret_cast<const char*>(geometry), sizeof geometry);
    const nlohmann::json doc = {
        {"asset", {{"version", "2.0"}}},
        {"buffers", {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}}},
        {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
                         {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}}}},
        {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"},
                        {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
                       {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}}}},
        {"images", {{{"name", "wide"}, {"uri", "data:image/bmp;base64," + base64(stripeBmp(width))}}}},
        {"textures", {{{"source", 0}}}},
        {"materials", {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"material", 0}}}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"scenes", {{{"nodes", {0}}}}},
        {"scene", 0}};
    const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                       ("vplgi-test-wide-image-" + std::to_string(::getpid()) + ".gltf");
    {
        std::ofstream file(path);
        file << doc.dump();
    }
    Scene scene;
    REQUIRE_NOTHROW(scene = loadGltf(path.string()));
    std::filesystem::remove(path);
    REQUIRE(scene.images.size() == 1);
    CHECK(scene.images[0].width == width / 2); // without the downscale: 8194
    CHECK(scene.images[0].height == 1);
    CHECK(scene.images[0].width <= kMaxImageEdge);
    // Black and white texel pairs average to mid grey.
    CHECK(static_cast<int>(scene.images[0].rgba[0]) == 128);
}
