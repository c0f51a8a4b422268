// The temporal experiment's inputs (SMCIR 5.2, Table 1): the tracked-pixel reference against the
// full image, the choice of tracked pixels in indirectly lit regions, and the animated sequences.
#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "core/scene/builtin_scenes.h"
#include "core/scene/scene_loader.h"
#include "core/trace/path_tracer.h"
#include "core/trace/ray_scene.h"
#include "core/util/error.h"
#include "core/util/metrics.h"
#include "measured.h"

using namespace vplgi;

namespace {

ImageRGBA32F greyImage(int w, int h, float value)
{
    ImageRGBA32F image;
    image.width = w;
    image.height = h;
    image.pixels.assign(static_cast<std::size_t>(w) * h * 4, value);
    return image;
}

void setGrey(ImageRGBA32F& image, int x, int y, float value)
{
    float* c = &image.pixels[(static_cast<std::size_t>(y) * image.width + x) * 4];
    c[0] = c[1] = c[2] = value;
}

// The name of the mesh the camera sees through the centre of pixel (x, y) (rows top to bottom), as
// the path tracer's camera rays go (core/trace/path_tracer.h: NDC from the pixel position).
std::string meshAtPixel(const Scene& scene, const RayScene& rays, const Camera& camera, int width, int height,
                        glm::ivec2 p)
{
    const glm::dmat4 worldFromClip = glm::inverse(glm::dmat4(
        camera.clipFromView(static_cast<float>(width) / static_cast<float>(height)) * camera.viewFromWorld()));
    const double ndcX = (p.x + 0.5) / width * 2.0 - 1.0, ndcY = 1.0 - (p.y + 0.5) / height * 2.0;
    const glm::dvec4 far = worldFromClip * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
    Ray ray;
    ray.origin = camera.position;
    ray.direction = glm::normalize(glm::vec3(glm::dvec3(far) / far.w) - camera.position);
    const Hit hit = rays.intersect(ray);
    if (!hit.valid()) return "";
    return scene.meshes[scene.instances[hit.instance].mesh].name;
}

} // namespace

TEST_CASE("the tracked-pixel reference is bit-identical to the full image's pixels", "[path_tracer][tracked]")
{
    Scene scene = makeBuiltinScene("cornell");
    RayScene rays(scene);
    const Camera& camera = scene.cameras[0];
    PathTracerParams params;
    params.mode = PathTracerParams::Mode::Clamped;
    params.clampGeometry = 400.0f;
    params.maxDepth = 4;
    params.untexturedBounces = true;
    params.spp = 40; // not a power of two: the full image's last pass is a partial one
    params.seed = 7;
    const int width = 16, height = 12;
    const ImageRGBA32F image = renderReference(scene, rays, camera, width, height, params).image;
    const std::vector<glm::ivec2> pixels{{0, 0}, {15, 11}, {8, 2}, {3, 9}, {8, 2}};
    const PixelReferenceResult tracked = renderReferencePixels(scene, rays, camera, width, height, pixels, params);
    REQUIRE(tracked.radiance.size() == pixels.size());
    CHECK(tracked.spp == params.spp);
    int nonBlack = 0;
    for (std::size_t k = 0; k < pixels.size(); ++k) {
        const float* expected = image.at(pixels[k].x, pixels[k].y);
        INFO("pixel (" << pixels[k].x << ", " << pixels[k].y << ")");
        // The same sample streams summed in the same order: equal to the last bit, not within noise.
        for (int c = 0; c < 3; ++c)
            CHECK(tracked.radiance[k][c] == expected[c]);
        nonBlack += tracked.radiance[k].g > 0.0f;
    }
    CHECK(nonBlack >= 3); // the comparison is not between black pixels

    // Another seed gives other values; pixels outside the image are an error.
    params.seed = 8;
    const PixelReferenceResult reseeded = renderReferencePixels(scene, rays, camera, width, height, {{8, 2}}, params);
    CHECK(reseeded.radiance[0] != tracked.radiance[2]);
    CHECK_THROWS_AS(renderReferencePixels(scene, rays, camera, width, height, {{16, 0}}, params), Error);
}

TEST_CASE("indirect tracked pixels: only indirectly lit interiors, spread out, deterministic", "[metrics][tracked]")
{
    // Left half: direct light dominates. Right half: indirect light dominates, except a dark band
    // at x = 24..27: no direct light and an indirect luminance tiny in absolute terms.
    const int w = 32, h = 20;
    ImageRGBA32F direct = greyImage(w, h, 0.0f), indirect = greyImage(w, h, 0.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool right = x >= 16, band = x >= 24 && x <= 27;
            setGrey(direct, x, y, !right ? 1.0f : band ? 0.0f : 0.1f);
            setGrey(indirect, x, y, !right ? 0.1f : band ? 0.001f : 0.5f);
        }
    const std::vector<glm::ivec2> chosen = indirectTrackedPixels(direct, indirect, 8);
    REQUIRE(chosen.size() == 8);
    CHECK(indirectTrackedPixels(direct, indirect, 8) == chosen);
    double closest = 1e9;
    for (std::size_t i = 0; i < chosen.size(); ++i) {
        const glm::ivec2 p = chosen[i];
        INFO("pixel " << i << " (" << p.x << ", " << p.y << ")");
        // The 3x3 means are indirectly lit for x in [17, 24] and [27, 30], y in [1, 18] (x = 16 sees
        // the direct half; x = 25, 26 have indirect >= direct = 0 but fall below the absolute floor,
        // 0.1 x 0.5); the eroded interiors are x in [18, 23] and [28, 29], y in [2, 17].
        CHECK(((p.x >= 18 && p.x <= 23) || p.x == 28 || p.x == 29));
        CHECK(p.y >= 2);
        CHECK(p.y <= 17);
        for (std::size_t j = 0; j < i; ++j)
            closest = std::min(closest, static_cast<double>(glm::length(glm::vec2(p - chosen[j]))));
    }
    // Farthest-point selection over two strips (6 x 16 and 2 x 16): 8 points end up >= 3 pixels apart.
    CHECK(closest >= 3.0);

    // Too few indirectly lit pixels: none (the caller falls back to the grid).
    const ImageRGBA32F dark = greyImage(w, h, 0.0f);
    CHECK(indirectTrackedPixels(direct, dark, 8).empty());
    CHECK_THROWS_AS(indirectTrackedPixels(direct, greyImage(w, h + 1, 0.0f), 8), Error);
}

TEST_CASE("on cornell the tracked pixels land in indirectly lit pixels, the ceiling among them",
          "[path_tracer][tracked][numbers]")
{
    // vplgi compare's estimate (16 spp, seed 1, Direct and Indirect modes), at a small size.
    Scene scene = makeBuiltinScene("cornell");
    RayScene rays(scene);
    const Camera& camera = scene.cameras[0];
    const int width = 40, height = 40;
    PathTracerParams params;
    params.spp = 16;
    params.seed = 1;
    params.maxDepth = 4;
    params.mode = PathTracerParams::Mode::Direct;
    const ImageRGBA32F direct = renderReference(scene, rays, camera, width, height, params).image;
    params.mode = PathTracerParams::Mode::Indirect;
    const ImageRGBA32F indirect = renderReference(scene, rays, camera, width, height, params).image;
    const std::vector<glm::ivec2> chosen = indirectTrackedPixels(direct, indirect, 8);
    REQUIRE(chosen.size() == 8);
    CHECK(indirectTrackedPixels(direct, indirect, 8) == chosen);

    // Each pixel's indirect share from a quieter estimate of that pixel alone.
    params.spp = 1024;
    params.seed = 99;
    params.mode = PathTracerParams::Mode::Direct;
    const std::vector<glm::vec3> d = renderReferencePixels(scene, rays, camera, width, height, chosen, params).radiance;
    params.mode = PathTracerParams::Mode::Indirect;
    const std::vector<glm::vec3> n = renderReferencePixels(scene, rays, camera, width, height, chosen, params).radiance;
    int onCeiling = 0;
    double smallestShare = 1.0;
    std::ostringstream where;
    for (std::size_t k = 0; k < chosen.size(); ++k) {
        const double yd = 0.2126 * d[k].r + 0.7152 * d[k].g + 0.0722 * d[k].b;
        const double yn = 0.2126 * n[k].r + 0.7152 * n[k].g + 0.0722 * n[k].b;
        const std::string mesh = meshAtPixel(scene, rays, camera, width, height, chosen[k]);
        onCeiling += mesh == "ceiling";
        smallestShare = std::min(smallestShare, yn / (yn + yd));
        where << " (" << chosen[k].x << "," << chosen[k].y << ") " << mesh << " " << yn / (yn + yd) << ";";
        CHECK(yn > 0.0);
    }
    MEASURED("cornell 40x40 tracked pixels, mesh and indirect share at 1024 spp:" << where.str());
    // The choice asks for a share >= 0.5 on 3x3 means of 16 spp; on the pixels themselves at 1024 spp
    // the smallest share measured 0.61 (a block's face; the ceiling's are 0.97-1.0). 0.4 leaves
    // room for the 16-spp noise of the choice without admitting directly lit pixels (share < 0.1).
    CHECK(smallestShare >= 0.4);
    CHECK(onCeiling >= 1); // lit only by bounced light: the light faces down
}

TEST_CASE("the temporal sequences animate what their names say", "[scene_loader][tracked]")
{
    namespace fs = std::filesystem;
    const fs::path scenes = fs::path(VPLGI_SOURCE_DIR) / "scenes";
    struct Sequence {
        const char* file;
        Animation::Target moves; // the one kind of target animated
    };
    for (const Sequence& sequence : {Sequence{"maze-moving-light.json", Animation::Target::Light},
                                     Sequence{"maze-walk.json", Animation::Target::Camera},
                                     Sequence{"cornell-moving-light.json", Animation::Target::Light}}) {
        INFO(sequence.file);
        const Scene scene = loadSceneFile((scenes / sequence.file).string()).scene;
        REQUIRE(scene.animations.size() == 1);
        const Animation& animation = scene.animations[0];
        CHECK(animation.targetKind == sequence.moves);
        // 60 frames at compare's default 30 fps span 2 s: the animation must last that long and move.
        REQUIRE(animation.duration() >= 2.0f);
        Scene start = scene, end = scene;
        applyAnimation(start, animation, 0.0f);
        applyAnimation(end, animation, 1.0f); // the middle of the 60 frames
        if (sequence.moves == Animation::Target::Light) {
            const Light* a = start.findLight(animation.targetName);
            const Light* b = end.findLight(animation.targetName);
            REQUIRE(a != nullptr);
            CHECK(glm::length(a->position - b->position) > 0.01f * RayScene(scene).sceneScale());
        } else {
            const Camera* a = start.findCamera(animation.targetName);
            const Camera* b = end.findCamera(animation.targetName);
            REQUIRE(a != nullptr);
            CHECK(glm::length(a->position - b->position) > 0.5f);
        }
    }
}
