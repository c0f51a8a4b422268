#include "imperfect_shadow_maps.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <list>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/packing.hpp>

#include "../api/debug.h"
#include "core/scene/surface_points.h"
#include "core/util/content_hash.h"
#include "core/util/error.h"
#include "core/util/params.h"
#include "core/util/power_of_two.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/ism.h"
#include "glsl/shared/normals.h"
#include "glsl/shared/vpl.h"

namespace vplgi {

namespace {

// A point of passes/ism_splat.comp's buffer: one uvec4 (the position's bits, the packed normal), and
// with the reach a second (the reach profile, 0, 0, 0).
struct ISMPointRecord {
    glm::vec3 position;            // world [m]
    std::uint32_t normalSnorm2x16; // octEncode'd unit geometric normal, packSnorm2x16'd
};
static_assert(sizeof(ISMPointRecord) == 16, "ISMPointRecord must match a std430 uvec4");

// surfaceReach of a point set, remembered for the last few sets in the process (ours): it takes
// about half a second for the default 524,288 points on 2 cores, and one process often makes maps
// of the same scene again (conform's seeds, a test's techniques, several ISM techniques at once).
// The key hashes every byte of the points, the normals, the area and the radius (Hasher: FNV-1a),
// so a hit is the same input; the result is a pure function of it.
std::vector<std::uint32_t> cachedSurfaceReach(const SurfacePoints& points, float radius)
{
    Hasher hasher;
    hasher.bytes(points.positions.data(), points.positions.size() * sizeof(glm::vec3));
    hasher.bytes(points.normals.data(), points.normals.size() * sizeof(glm::vec3));
    hasher.value(points.totalArea);
    hasher.value(radius);
    const std::uint64_t hash = hasher.digest();
    const std::size_t count = points.positions.size();
    static std::mutex mutex;
    static std::list<std::pair<std::uint64_t, std::vector<std::uint32_t>>> recent; // most recent first
    {
        const std::lock_guard<std::mutex> lock(mutex);
        for (auto it = recent.begin(); it != recent.end(); ++it)
            if (it->first == hash && it->second.size() == count) {
                recent.splice(recent.begin(), recent, it);
                return recent.front().second;
            }
    }
    std::vector<std::uint32_t> reach = surfaceReach(points, radius);
    const std::lock_guard<std::mutex> lock(mutex);
    recent.emplace_front(hash, reach);
    if (recent.size() > 4) recent.pop_back();
    return reach;
}

// Points one splat invocation handles (passes/ism_splat.comp ISM_POINTS_PER_INVOCATION).
constexpr int kSplatPointsPerInvocation = 8;

// Level `level` of the maps at image unit `unit` as r32ui (the splat's atomics need an integer
// format; r32f and r32ui are compatible by size, GL 4.5 section 8.26).
void bindMapsAsUint(int unit, const gl::Texture& maps, GLenum access, int level)
{
    glBindImageTexture(static_cast<GLuint>(unit), maps.id(), level, GL_TRUE, 0, access, GL_R32UI);
}

} // namespace

void ISMParams::visitParams(ParamVisitor& v, const std::string& prefix)
{
    v.field(prefix + "Points", points, 1, 1 << 24, "surface points of the scene shared by all maps (P)");
    v.field(prefix + "PointsPerMap", pointsPerMap, 1, 1 << 24,
            "points splatted into each light's map (VSGL section 4: 8192), at most P");
    v.field(prefix + "MapSize", mapSize, 4, 1024, "paraboloid map resolution, a power of two (VSGL section 4: 64)");
    v.field(prefix + "PullPushLevels", pullPushLevels, 0, 10,
            "pyramid levels of the pull-push hole filling (0 = none, log2 mapSize = every hole)");
    v.field(prefix + "PullPushDepthRange", pullPushDepthRange, 0.0f, 100.0f,
            "pull-push averages only texels within (1 + this) x the nearest distance (ours)");
    v.field(prefix + "DepthBias", depthBias, 0.0f, 1.0f, "lookup: lit while distance <= stored * (1 + bias) (ours)");
    v.field(prefix + "NormalOffset", normalOffset, 0.0f, 64.0f,
            "lookup: lift the shaded point along its normal by this many map texels (ours)");
    v.field(prefix + "SplatScale", splatScale, 0.0f, 8.0f,
            "footprint splats: each point covers the image of a disk of its tangent plane, radius this x sqrt(area / "
            "(pi x points per map)); 0 = one-texel points (Ritschel et al.) (ours)");
    v.field(prefix + "SplatMaxExtent", splatMaxExtent, 1.0f, 64.0f,
            "footprint splats: each disk's bounding box is cut to this half-size [texels] (ours)");
    v.field(prefix + "OwnRadius", ownRadius, 0.0f, 16.0f,
            "points nearer to a light with extent (a VSGL) than this x its radius r_i are not splatted into its map: "
            "its own footprint does not shadow it; 0 = every point (ours)");
    v.field(prefix + "OwnSurfaceOnly", ownSurfaceOnly,
            "of the points within ownRadius of a light with extent, leave out only those of its own surface (facing "
            "its way, near its tangent plane): the walls beside it still shadow (ours)");
    v.field(prefix + "Stratified", stratified,
            "each light's run of points per map is a stratified sample of the scene's area (every triangle gets its "
            "share within one point); false: i.i.d. points (ours)");
    v.field(prefix + "Planes", planes,
            "each texel keeps the plane of the point that won it and the lookup judges a receiver by the planes of "
            "the four texels around its direction (the rule of LightSkin's visibility maps) instead of one depth "
            "with depthBias and normalOffset (ours)");
    v.field(prefix + "EdgeMargin", edgeMargin, 0.0f, 1.0f,
            "with planes: a texel beside a parallel step of its surface (another texel's hit up to this x the distance "
            "behind its plane) hides a receiver only beyond this x the distance behind its plane (ours)");
    v.field(prefix + "GapReach", gapReach, 0, 4,
            "with planes: a texel whose two opposite neighbours up to this many texels away saw one plane that its ray "
            "crosses before its own hit looked through a gap between splats and takes that plane; 0 = no gap filling "
            "(ours)");
    v.field(prefix + "NearField", nearField, 0.0f, 8.0f,
            "near field: every point of the scene's set within this x sqrt(area / points per map) of a light is "
            "splatted into its map too, with the full set's smaller disks, so that the surfaces right around a light "
            "(a wall beside it, a corner) have no gaps; 0 = none (ours)");
    v.field(prefix + "Reach", reach,
            "with planes: each point's disk stops where its surface does (per sector of its tangent plane, found "
            "once from the point set), so a disk at a surface's edge writes no plane where there is no surface "
            "(ours)");
    v.field(prefix + "ReachMargin", reachMargin, 0.0f, 8.0f,
            "with the reach: a disk runs this many spacings of the scene's point set (sqrt(area / points)) past "
            "its sector's reach, where an edge can lie unseen by the probes; without it strips along edges that no "
            "disk of a map's run covers let light through walls (ours)");
    v.field(prefix + "Seed", seed, "random stream of the surface points");
}

ImperfectShadowMaps::ImperfectShadowMaps(const gl::ShaderLoader& shaders, const ISMParams& params, int maxLights)
    : mParams(params), mMaxLights(maxLights)
{
    const std::string name = "imperfect shadow maps: ";
    require(params.mapSize >= 4 && params.mapSize <= 1024 && (params.mapSize & (params.mapSize - 1)) == 0,
            name + "map size " + std::to_string(params.mapSize) + " must be a power of two in [4, 1024]");
    require(params.pullPushLevels >= 0 && params.pullPushLevels <= ceilLog2(params.mapSize),
            name + "pull-push levels " + std::to_string(params.pullPushLevels) + " outside [0, log2 " +
                std::to_string(params.mapSize) + " = " + std::to_string(ceilLog2(params.mapSize)) + "]");
    require(params.points >= 1 && params.points <= (1 << 24),
            name + "points " + std::to_string(params.points) + " outside [1, 2^24]");
    require(params.pointsPerMap >= 1 && params.pointsPerMap <= params.points,
            name + "points per map " + std::to_string(params.pointsPerMap) +
                " outside [1, points = " + std::to_string(params.points) + "]");
    require(params.pullPushDepthRange >= 0.0f && params.depthBias >= 0.0f && params.normalOffset >= 0.0f,
            name + "pull-push depth range, depth bias and normal offset must be >= 0");
    require(params.splatScale >= 0.0f && params.splatScale <= 8.0f && params.splatMaxExtent >= 1.0f &&
                params.splatMaxExtent <= 64.0f,
            name + "splat scale must lie in [0, 8] and splat max extent in [1, 64] texels");
    require(maxLights >= 1, name + "maxLights must be >= 1 (got " + std::to_string(maxLights) + ")");
    // The splat computes light * pointsPerMap in 32-bit unsigned arithmetic.
    require(static_cast<std::uint64_t>(maxLights) * static_cast<std::uint64_t>(params.pointsPerMap) < (1ull << 32),
            name + std::to_string(maxLights) + " lights x " + std::to_string(params.pointsPerMap) +
                " points per map must stay below 2^32");

    mMaps = makeParaboloidMapAtlas("imperfect shadow maps", params.mapSize, maxLights, params.pullPushLevels + 1,
                                   mLayout);
    if (params.planes) {
        // The same layout (the same limits give the same layout); kISMNoNormal = 0xFFFFFFFF.
        static_assert(shared::kISMNoNormal == 0xFFFFFFFFu, "the normals' atlas is cleared to all ones");
        ShadowAtlasLayout same;
        mNormals = makeParaboloidMapAtlas("imperfect shadow maps' normals", params.mapSize, maxLights, 1, same,
                                          GL_R32UI);
        if (params.gapReach > 0) {
            mGapMaps = makeParaboloidMapAtlas("imperfect shadow maps' gap filling: distances", params.mapSize,
                                              maxLights, 1, same);
            mGapNormals = makeParaboloidMapAtlas("imperfect shadow maps' gap filling: normals", params.mapSize,
                                                 maxLights, 1, same, GL_R32UI);
        }
    }

    gl::SamplerDesc samplerDesc;
    samplerDesc.minFilter = GL_NEAREST;
    samplerDesc.magFilter = GL_NEAREST;
    mSampler = gl::Sampler("imperfect shadow maps sampler", samplerDesc);
    reloadShaders(shaders);
}

void ImperfectShadowMaps::reloadShaders(const gl::ShaderLoader& shaders)
{
    mSplat = ComputePass(shaders, "ISM splat", "passes/ism_splat.comp",
                         {"ISM_POINTS_PER_INVOCATION=" + std::to_string(kSplatPointsPerInvocation)});
    mPull = ComputePass(shaders, "ISM pull", "passes/ism_pull.comp");
    mPush = ComputePass(shaders, "ISM push", "passes/ism_push.comp");
    mGaps = ComputePass(shaders, "ISM gaps", "passes/ism_gaps.comp");
}

void ImperfectShadowMaps::setScene(const Scene& scene)
{
    const SurfacePoints sample = sampleSurfacePoints(scene, mParams.points, mParams.seed, mParams.stratified ? mParams.pointsPerMap : 0);
    // n points sampled uniformly over the area A: one per A / n square metres, whose disk has radius
    // sqrt(A / (pi n)); the splats are splatScale times that.
    const auto diskRadius = [&](int n) {
        return mParams.splatScale * static_cast<float>(std::sqrt(sample.totalArea / (3.14159265358979 * n)));
    };
    // Each light's run of pointsPerMap points is a uniform sample of the area.
    mSplatRadius = diskRadius(mParams.pointsPerMap);
    const bool reach = mParams.reach && mParams.planes && mSplatRadius > 0.0f;
    // 16 bytes a point; with the reach (the default) its profile in a second uvec4.
    mPointStride = reach ? 2 : 1;
    const double spacing = std::sqrt(sample.totalArea / static_cast<double>(sample.positions.size()));
    mReachMargin = reach ? mParams.reachMargin * static_cast<float>(spacing) : 0.0f;
    const std::vector<std::uint32_t> reaches = reach ? cachedSurfaceReach(sample, mSplatRadius) : std::vector<std::uint32_t>();
    std::vector<glm::uvec4> packed(sample.positions.size() * static_cast<std::size_t>(mPointStride), glm::uvec4(0u));
    for (std::size_t i = 0; i < sample.positions.size(); ++i) {
        const ISMPointRecord record{sample.positions[i], glm::packSnorm2x16(shared::octEncode(sample.normals[i]))};
        std::memcpy(&packed[i * static_cast<std::size_t>(mPointStride)], &record, sizeof(record));
        if (reach) packed[i * 2 + 1].x = reaches[i];
    }
    mPoints = gl::Buffer("ISM surface points", static_cast<GLsizeiptr>(packed.size() * sizeof(glm::uvec4)),
                         packed.data(), false);
    mPointCount = static_cast<int>(sample.positions.size());
    // As LightSkin's lightCacheVisibilityLift: an absolute margin far below any wall's thickness.
    mLift = 1e-4f * glm::length(scene.worldBounds().extent());
    mNearSlotCount = 0;
    if (mParams.nearField > 0.0f && mPointCount > 0) {
        // Near field: a light's own run holds one point per A / pointsPerMap, so the surfaces within a
        // few such spacings of it (a wall beside it, a corner) are seen from so close that the run's
        // disks leave gaps between them; every point of the whole set P there is splatted too.
        mNearRadius = mParams.nearField * static_cast<float>(std::sqrt(sample.totalArea / mParams.pointsPerMap));
        mNearSplatRadius = diskRadius(mPointCount);
        mNearOrigin = scene.worldBounds().lower;
        // Cells a hair wider than the radius (1e-4): 1 / (1 / r) rounded may fall below r, and the 3^3
        // cells around a light must hold every point within r of it.
        mNearInverseEdge = 1.0f / (mNearRadius * 1.0001f);
        mNearSlotCount = 1;
        while (mNearSlotCount < 2 * mPointCount && mNearSlotCount < (1 << 24)) mNearSlotCount *= 2;
        std::vector<std::uint32_t> slotOf(sample.positions.size()), start(static_cast<std::size_t>(mNearSlotCount) + 1, 0);
        for (std::size_t i = 0; i < sample.positions.size(); ++i) {
            const glm::ivec3 cell = shared::ismNearCell(sample.positions[i], mNearOrigin, mNearInverseEdge);
            slotOf[i] = shared::ismNearSlot(cell, static_cast<std::uint32_t>(mNearSlotCount));
            ++start[slotOf[i] + 1];
        }
        for (std::size_t s = 1; s < start.size(); ++s) start[s] += start[s - 1];
        std::vector<std::uint32_t> indices(sample.positions.size()), next(start.begin(), start.end() - 1);
        for (std::size_t i = 0; i < sample.positions.size(); ++i) indices[next[slotOf[i]]++] = static_cast<std::uint32_t>(i);
        mNearIndices = gl::Buffer("ISM near-field indices", static_cast<GLsizeiptr>(indices.size() * 4), indices.data(), false);
        mNearSlots = gl::Buffer("ISM near-field slots", static_cast<GLsizeiptr>(start.size() * 4), start.data(), false);
    }
}

void ImperfectShadowMaps::update(const gl::Buffer& lights, int count, int strideVec4, int validVec4,
                                 int radius2Vec4, gl::PassTimer* timer)
{
    require(mPointCount > 0, "imperfect shadow maps: update() before setScene()");
    require(count >= 0 && count <= mMaxLights,
            "imperfect shadow maps: " + std::to_string(count) + " lights, at most " + std::to_string(mMaxLights));
    require(strideVec4 >= 2, "imperfect shadow maps: light stride " + std::to_string(strideVec4) + " < 2 vec4s");
    require(validVec4 >= 0 && validVec4 < strideVec4,
            "imperfect shadow maps: the valid flag's vec4 " + std::to_string(validVec4) + " is outside the record");
    require(radius2Vec4 >= -1 && radius2Vec4 < strideVec4,
            "imperfect shadow maps: the radius's vec4 " + std::to_string(radius2Vec4) + " is outside the record");
    require(static_cast<std::int64_t>(count) * strideVec4 * 16 <= lights.size(),
            "imperfect shadow maps: " + std::to_string(count) + " lights x " + std::to_string(strideVec4) +
                " vec4s exceed the light buffer (" + std::to_string(lights.size()) + " bytes)");
    if (count == 0) return;
    gl::DebugGroup group("imperfect shadow maps");

    clearMaps(count, timer);

    bindMapsAsUint(shared::kImageISMMaps, mMaps, GL_READ_WRITE, 0);
    bindStorageBuffer(shared::kBindingISMPoints, mPoints);
    bindStorageBuffer(shared::kBindingISMLights, lights);
    const gl::Program& splat = mSplat.program();
    splat.set("uCount", count);
    splat.set("uStride", strideVec4);
    splat.set("uValidVec4", validVec4);
    splat.set("uPointsPerMap", mParams.pointsPerMap);
    splat.set("uPointCount", mPointCount);
    splat.set("uMapSize", mParams.mapSize);
    splat.set("uTilesPerRow", mLayout.tilesPerRow);
    splat.set("uSplatRadius", mSplatRadius);
    splat.set("uSplatMaxExtent", mParams.splatMaxExtent);
    splat.set("uRadius2Vec4", radius2Vec4);
    splat.set("uOwnRadius", mParams.ownRadius);
    splat.set("uPlanes", mParams.planes ? 1 : 0);
    splat.set("uPointStride", mPointStride);
    splat.set("uReachMargin", mReachMargin);
    splat.set("uOwnSurfaceOnly", mParams.ownSurfaceOnly ? 1 : 0);
    splat.set("uPass", 0);
    const int runInvocations = (mParams.pointsPerMap + kSplatPointsPerInvocation - 1) / kSplatPointsPerInvocation;
    splat.set("uRunInvocations", runInvocations);
    splat.set("uNearSlots", mNearSlotCount);
    splat.set("uNearRadius", mNearRadius);
    splat.set("uNearSplatRadius", mNearSplatRadius);
    splat.set("uNearOrigin", mNearOrigin);
    splat.set("uNearInverseEdge", mNearInverseEdge);
    if (mNearSlotCount > 0) {
        bindStorageBuffer(shared::kBindingISMNearIndices, mNearIndices);
        bindStorageBuffer(shared::kBindingISMNearSlots, mNearSlots);
    }
    // Pull reads the splat next (or the normals' pass); without pull-push the shading pass (or a
    // test's readback) does.
    // The run's invocations, then with the near field 27 more per light: the 3^3 cells around it.
    const int splatInvocations = runInvocations + (mNearSlotCount > 0 ? 27 : 0);
    mSplat.dispatch(glm::ivec3(splatInvocations, count, 1),
                    NextRead::Image | NextRead::TextureFetch | NextRead::TextureReadback, timer);
    if (mParams.planes) {
        // The same splats again: each writes its normal where its distance won (glsl/shared/ism.h, planes).
        glBindImageTexture(static_cast<GLuint>(shared::kImageISMNormals), mNormals.id(), 0, GL_TRUE, 0,
                           GL_READ_WRITE, GL_R32UI);
        splat.set("uPass", 1);
        std::optional<gl::PassTimer::Scope> scope; // the second splat under its own name in the timings
        if (timer) scope.emplace(*timer, "ISM splat normals");
        mSplat.dispatch(glm::ivec3(splatInvocations, count, 1),
                        NextRead::Image | NextRead::TextureFetch | NextRead::TextureReadback, nullptr);
        scope.reset();
        if (mParams.gapReach > 0) fillGaps(lights, count, strideVec4, timer);
    }

    fillHoles(count, timer);
}

template <typename F> void ImperfectShadowMaps::forEachTileRectangle(int count, F f) const
{
    // Tiles 0 .. count-1 fill whole layers, then whole rows of the next layer, then part of one row.
    const int n = mLayout.tilesPerRow, perLayer = n * n;
    const int layers = count / perLayer, rows = (count % perLayer) / n, rest = count % n;
    if (layers > 0) f(0, 0, 0, n, n, layers);
    if (rows > 0) f(0, 0, layers, n, rows, 1);
    if (rest > 0) f(0, rows, layers, rest, 1, 1);
}

void ImperfectShadowMaps::clearMaps(int count, gl::PassTimer* timer) const
{
    // At most three rectangles. On llvmpipe this took 1 ms for 1024 maps of 64^2, a clearing kernel 37 ms.
    std::optional<gl::PassTimer::Scope> scope;
    if (timer) scope.emplace(*timer, "ISM clear");
    const float none = shared::kVPLNoOccluder;
    const int size = mParams.mapSize;
    const std::uint32_t noNormal = shared::kISMNoNormal;
    forEachTileRectangle(count, [&](int x, int y, int layer, int width, int height, int depth) {
        glClearTexSubImage(mMaps.id(), 0, x * size, y * size, layer, width * size, height * size, depth, GL_RED,
                           GL_FLOAT, &none);
        if (mParams.planes)
            glClearTexSubImage(mNormals.id(), 0, x * size, y * size, layer, width * size, height * size, depth,
                               GL_RED_INTEGER, GL_UNSIGNED_INT, &noNormal);
    });
}

void ImperfectShadowMaps::fillGaps(const gl::Buffer& lights, int count, int strideVec4, gl::PassTimer* timer)
{
    bindMapsAsUint(shared::kImageISMMaps, mMaps, GL_READ_ONLY, 0);
    glBindImageTexture(static_cast<GLuint>(shared::kImageISMNormals), mNormals.id(), 0, GL_TRUE, 0, GL_READ_ONLY,
                       GL_R32UI);
    bindMapsAsUint(shared::kImageISMGapDistances, mGapMaps, GL_WRITE_ONLY, 0);
    glBindImageTexture(static_cast<GLuint>(shared::kImageISMGapNormals), mGapNormals.id(), 0, GL_TRUE, 0,
                       GL_WRITE_ONLY, GL_R32UI);
    bindStorageBuffer(shared::kBindingISMLights, lights);
    const gl::Program& gaps = mGaps.program();
    gaps.set("uCount", count);
    gaps.set("uStride", strideVec4);
    gaps.set("uMapSize", mParams.mapSize);
    gaps.set("uTilesPerRow", mLayout.tilesPerRow);
    gaps.set("uReach", mParams.gapReach);
    gaps.set("uLift", mLift);
    mGaps.dispatch(glm::ivec3(mParams.mapSize * mParams.mapSize, count, 1), NextRead::TextureReadback, timer);
    // The copies back into the maps (glCopyImageSubData after the barrier for texture updates).
    std::optional<gl::PassTimer::Scope> scope;
    if (timer) scope.emplace(*timer, "ISM gaps copy");
    const int size = mParams.mapSize;
    forEachTileRectangle(count, [&](int x, int y, int layer, int width, int height, int depth) {
        glCopyImageSubData(mGapMaps.id(), GL_TEXTURE_2D_ARRAY, 0, x * size, y * size, layer, mMaps.id(),
                           GL_TEXTURE_2D_ARRAY, 0, x * size, y * size, layer, width * size, height * size, depth);
        glCopyImageSubData(mGapNormals.id(), GL_TEXTURE_2D_ARRAY, 0, x * size, y * size, layer, mNormals.id(),
                           GL_TEXTURE_2D_ARRAY, 0, x * size, y * size, layer, width * size, height * size, depth);
    });
}

void ImperfectShadowMaps::fillHoles(int count, gl::PassTimer* timer)
{
    require(count >= 0 && count <= mMaxLights, "imperfect shadow maps: fillHoles of " + std::to_string(count) +
                                                   " lights, at most " + std::to_string(mMaxLights));
    if (count == 0 || mParams.pullPushLevels == 0) return;
    gl::DebugGroup group("ISM pull-push");
    for (const gl::Program* program : {&mPull.program(), &mPush.program()}) {
        program->set("uCount", count);
        program->set("uTilesPerRow", mLayout.tilesPerRow);
        program->set("uDepthRange", mParams.pullPushDepthRange);
    }
    // Pull: level l -> l + 1.
    for (int level = 0; level < mParams.pullPushLevels; ++level) {
        const int coarseSize = mParams.mapSize >> (level + 1);
        bindMapsAsUint(shared::kImageISMMaps, mMaps, GL_READ_ONLY, level);
        bindMapsAsUint(shared::kImageISMCoarser, mMaps, GL_WRITE_ONLY, level + 1);
        mPull.program().set("uCoarseSize", coarseSize);
        mPull.dispatch(glm::ivec3(coarseSize * coarseSize, count, 1), NextRead::Image, timer);
    }
    // Push: level l from l + 1, coarsest first. The shading pass fetches level 0 next.
    for (int level = mParams.pullPushLevels - 1; level >= 0; --level) {
        const int coarseSize = mParams.mapSize >> (level + 1);
        bindMapsAsUint(shared::kImageISMMaps, mMaps, GL_READ_WRITE, level);
        bindMapsAsUint(shared::kImageISMCoarser, mMaps, GL_READ_ONLY, level + 1);
        mPush.program().set("uCoarseSize", coarseSize);
        mPush.dispatch(
            glm::ivec3(4 * coarseSize * coarseSize, count, 1),
            level == 0 ? NextRead::TextureFetch | NextRead::Image | NextRead::TextureReadback : NextRead::Image, timer);
    }
}

void ImperfectShadowMaps::bindForReading(const gl::Program& program) const
{
    glBindTextureUnit(shared::kUnitISM, mMaps.id());
    glBindSampler(shared::kUnitISM, mSampler.id());
    program.set("uISMMapSize", mParams.mapSize);
    program.set("uISMTilesPerRow", mLayout.tilesPerRow);
    program.set("uISMNormalOffset", mParams.normalOffset);
    program.set("uISMDepthBias", mParams.depthBias);
    program.set("uISMPlanes", mParams.planes ? 1 : 0);
    program.set("uISMLift", mLift);
    program.set("uISMEdgeMargin", mParams.edgeMargin);
    program.set("uISMOverhang", mSplatRadius);
    if (mParams.planes) {
        glBindTextureUnit(shared::kUnitISMNormals, mNormals.id());
        glBindSampler(shared::kUnitISMNormals, mSampler.id());
    }
}

} // namespace vplgi
