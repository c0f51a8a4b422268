// Imperfect shadow maps (Ritschel et al. 2008): approximate visibility for thousands of virtual
// lights at once, from a point sample of the scene instead of its triangles. VSGL (papers/002) uses
// them for its N virtual lights (section 4: 8192 points and 64^2 texels per map).
//
// Intro
// -----
// Rendering the scene once per light (SMCIR's hemisphere cubes, gl/passes/vpl_shadow_maps.h) costs
// triangles x lights. An ISM instead splats a small, different random subset of surface points into
// each light's paraboloid map as one-texel points, nearest distance wins: each map alone is full of
// holes and misses thin features, but the errors of different lights are independent, and the
// shading sums over many lights average them. Pull-push then fills the holes from the coarser levels
// of a pyramid. The maps are SMCIR's paraboloid distance maps exactly (glsl/shared/vpl.h: frame
// about the light's normal, texel, r32f distance [m], kVPLNoOccluder = nothing), so a shading pass
// looks them up with the same arithmetic (glsl/lib/ism.glsl: ismVisibility).
//
// Overview
// --------
//  ImperfectShadowMaps(shaders, params, maxLights)  the map atlas: one tile per light, with
//                                   pullPushLevels coarser mip levels for the pyramid
//  setScene(scene)                  params.points points uniform over the surface area
//                                   (core/scene/surface_points.h), uploaded once
//  update(lights, count, stride)    the maps of lights 0..count-1: clear (glClearTexSubImage) ->
//                                   splat each light's pointsPerMap points -> pull -> push
//                                   (compute passes ism_splat, ism_pull, ism_push .comp)
//  bindForReading(program)          the maps at kUnitISM + the uniforms of glsl/lib/ism.glsl
//
// Details
// -------
//  Lights: an SSBO of records of `stride` vec4s whose first two hold the xyz position and the xyz
//  unit normal; the w of vec4 `validVec4` is 0 for an empty record, which gets an empty map
//  (visible from everywhere): SMCIR's GpuVPL (3 vec4s, valid in the position's w: validVec4 0) and
//  VSGL's VSGLight (6 vec4s, r^2 in the position's w, valid in the normal's: validVec4 1).
//  Points: P = params.points (default 8192 x 64 = 524288, 8 MiB as vec4). Light i takes the run of
//  pointsPerMap points starting at i * pointsPerMap mod P (wrapping), so P / pointsPerMap disjoint
//  subsets; with VSGL's N = 1024 each serves 16 lights, which sit at other places and see the same
//  points through other maps, so their holes still differ. Consecutive points are i.i.d. uniform
//  over the area, so every run is a uniform sample. More subsets cost memory and upload only.
//  Splat: a compute pass with imageAtomicMin on the distance's float bits (positive floats order
//  like their bits) through an r32ui binding of the r32f maps (compatible by size). This is a
//  one-texel point with a depth test, order-independent, and it lands in the texel the lookup reads
//  (both go through vplParaboloidTexel); rasterised GL_POINTS would need the atlas squeeze and clip
//  planes of the shadow atlas for every point. Points within kISMHorizonCosine of the light's
//  tangent plane (its own surface) are skipped.
//  Pull-push: glsl/shared/ism.h (the arithmetic, shared with the test's CPU twin). Levels 1 ..
//  pullPushLevels of the atlas texture hold the pyramid: with a power-of-two map size and
//  tilesPerRow, level l of the atlas is every tile's level l in place. A hole larger than about
//  2^pullPushLevels texels stays empty (log2(mapSize) fills every hole of a map with any point).
//  Defaults measured in the Cornell box against Embree (tests/gl/test_imperfect_shadow_maps.cpp,
//  test case "ISM: visibility in the Cornell box against Embree rays", which prints the numbers
//  below for 0, 2, 4 and 6 pull-push levels: ./build/tests/vplgi_tests_gl "ISM: visibility in the
//  Cornell box*"; 64 lights on the surfaces x 552 receivers; "mean" = the mean over receivers of
//  the visible fraction of their lights, ISM minus Embree): pull-push cuts the light leak of the
//  holes (mean +0.044 without, +0.008 with 4 levels) for a few more false shadows; 2, 4 and 6
//  levels differ little there, and 4 leaves directions with no surface within about 16 texels
//  (sky) empty. Depth range and depth bias were chosen with the same comparison at values the test
//  does not run (no command prints them, so no figures here): ignoring texels beyond 1.1x the
//  nearest shadowed too much (holes on surfaces seen at grazing angles took too near a
//  distance), a plain average leaked; 4x (3) came closest to 0 in the mean, and still gives a hole
//  on a depth edge the foreground's distance. Depth bias 0.1 rather than SMCIR's 0.02, which
//  shadowed too much (hole-filled distances are averages over a few texels); 0.2 leaks.
//  Cost: update() of 1024 lights x 8192 points at 64^2 took 175 ms on llvmpipe on an idle 2-core
//  machine (splat 106, push 53, pull 14, clear 1 ms; 0.2-0.5 s while other builds shared it). The
//  paper reports 8-12 ms for its AISMs on a 2011 GPU.
//  Determinism: no step depends on the order invocations run in (min is order-independent, the
//  other kernels write only their own texel), so the maps are bit-identical run to run.
//  Memory: maxLights tiles of mapSize^2 r32f plus a third for the pyramid: 1024 x 64^2 = 16 MiB
//  (+5.3 MiB). The tiles of 16384 lights (GL_MAX_ARRAY_TEXTURE_LAYERS >= 2048) fit because a layer holds
//  tilesPerRow^2 tiles (ShadowAtlas::chooseLayout).
//
// References
// ----------
//  T. Ritschel et al.: Imperfect Shadow Maps for Efficient Computation of Indirect Illumination,
//    SIGGRAPH Asia 2008 (MATH.md 10.2; the paper's text was not available here).
//  J. P. Grossman, W. Dally: Point Sample Rendering, EGWR 1998 (pull-push).
//  VSGL (papers/002) section 4; S. Brabec et al. 2002 (paraboloid maps, MATH.md 6.1).
#pragma once

#include <cstdint>
#include <string>

#include "../api/objects.h"
#include "../api/shader_loader.h"
#include "../api/timer.h"
#include "compute_pass.h"
#include "core/scene/scene.h"
#include "shadow_atlas.h"

namespace vplgi {

class ParamVisitor;

struct ISMParams {
    int points = 8192 * 64;          // P: surface points of the scene, shared by all maps [1, 2^24]
    int pointsPerMap = 8192;         // points splatted per light's map (VSGL section 4: 8192) [1, P]
    int mapSize = 64;                // paraboloid map resolution [texels], a power of two (section 4: 64) [4, 1024]
    int pullPushLevels = 4;          // pyramid levels above the map for hole filling; 0 = none [0, log2 mapSize]
    float pullPushDepthRange = 3.0f; // pull-push ignores texels farther than (1 + this) x the nearest one
    float depthBias = 0.1f;          // lookup: lit while distance <= stored (1 + depthBias) (SMCIR's test; Details)
    float normalOffset = 1.0f;       // lookup: lift along the normal [map texels at the distance] (as SMCIR's)
    std::uint32_t seed = 1;          // the point set's random stream

    // Keys prefix + "Points", "PointsPerMap", "MapSize", "PullPushLevels", "PullPushDepthRange",
    // "DepthBias", "NormalOffset", "Seed" (prefix "vsgl.ism" gives "vsgl.ismPoints").
    void visitParams(ParamVisitor& visitor, const std::string& prefix);
};

class ImperfectShadowMaps {
public:
    // Throws Error naming the numbers when the parameters are out of range or the maps of maxLights
    // lights do not fit the GL limits.
    ImperfectShadowMaps(const gl::ShaderLoader& shaders, const ISMParams& params, int maxLights);
    void reloadShaders(const gl::ShaderLoader& shaders);

    // Samples params.points points over the scene's surface (params.seed) and uploads them.
    void setScene(const Scene& scene);
    // Rebuilds the maps of lights 0 .. count-1 (count <= maxLights) from `lights`, records of
    // `strideVec4` vec4s (>= 2) each (see Details). With a timer, each kernel is a scope.
    void update(const gl::Buffer& lights, int count, int strideVec4, int validVec4, gl::PassTimer* timer = nullptr);
    // Pull-push alone on the maps of lights 0 .. count-1 (update() runs it after the splat; tests
    // run it on maps they wrote).
    void fillHoles(int count, gl::PassTimer* timer = nullptr);
    // The maps (nearest sampler) at kUnitISM, and the uniforms of glsl/lib/ism.glsl on `program`.
    void bindForReading(const gl::Program& program) const;

    const ISMParams& params() const { return mParams; }
    const ShadowAtlasLayout& layout() const { return mLayout; }
    const gl::Texture& maps() const { return mMaps; } // r32f 2D array, pullPushLevels + 1 levels
    const gl::Buffer& points() const { return mPoints; }
    int maxLights() const { return mMaxLights; }

private:
    void clearMaps(int count, gl::PassTimer* timer) const; // level 0 of lights 0 .. count-1: no occluder

    ISMParams mParams;
    int mMaxLights = 0;
    ShadowAtlasLayout mLayout;
    gl::Texture mMaps;
    gl::Sampler mSampler;
    gl::Buffer mPoints;
    int mPointCount = 0;
    ComputePass mSplat;
    ComputePass mPull;
    ComputePass mPush;
};

} // namespace vplgi
