// Imperfect shadow maps (Ritschel et al. 2008): approximate visibility for thousands of virtual
// lights at once, from a point sample of the scene instead of its triangles. VSGL (papers/002) uses
// them for its N virtual lights (section 4: 8192 points and 64^2 texels per map).
//
// Intro
// -----
// Rendering the scene once per light (SMCIR's hemisphere cubes, gl/passes/vpl_shadow_maps.h) costs
// triangles x lights. An ISM instead splats a small, different random subset of surface points into
// each light's paraboloid map, nearest distance wins: each map alone is full of holes and misses thin
// features, but the errors of different lights are independent, and the shading sums over many
// lights average them. Pull-push then fills the holes from the coarser levels of a pyramid. Ritschel
// et al. splat one-texel points; ours splats each point as the disk of its tangent plane it stands
// for (footprint splats, glsl/shared/ism.h; `splatScale`, 0 = one-texel points), because a hole in a
// near wall is not empty but shows the farther surfaces behind it, which pull-push cannot repair. The maps are SMCIR's paraboloid distance maps exactly (glsl/shared/vpl.h: frame
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
//  VSGL's VSGLight (7 vec4s, r^2 in the position's w, valid in the normal's: validVec4 1,
//  radius2Vec4 0). A light with a radius r_i (a VSGL stands for a footprint of RSM texels around its
//  mean position) does not get the points within ownRadius x r_i: they are the surface it stands
//  for, and where the footprint spans a convex edge its mean lies inside the object, whose walls
//  would enclose it (ours; VSGL's cornell bias -15.9% with them, -10.1% without, 4 seeds:
//  docs/vsgl.md). Point lights (vpl-brsm, r_i = 0) keep every point.
//  Points: P = params.points (default 8192 x 64 = 524288, 8 MiB: a vec3 and a packed normal each). Light i takes the run of
//  pointsPerMap points starting at i * pointsPerMap mod P (wrapping), so P / pointsPerMap disjoint
//  subsets; with VSGL's N = 1024 each serves 16 lights, which sit at other places and see the same
//  points through other maps, so their holes still differ. Consecutive points are i.i.d. uniform
//  over the area, so every run is a uniform sample. More subsets cost memory and upload only.
//  Splat: a compute pass with imageAtomicMin on the distance's float bits (positive floats order
//  like their bits) through an r32ui binding of the r32f maps (compatible by size): a depth test,
//  order-independent. Each point writes its own distance into the texel of its direction (the texel
//  the lookup reads: both go through vplParaboloidTexel) and, with splatScale > 0, the distance to its
//  tangent plane into every texel whose centre lies in the image of its disk of radius splatScale x
//  sqrt(A / (pi pointsPerMap)) (A: the scene's area; an ellipse, its bounding box cut to
//  splatMaxExtent texels), the arithmetic of glsl/shared/ism.h shared with the test's CPU twin.
//  Rasterised GL_POINTS would need the atlas squeeze and clip planes of the shadow atlas for every
//  point. Points within kISMHorizonCosine of the light's tangent plane (its own surface) are skipped.
//  The points carry their geometric normal (octahedral, snorm 2 x 16 bits beside the position).
//  Pull-push: glsl/shared/ism.h (the arithmetic, shared with the test's CPU twin). Levels 1 ..
//  pullPushLevels of the atlas texture hold the pyramid: with a power-of-two map size and
//  tilesPerRow, level l of the atlas is every tile's level l in place. A hole larger than about
//  2^pullPushLevels texels stays empty (log2(mapSize) fills every hole of a map with any point).
//  Defaults, measured against Embree per light-receiver pair (tests/gl/test_imperfect_shadow_maps.cpp,
//  "ISM: visibility in the Cornell box*" and "ISM: the sealed room's*", which print every variant;
//  the tables are in docs/vsgl.md, "Imperfect shadow maps" and "... with planes"): footprint splats
//  at splatScale 1.25, stratified points, no pull-push, planes, the near field (below: 5.4% of the
//  Cornell pairs disagree, 0.03% of the sealed room's; 0.44% without the near field). With depth lookups, in the Cornell box 6.8% of the pairs disagree (one-texel points
//  with 4 pull-push levels, the previous default: 13.9%; exact 64^2 maps: 3.9%); in the sealed room
//  1.8% (17.6%), 1.4% lit though occluded (17.3%). Pull-push, once the splats close the holes, only
//  adds false shadows (Cornell: 9.6% of the pairs disagree with 4 levels): it fills the directions
//  with no surface (the box's open front) with the foreground's distance. Larger disks leak less
//  and shadow more at silhouettes (they overhang a surface's edge by up to their radius): scale 2
//  gives 1.0% false lit in the sealed room but -3.3% of visible light in the Cornell box; scale
//  1.25 is where the image-level bias over the built-in scenes was smallest (docs/vsgl.md). For depth
//  lookups the depth bias stays 0.1: 0.02 halves what still leaks in the sealed room (at the wall
//  joints, where a receiver lies within 10% of its distance behind the wall) but adds false shadows
//  in the box; planes replace it.
//  Cost: update() of 1024 lights x 8192 points at 64^2 took 175 ms on llvmpipe on an idle 2-core
//  machine with depth lookups (splat 106, push 53, pull 14, clear 1 ms); planes make the "shadow
//  maps" pass 3.6x as long (the second splat pass, gap filling: docs/vsgl.md). The paper reports
//  8-12 ms for its AISMs on a 2011 GPU.
//  Planes (`planes`, ours): the splat runs twice; the second pass writes, into a second r32ui atlas,
//  the packed normal of the point whose distance won each texel, and every texel a point writes holds
//  the distance along the texel's central direction to the point's plane (unclamped, so that the
//  distance and the normal describe one plane; a disk's texel whose ray meets the plane outside the
//  disk, or at a grazing angle, is not written). The lookup (glsl/lib/ism.glsl) then judges a
//  receiver by the planes of the four texels around its direction (glsl/shared/plane_visibility.h,
//  the rule LightSkin's visibility maps use; a hit up to the disks' radius behind a plane counts as in
//  front of it for the rule's cut, since a disk overhangs the corner where its wall meets the next)
//  instead of one texel's depth with the relative depthBias and normalOffset, which it does not use.
//  A texel without a normal (filled by pull-push) counts as a plane facing the light. Beside a
//  parallel step of its surface (another of the four texels sees a parallel face up to edgeMargin x
//  the distance behind its plane, which does not hide the receiver) a texel hides a receiver only
//  beyond that margin: a texel is 2-4 / N radians wide, and terraces under it (the canyon's, 21 m
//  away under 2.6 m texels) are not in the map. Gap filling
//  (`gapReach`, ours, passes/ism_gaps.comp into copies, then copied back): a texel whose two opposite
//  neighbours up to gapReach texels away saw one plane that its ray crosses before its own hit takes
//  that plane; at the rim one neighbour suffices when the other lies beyond it. Lights with extent
//  leave out only their own surface (`ownSurfaceOnly`). Why: the relative bias let a receiver within
//  10% of its distance behind a wall count as lit, and the gaps between splats let light through the
//  walls (the sealed room's closed side); measured per pair and per image in docs/vsgl.md,
//  "Imperfect shadow maps with planes".
//  Near field (`nearField`, ours): a light's run holds one point per A / pointsPerMap of surface, so
//  the surfaces within a few such spacings of the light (the wall beside a light near a corner, seen
//  from centimetres) fall between its disks, and what lies behind shows through: in the sealed room
//  0.42% of the light-receiver pairs came out lit though occluded, at the corners. Every point of the
//  whole set P within nearField x sqrt(A / pointsPerMap) of the light is splatted too, with the whole
//  set's smaller disks (splatScale sqrt(A / (pi P))). The points are hashed by grid cells of that
//  radius at setScene (glsl/shared/ism.h, ismNearSlot; a counting sort by slot); 27 more invocations
//  per light each take one of the 3^3 cells around it. Sealed room at nearField 1.5: 0.0001 lit though
//  occluded, 0.0003 disagreeing (0.0042, 0.0044 without); Cornell 5.4% either way (tests/gl/test_imperfect_shadow_maps.cpp,
//  whose CPU twin finds the near points by brute force). Images: docs/vsgl.md, "The near field".
//  Reach (`reach`, with planes, ours): a disk centred near the edge of its surface overhangs it, and
//  with planes the overhang is a plane where no surface is, which hides every receiver behind it (on
//  Sponza's columns and arches 29% of the pairs Embree sees lit). setScene finds, once, how far each
//  point's surface continues in 8 sectors of its tangent plane (core/scene/surface_points.h,
//  surfaceReach, from the point set itself) and the splat writes no texel beyond it
//  (glsl/shared/ism.h, ismWithinReach) plus a margin of `reachMargin` set spacings (the probes round
//  down: without it strips along edges stayed uncovered and the sealed rooms' closed sides leaked
//  twice as much); a hit cache keeps the last four point sets' reach. Sponza -37% -> -30% over 8 seeds (-25%
//  without the margin). The default since 2026-12-08. Measured per pair and per image in
//  docs/vsgl.md, "Reach" and "The margin".
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
    int pullPushLevels = 0;          // pyramid levels above the map for hole filling; 0 = none [0, log2 mapSize]
    float pullPushDepthRange = 3.0f; // pull-push ignores texels farther than (1 + this) x the nearest one
    float depthBias = 0.1f;          // lookup: lit while distance <= stored (1 + depthBias) (SMCIR's test; Details)
    float normalOffset = 1.0f;       // lookup: lift along the normal [map texels at the distance] (as SMCIR's)
    float splatScale = 1.25f;        // footprint splats: disk radius / sqrt(A / (pi pointsPerMap)); 0 = one texel (ours)
    float splatMaxExtent = 8.0f;     // a disk's bounding box is cut to this half-size [texels] (ours)
    bool stratified = true;          // each run of pointsPerMap points a stratified sample of the area (ours)
    float ownRadius = 1.0f;          // lights with extent: points within this x their radius are not splatted (ours)
    bool ownSurfaceOnly = true;      // ... of those, only the light's own surface (ismOwnSurface) (ours)
    bool planes = true;              // texels keep the winning point's plane; the lookup tests planes (ours)
    float edgeMargin = 0.1f;         // planes: margin beside a parallel step, relative to the distance (ours)
    int gapReach = 4;                // planes: gap filling from opposite neighbours up to this many texels away; 0 = none (ours)
    float nearField = 1.5f;          // every point of P within this x sqrt(A / pointsPerMap) of a light is splatted too; 0 = none (ours)
    bool reach = true;               // planes: a disk stops where its point's surface does (surfaceReach) (ours; docs/vsgl.md "Reach")
    float reachMargin = 1.5f;        // reach: a disk runs this many set spacings past it (ismWithinReach margin) (ours)
    std::uint32_t seed = 1;          // the point set's random stream

    // Keys prefix + "Points", "PointsPerMap", "MapSize", "PullPushLevels", "PullPushDepthRange",
    // "DepthBias", "NormalOffset", "SplatScale", "SplatMaxExtent", "Stratified", "OwnRadius",
    // "Planes", "EdgeMargin", "GapReach", "NearField", "Reach", "Seed" (prefix "vsgl.ism" gives
    // "vsgl.ismPoints").
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
    // radius2Vec4: the record's vec4 whose w holds the light's squared radius (VSGL's r_i^2: points
    // within ownRadius x r_i are its own footprint and are not splatted), -1 for point lights.
    void update(const gl::Buffer& lights, int count, int strideVec4, int validVec4, int radius2Vec4 = -1,
                gl::PassTimer* timer = nullptr);
    // Pull-push alone on the maps of lights 0 .. count-1 (update() runs it after the splat; tests
    // run it on maps they wrote).
    void fillHoles(int count, gl::PassTimer* timer = nullptr);
    // The maps (nearest sampler) at kUnitISM, and the uniforms of glsl/lib/ism.glsl on `program`.
    void bindForReading(const gl::Program& program) const;

    const ISMParams& params() const { return mParams; }
    const ShadowAtlasLayout& layout() const { return mLayout; }
    const gl::Texture& maps() const { return mMaps; } // r32f 2D array, pullPushLevels + 1 levels
    // With params.planes: r32ui 2D array in the maps' layout, level 0 only: the packed normal of each
    // texel's winning point (glsl/shared/ism.h, ismPackNormal), kISMNoNormal where none won it.
    const gl::Texture& normals() const { return mNormals; }
    float reachMargin() const { return mReachMargin; } // [m] ISMParams::reachMargin x the set's spacing (0 without the reach)
    const gl::Buffer& points() const { return mPoints; } // per point: vec3 position, uint packed normal; with the reach a second uvec4 (its profile)
    float splatRadius() const { return mSplatRadius; }   // after setScene
    // The near field's radius and its points' disk radius [m] (after setScene; 0 without a near field).
    float nearRadius() const { return mNearSlotCount > 0 ? mNearRadius : 0.0f; }
    float nearSplatRadius() const { return mNearSlotCount > 0 ? mNearSplatRadius : 0.0f; }
    int maxLights() const { return mMaxLights; }

private:
    void clearMaps(int count, gl::PassTimer* timer) const; // level 0 of lights 0 .. count-1: no occluder (no normal)
    void fillGaps(const gl::Buffer& lights, int count, int strideVec4, gl::PassTimer* timer);
    // The (at most three) rectangles of the atlas that the tiles of lights 0 .. count-1 cover: f(x, y,
    // layer, width, height, depth) in tiles.
    template <typename F> void forEachTileRectangle(int count, F f) const;

    ISMParams mParams;
    int mMaxLights = 0;
    ShadowAtlasLayout mLayout;
    gl::Texture mMaps;
    gl::Texture mNormals; // params.planes only
    gl::Texture mGapMaps, mGapNormals; // params.planes && gapReach > 0: gap filling's output, copied back
    float mLift = 0.0f;   // the plane rule's absolute margin [m]: 1e-4 x the scene's diagonal (after setScene)
    gl::Sampler mSampler;
    gl::Buffer mPoints;
    int mPointStride = 1; // uvec4s a point in mPoints: 2 with the reach
    float mReachMargin = 0.0f; // ISMParams::reachMargin x the set's spacing [m]
    int mPointCount = 0;
    float mSplatRadius = 0.0f; // world radius of a point's disk [m] (splatScale sqrt(A / (pi pointsPerMap)))
    // Near field (params.nearField > 0): the points hashed by cells of edge mNearRadius (glsl/shared/ism.h,
    // ismNearSlot), indices sorted by slot, each slot's first index.
    gl::Buffer mNearIndices, mNearSlots;
    float mNearRadius = 0.0f;     // [m]
    float mNearSplatRadius = 0.0f; // splatScale sqrt(A / (pi P)) [m]
    glm::vec3 mNearOrigin{0.0f};
    float mNearInverseEdge = 0.0f; // 1 / the cells' edge, a hair more than mNearRadius (ismNearCell)
    int mNearSlotCount = 0;
    ComputePass mSplat;
    ComputePass mPull;
    ComputePass mPush;
    ComputePass mGaps;
};

} // namespace vplgi
