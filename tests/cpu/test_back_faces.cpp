// The back-face rule on the CPU side (scene.h Material::doubleSided; docs/back-faces.md): rays pass
// through the back of a single-sided surface and stop on its front, for closest hits and shadow rays;
// a double-sided surface stops them from both sides; a mirroring instance's front is its clockwise
// side (glTF). Surface samples carry the front normal and the single-sided flag. On the built-in
// one-sided scene: panel "facing" (instance 1, x in [-2.2, -0.2]) with its front +z, panel "away"
// (instance 2, x in [0.2, 2.2], mirrored) with its front -z; the rasterizer's side is in
// tests/image/test_back_faces.cpp.
#include <catch2/catch.hpp>

#include "core/scene/builtin_scenes.h"
#include "core/scene/surface.h"
#include "core/scene/surface_points.h"
#include "core/trace/ray_scene.h"

using namespace vplgi;

namespace {

constexpr int kFacing = 1, kAway = 2, kPanelMaterial = 1;

// The instance a ray from `from` towards `to` hits first (-1: none), and whether it is occluded.
std::pair<int, bool> cast(const RayScene& rays, glm::vec3 from, glm::vec3 to, Looker looker)
{
    Ray ray;
    ray.origin = from;
    ray.direction = glm::normalize(to - from);
    ray.tMin = 1e-4f;
    ray.tMax = 1e30f;
    const Hit hit = rays.intersect(ray, looker);
    return {hit.valid() ? hit.instance : -1, rays.occluded(ray, looker)};
}

} // namespace

TEST_CASE("back faces: the looker does not see the back of a single-sided surface, mirrored instances turn the "
          "front", "[trace]")
{
    Scene scene = makeBuiltinScene("one-sided");
    REQUIRE(scene.instances[kAway].winding() < 0.0f);
    REQUIRE(scene.instances[kFacing].winding() > 0.0f);
    REQUIRE_FALSE(scene.materials[kPanelMaterial].doubleSided);
    {
        const RayScene rays(scene);
        // Horizontal rays at y = 1 through each panel's centre, from +z and from -z. The origin looks
        // (a camera): fronts stop the ray, backs do not.
        const glm::vec3 facingFront(-1.2f, 1.0f, 2.0f), facingBack(-1.2f, 1.0f, -2.0f);
        const glm::vec3 awayBack(1.2f, 1.0f, 2.0f), awayFront(1.2f, 1.0f, -2.0f);
        const std::pair<int, bool> none(-1, false);
        CHECK(cast(rays, facingFront, facingBack, Looker::Origin) == std::make_pair(kFacing, true));
        CHECK(cast(rays, facingBack, facingFront, Looker::Origin) == none);
        CHECK(cast(rays, awayBack, awayFront, Looker::Origin) == none);
        CHECK(cast(rays, awayFront, awayBack, Looker::Origin) == std::make_pair(kAway, true));
        // The end looks (a shadow ray towards a light): the side facing the end decides.
        CHECK(cast(rays, facingBack, facingFront, Looker::End) == std::make_pair(kFacing, true));
        CHECK(cast(rays, facingFront, facingBack, Looker::End) == none);
        CHECK(cast(rays, awayFront, awayBack, Looker::End) == none);
        CHECK(cast(rays, awayBack, awayFront, Looker::End) == std::make_pair(kAway, true));
        // Nobody looks (a bounce): both sides stop it.
        CHECK(cast(rays, facingBack, facingFront, Looker::None) == std::make_pair(kFacing, true));
        CHECK(cast(rays, awayBack, awayFront, Looker::None) == std::make_pair(kAway, true));
        // The spot light and the floor behind each panel: shadowed behind "facing" only, whichever end
        // the segment starts from (the light looks either way).
        const glm::vec3 light = scene.lights[0].position;
        const glm::vec3 behindFacing(-1.2f, 0.0f, -1.0f), behindAway(1.2f, 0.0f, -1.0f);
        CHECK_FALSE(rays.visible(light, behindFacing, Looker::Origin));
        CHECK_FALSE(rays.visible(behindFacing, light, Looker::End));
        CHECK(rays.visible(light, behindAway, Looker::Origin));
        CHECK(rays.visible(behindAway, light, Looker::End));
        CHECK_FALSE(rays.visible(behindAway, light, Looker::None));
        // The surface seen on the mirrored panel's front has the front's normal, -z.
        Ray ray;
        ray.origin = {1.2f, 1.0f, -2.0f};
        ray.direction = {0.0f, 0.0f, 1.0f};
        ray.tMin = 1e-4f;
        ray.tMax = 1e30f;
        const Hit hit = rays.intersect(ray, Looker::Origin);
        REQUIRE(hit.valid());
        const SurfacePoint s = surfaceAt(scene, hit, -ray.direction);
        CHECK(s.normal.z == Approx(-1.0f).margin(1e-5));
        CHECK(s.geometricNormal.z == Approx(-1.0f).margin(1e-5));
    }
    // Double-sided, the same panels stop rays from both sides for every looker.
    scene.materials[kPanelMaterial].doubleSided = true;
    const RayScene rays(scene);
    for (const Looker looker : {Looker::Origin, Looker::End}) {
        CHECK(cast(rays, {-1.2f, 1.0f, -2.0f}, {-1.2f, 1.0f, 2.0f}, looker) == std::make_pair(kFacing, true));
        CHECK(cast(rays, {1.2f, 1.0f, 2.0f}, {1.2f, 1.0f, -2.0f}, looker) == std::make_pair(kAway, true));
    }
    CHECK_FALSE(rays.visible(scene.lights[0].position, {1.2f, 0.0f, -1.0f}, Looker::Origin));
}

TEST_CASE("back faces: surface samples carry the front's normal (mirrored: clockwise)", "[trace]")
{
    const Scene scene = makeBuiltinScene("one-sided");
    const SurfacePoints points = sampleSurfacePoints(scene, 4000, 7);
    int facing = 0, away = 0, floor = 0;
    for (std::size_t i = 0; i < points.positions.size(); ++i) {
        const glm::vec3 p = points.positions[i], n = points.normals[i];
        if (p.y < 1e-4f) { // the floor
            ++floor;
            CHECK(n.y == Approx(1.0f).margin(1e-5));
        } else {
            (p.x < 0.0f ? facing : away) += 1;
            CHECK(n.z == Approx(p.x < 0.0f ? 1.0f : -1.0f).margin(1e-5));
        }
    }
    CHECK(facing > 100);
    CHECK(away > 100);
    CHECK(floor > 1000);
}
