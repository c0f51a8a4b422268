#include "vpl_technique.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "../api/debug.h"
#include "../api/limits.h"
#include "core/util/error.h"
#include "core/util/params.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/shadow_atlas.h"
#include "glsl/shared/vpl.h"

namespace vplgi {

namespace {

SceneProgram loadDebugProgram(const gl::ShaderLoader& shaders)
{
    return SceneProgram(shaders, "VPL debug views",
                        {{GL_VERTEX_SHADER, "passes/vpl_debug.vert"}, {GL_FRAGMENT_SHADER, "passes/vpl_debug.frag"}});
}

float luminance(const glm::vec3& c)
{
    return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b;
}

} // namespace

void VPLRenderParams::visitParams(ParamVisitor& v, const std::string& prefix)
{
    v.field(prefix + ".shadowMapSize", shadowMapSize, 4, 4096, "paraboloid shadow map resolution per VPL (section 4: 128)");
    v.choice(prefix + ".shading", shading, {"interleaved", "exhaustive"},
             "interleaved: each pixel of a 4x4 tile gathers 1/16 of the VPLs (section 4); exhaustive: every VPL");
    v.field(prefix + ".interleaveTile", interleaveTile, 1, 16, "interleaving tile size (section 4: 4)");
    v.choice(prefix + ".visibility", visibility, {"shadowmaps", "raytraced", "none", "probe"},
             "VPL visibility: paraboloid shadow maps (the paper), Embree rays on the CPU, none, or probe (a "
             "one-texel fetch in place of the shadow lookup: what the lookups cost)");
    v.field(prefix + ".normalOffset", normalOffset, 0.0f, 64.0f,
            "shadow test: lift the shaded point along its normal by this many map texels (not in the paper)");
    v.field(prefix + ".depthBias", depthBias, 0.0f, 64.0f,
            "shadow test: lit while distance <= stored + bias map texels at the distance, i.e. stored * (1 + 4 bias / "
            "mapSize) (not in the paper)");
    v.field(prefix + ".shadowBatch", shadowBatch, 1, 65536, "VPLs whose cube faces are rendered per batch");
    v.field(prefix + ".mapsPerFrame", mapsPerFrame, 0, 1 << 20,
            "most shadow maps made per frame, the rest in later frames (spreads the initial build); 0 = all");
    v.field(prefix + ".rebuildEveryFrame", rebuildEveryFrame,
            "re-render every shadow map every frame instead of the changed ones (a yardstick)");
    filter.visitParams(v, prefix + ".filter.");
    v.field(prefix + ".debugVPL", debugVPL, 0, 1 << 20, "the slot whose paraboloid map the <technique>.map view shows");
}

VPLTechnique::VPLTechnique(Source source) : mSource(source) {}

VPLTechnique::~VPLTechnique() = default; // the pipeline joins its worker

std::string_view VPLTechnique::name() const
{
    switch (mSource) {
    case Source::SMCIR: return "smcir";
    case Source::IR: return "ir";
    case Source::MIR: return "mir";
    }
    return "ir";
}

void VPLTechnique::visitParams(ParamVisitor& v)
{
    if (mSource == Source::SMCIR) {
        mSMCIR.visitParams(v);
    } else if (mSource == Source::IR) {
        mIR.visitParams(v);
        v.field("ir.clampScale", mIRClampScale, 0.0f, 1000.0f,
                "VPL clamping as smcir.clampScale: G_max = 1/d^2, d = clampScale * D / sqrt(I); 0 = none "
                "(the paper's comparisons clamp every method alike)");
    } else {
        mMIR.visitParams(v);
        v.field("mir.clampScale", mMIRClampScale, 0.0f, 1000.0f,
                "VPL clamping as smcir.clampScale: G_max = 1/d^2, d = clampScale * D / sqrt(I); 0 = none "
                "(the paper's comparisons clamp every method alike)");
    }
    mRender.visitParams(v, prefix());
    v.field(prefix() + ".synchronous", mSynchronous,
            "run the sampler step on the render thread (no overlap with the GPU frame; for clean timings)");
}

int VPLTechnique::vplCount() const
{
    switch (mSource) {
    case Source::SMCIR: return mSMCIR.vplCount;
    case Source::IR: return mIR.vplCount;
    case Source::MIR: return mMIR.vplCount;
    }
    return mIR.vplCount;
}

float VPLTechnique::clampGeometry() const
{
    if (mSource == Source::SMCIR) return computeClampGeometry(mSMCIR, mRays->sceneScale());
    if (mSource == Source::MIR) return clampGeometryFor(mMIRClampScale, mMIR.vplCount, mRays->sceneScale());
    return clampGeometryFor(mIRClampScale, mIR.vplCount, mRays->sceneScale());
}

void VPLTechnique::setScene(const SceneContext& context)
{
    mScene = &context.scene;
    mGpuScene = &context.gpuScene;
    mShaders = &context.shaders;
    mRays = &context.rays.get();
    mProgress = context.progress;
    mShading = std::make_unique<FullscreenPass>(context.shaders, "VPL shading", "passes/vpl_shading.frag");
    gl::RenderTargetDesc desc = gl::RenderTargetDesc::colors({GL_RGBA32F}, {"interleaved indirect"});
    mInterleaved = gl::RenderTarget("VPL interleaved shading", desc);
    mFilter = std::make_unique<CrossBilateralFilter>(context.shaders);
    mDebugProgram = loadDebugProgram(context.shaders);
    mEmptyVertexArray = gl::VertexArray("VPL debug points");
    mSplats = gl::RenderTarget("VPL splats", gl::RenderTargetDesc::colors({GL_RGBA32F}, {"splats"}));
    gl::RenderTargetDesc overhead = gl::RenderTargetDesc::colors({GL_RGBA32F}, {"overhead"});
    overhead.depthFormat = GL_DEPTH_COMPONENT32F;
    mOverhead = gl::RenderTarget("VPL overhead view", overhead);
    startPipeline();
    dropShadowMaps(); // made on the first frame whose visibility reads them
}

void VPLTechnique::startPipeline()
{
    mPipeline.reset(); // joins a running step before its sampler goes
    mRendered = nullptr;
    mMapsGeneration.reset();
    mMapPending.clear();
    std::unique_ptr<VPLSampler> sampler;
    if (mSource == Source::SMCIR)
        sampler = std::make_unique<SMCIRSampler>(*mScene, *mRays, mSMCIR);
    else if (mSource == Source::IR)
        sampler = std::make_unique<IRSampler>(*mScene, *mRays, mIR);
    else
        sampler = std::make_unique<MIRSampler>(*mScene, *mRays, mMIR, clampGeometry());
    mPipeline = std::make_unique<VPLPipeline>(std::move(sampler), mRays);
}

void VPLTechnique::dropShadowMaps()
{
    mShadowMaps.reset();
    mMapsGeneration.reset();
    mMapPending.clear();
}

void VPLTechnique::createShadowMaps()
{
    VPLShadowMapParams params;
    params.mapSize = mRender.shadowMapSize;
    params.slots = vplCount();
    params.batchSize = mRender.shadowBatch;
    // The faces clip axial depth (glsl/shared/light_view.h): zFar beyond the scene's diagonal, zNear
    // a small fraction of it (closer occluders are lost; G is clamped there anyway).
    const float diagonal = mRays->sceneScale();
    params.zFar = 1.01f * diagonal;
    params.zNear = 1e-4f * diagonal;
    mShadowMaps.reset();
    mShadowMaps = std::make_unique<VPLShadowMaps>(*mShaders, params);
    mMapsGeneration.reset();
    mMapPending.clear();
}

void VPLTechnique::reloadShaders(const gl::ShaderLoader& shaders)
{
    mShading->reloadShaders(shaders);
    mFilter->reloadShaders(shaders);
    mDebugProgram = loadDebugProgram(shaders);
    if (mShadowMaps) mShadowMaps->reloadShaders(shaders);
}

void VPLTechnique::update(const FrameContext& frame)
{
    const float aspect = static_cast<float>(frame.width) / static_cast<float>(frame.height);
    VPLSampler::Progress progress;
    if (mProgress && mScene->triangleCount() > 50000)
        progress = [this](int done, int total) { mProgress(std::string(name()) + " warm-up", done, total); };
    mRendered = &mPipeline->advance(FrameSnapshot::of(*mScene, frame.camera, aspect, frame.time), mSynchronous, progress);
}

void VPLTechnique::render(const FrameContext& frame, const GBuffer& gbuffer, const IndirectTarget& target)
{
    const VPLSet& set = *mRendered;
    const int tile = mRender.shading == VPLRenderParams::Exhaustive ? 1 : std::max(mRender.interleaveTile, 1);
    // The shading pass reads every slot from one storage block and visits every tile^2-th slot per
    // pixel in one loop: a GL implementation may hold fewer slots in a block, and llvmpipe ends a
    // shader invocation's loops after 65535 iterations (gl/api/limits.h). Past either limit only
    // the first `shaded` slots are uploaded and shaded, n counting the valid VPLs among them: a
    // subset of the set, the same expected image with more variance, with one warning (not
    // silently darker by the VPLs the loop never reached).
    int shaded = static_cast<int>(set.slots.size());
    if (mRender.visibility != VPLRenderParams::RayTraced) {
        const int classes = tile * tile;
        const std::string what = prefix() + ".vplCount";
        shaded = gl::clampStorageCount(shaded, sizeof(shared::GpuVPL), what);
        const int perPixel = gl::clampShaderLoopCount((shaded + classes - 1) / classes,
                                                      what + " / " + std::to_string(classes) + " per pixel");
        shaded = std::min(shaded, perPixel * classes);
    }
    // 1. Every slot's VPL (48 bytes each: re-uploading all is cheaper than tracking them).
    std::vector<shared::GpuVPL> gpu(static_cast<std::size_t>(shaded));
    int validCount = 0;
    for (std::size_t i = 0; i < gpu.size(); ++i) {
        const VPL& vpl = set.slots[i];
        const bool valid = vpl.valid && vpl.density > 0.0f;
        validCount += vpl.valid ? 1 : 0; // n counts valid slots (VPLSet::validCount), density 0 included
        gpu[i].positionValid = glm::vec4(vpl.position, valid ? 1.0f : 0.0f);
        gpu[i].normal = glm::vec4(vpl.normal, 0.0f);
        gpu[i].intensity = glm::vec4(valid ? vpl.intensity() : glm::vec3(0.0f), 0.0f);
    }
    gl::uploadVector(mVPLBuffer, std::string(name()) + " VPLs", gpu);

    mInterleaved.resize(frame.width, frame.height);
    mFacesRendered = 0;
    mEvaluations = static_cast<double>(frame.width) * frame.height * validCount / (tile * tile);
    if (mRender.visibility == VPLRenderParams::RayTraced) {
        shadeRayTraced(frame, mInterleaved);
    } else {
        // The atlas (I maps) only while the visibility reads it: with none, I can exceed what the
        // atlas's memory budget holds.
        const bool readsMaps = mRender.visibility == VPLRenderParams::ShadowMaps ||
                               mRender.visibility == VPLRenderParams::FetchProbe;
        if (readsMaps && !mShadowMaps) createShadowMaps();
        // 2. Lazy update: only the slots that changed since the set whose maps we hold.
        if (mRender.visibility == VPLRenderParams::ShadowMaps) {
            gl::PassTimer::Scope scope(frame.timer, "shadow maps");
            std::vector<std::uint32_t> dirty;
            if (mMapsGeneration && *mMapsGeneration == set.generation && !mRender.rebuildEveryFrame) {
                // the same set as last frame (the pipeline's first asynchronous frame): nothing moved
            } else if (mMapsGeneration && *mMapsGeneration + 1 == set.generation && !mRender.rebuildEveryFrame) {
                dirty = set.changed;
            } else {
                for (std::uint32_t i = 0; i < set.slots.size(); ++i)
                    dirty.push_back(i);
            }
            if (mRender.mapsPerFrame > 0) {
                // Spread over frames: queue the dirty slots, make the lowest mapsPerFrame of the queue.
                mMapPending.resize(set.slots.size(), 0);
                for (std::uint32_t slot : dirty)
                    mMapPending[slot] = 1;
                dirty.clear();
                for (std::uint32_t i = 0; i < mMapPending.size() && static_cast<int>(dirty.size()) < mRender.mapsPerFrame; ++i)
                    if (mMapPending[i]) {
                        dirty.push_back(i);
                        mMapPending[i] = 0;
                    }
            }
            VPLShadowMaps::Progress progress;
            if (mProgress && dirty.size() > 512)
                progress = [this](int done, int total) { mProgress(std::string(name()) + " shadow maps", done, total); };
            mShadowMaps->update(*mGpuScene, set, dirty, progress);
            mFacesRendered = mShadowMaps->facesRendered();
            mMapsGeneration = set.generation;
        }
        // 3. Interleaved shading, eq. (5).
        gl::PassTimer::Scope scope(frame.timer, "interleaved shading");
        gbuffer.bindForReading();
        if (readsMaps) mShadowMaps->bindForReading();
        bindStorageBuffer(shared::kBindingVPLs, mVPLBuffer);
        const gl::Program& program = mShading->program();
        program.set("uTile", tile);
        program.set("uValidCount", validCount);
        program.set("uClampGeometry", clampGeometry());
        program.set("uVisibility", mRender.visibility == VPLRenderParams::ShadowMaps   ? 1
                                   : mRender.visibility == VPLRenderParams::FetchProbe ? 2
                                                                                       : 0);
        program.set("uMapSize", readsMaps ? mShadowMaps->params().mapSize : 1);
        program.set("uMapTilesPerRow", readsMaps ? mShadowMaps->layout().tilesPerRow : 1);
        program.set("uNormalOffset", mRender.normalOffset);
        // depthBias [texels at the distance] as the relative bias the lookup takes: a paraboloid texel
        // spans up to 4/N radians, so the bias shrinks with the map resolution (as the paper's, Fig. 9).
        program.set("uDepthBias", readsMaps ? 4.0f * mRender.depthBias / static_cast<float>(mShadowMaps->params().mapSize)
                                            : 0.0f);
        mShading->render(mInterleaved);
    }
    // 4. The cross-bilateral filter (section 4) over the interleaved result, into the indirect target.
    mFilter->apply(gbuffer, mInterleaved.color(0), target.target, BilateralFilterView::fromCamera(frame.camera),
                   mRender.filter, FullscreenDraw::Blend::None, &frame.timer);

    // Debug overlays, only while shown: VPLs as splats coloured by intensity (the brightest at 4),
    // and the overhead view.
    const std::string t(name());
    if (frame.display == t + ".splats" || frame.display == t + ".overhead") {
        float brightest = 0.0f;
        for (const shared::GpuVPL& v : gpu)
            brightest = std::max(brightest, luminance(glm::vec3(v.intensity)));
        drawDebugOverlay(frame, target.radiance(), frame.display == t + ".overhead",
                         brightest > 0.0f ? 4.0f / brightest : 0.0f);
    }
}

void VPLTechnique::drawDebugOverlay(const FrameContext& frame, const gl::Texture& indirect, bool overhead,
                                    float colorScale)
{
    gl::DebugGroup group(std::string(name()) + " debug overlay");
    const AABB bounds = mScene->worldBounds();
    const gl::Program& program = mDebugProgram.opaque();
    glUseProgram(program.id());
    bindStorageBuffer(shared::kBindingVPLs, mVPLBuffer);
    program.set("uColorScale", colorScale);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glm::mat4 clipFromWorld = frame.clipFromWorld;
    if (overhead) {
        // SMCIR Fig. 3 (bottom): the scene from above. Back faces are culled, so ceilings (which
        // face down) vanish and wall tops, floors and everything facing up remain.
        mOverhead.resize(512, 512);
        mOverhead.clear();
        mOverhead.bindForDrawing();
        clipFromWorld = shared::lightViewDirectionalFit(glm::vec3(0.0f, -1.0f, 0.0f), bounds.lower, bounds.upper);
        // The scene through both variants (alpha-masked materials cut as every pass cuts them).
        mDebugProgram.set("uClipFromWorld", clipFromWorld);
        mDebugProgram.set("uMode", 0);
        mDebugProgram.set("uCutHeight", bounds.upper.y + 1.0f);
        mDebugProgram.set("uHeightRange", glm::vec2(bounds.lower.y, bounds.upper.y));
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glEnable(GL_CULL_FACE);
        glCullFace(GL_BACK);
        mGpuScene->draw(mDebugProgram, GpuScene::Bind::Geometry); // (it leaves culling off and no program bound)
        glUseProgram(program.id());
        glDisable(GL_DEPTH_TEST);
        // The camera frustum: near corners and the corners half a scene diagonal further on.
        const glm::mat4 worldFromClip = glm::inverse(frame.clipFromWorld);
        glm::vec3 nearCorner[4], farCorner[4];
        const glm::vec2 ndc[4] = {{-1.0f, -1.0f}, {1.0f, -1.0f}, {1.0f, 1.0f}, {-1.0f, 1.0f}};
        const float reach = 0.5f * glm::length(bounds.extent());
        for (int i = 0; i < 4; ++i) {
            const glm::vec4 a = worldFromClip * glm::vec4(ndc[i], -1.0f, 1.0f);
            const glm::vec4 b = worldFromClip * glm::vec4(ndc[i], 1.0f, 1.0f);
            nearCorner[i] = glm::vec3(a) / a.w;
            farCorner[i] = nearCorner[i] + glm::normalize(glm::vec3(b) / b.w - nearCorner[i]) * reach;
        }
        std::vector<glm::vec3> lines;
        for (int i = 0; i < 4; ++i) {
            lines.insert(lines.end(), {nearCorner[i], nearCorner[(i + 1) % 4], farCorner[i], farCorner[(i + 1) % 4],
                                       nearCorner[i], farCorner[i]});
        }
        glProgramUniform3fv(program.id(), program.uniformLocation("uLines"), 24, &lines[0].x);
        glBindVertexArray(mEmptyVertexArray.id());
        program.set("uMode", 2);
        glDrawArrays(GL_LINES, 0, 24);
        program.set("uPointSize", 3.0f);
    } else {
        mSplats.resize(frame.width, frame.height);
        glCopyImageSubData(indirect.id(), GL_TEXTURE_2D, 0, 0, 0, 0, mSplats.color(0).id(), GL_TEXTURE_2D, 0, 0, 0, 0,
                           frame.width, frame.height, 1);
        mSplats.bindForDrawing();
        program.set("uClipFromWorld", clipFromWorld);
        program.set("uPointSize", 3.0f);
    }
    program.set("uClipFromWorld", clipFromWorld);
    program.set("uMode", 1);
    glBindVertexArray(mEmptyVertexArray.id());
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(mRendered->slots.size()));
    glBindVertexArray(0);
    glDisable(GL_PROGRAM_POINT_SIZE);
    glUseProgram(0);
}

void VPLTechnique::shadeRayTraced(const FrameContext& frame, const gl::RenderTarget& into)
{
    const auto start = std::chrono::steady_clock::now();
    VPLGatherParams gather;
    gather.clampGeometry = clampGeometry();
    gather.interleaveTile = mRender.shading == VPLRenderParams::Exhaustive ? 1 : std::max(mRender.interleaveTile, 1);
    const ImageRGBA32F image =
        renderVPLGather(*mScene, *mRays, frame.camera, frame.width, frame.height, *mRendered, gather);
    gl::uploadTopDownRGBA32F(into.color(0), image.pixels, frame.width, frame.height);
    mRayTracedMilliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void VPLTechnique::applyParamChanges(const std::set<std::string>& changedKeys)
{
    if (!mScene) return;
    const std::string p = prefix() + ".";
    // Read every frame: the clamp, the shading and shadow-test settings, where the step runs.
    static const std::set<std::string> cheap = {"clampScale", "synchronous", "shading", "interleaveTile", "visibility",
                                                "normalOffset", "depthBias", "rebuildEveryFrame", "debugVPL",
                                                "mapsPerFrame"};
    bool restart = false, maps = false;
    for (const std::string& key : changedKeys) {
        if (key.rfind(p, 0) != 0) continue;
        const std::string field = key.substr(p.size());
        // mir's sampler weighs its candidates with the clamp (core/vpl/mir_sampler.h): a new sampler.
        if (mSource == Source::MIR && field == "clampScale") {
            restart = true;
            continue;
        }
        if (cheap.count(field) || field.rfind("filter.", 0) == 0) continue;
        if (field == "shadowMapSize" || field == "shadowBatch")
            maps = true;
        else
            restart = true; // the sampler keeps a copy of its parameters (slots, seeds)
    }
    if (restart) {
        startPipeline();
        maps = true;
    }
    if (maps) dropShadowMaps();
}

std::vector<std::pair<std::string, double>> VPLTechnique::frameStats() const
{
    std::vector<std::pair<std::string, double>> stats = mPipeline->stats();
    const VPLSet& set = mPipeline->published();
    stats.emplace_back("vpls", static_cast<double>(set.validCount()));
    stats.emplace_back("vpls changed", static_cast<double>(set.changed.size()));
    stats.emplace_back("shadow map faces", static_cast<double>(mFacesRendered));
    stats.emplace_back("light-pixel evaluations", mEvaluations);
    if (mRender.visibility == VPLRenderParams::RayTraced) stats.emplace_back("cpu gather ms", mRayTracedMilliseconds);
    return stats;
}

void VPLTechnique::configureReference(PathTracerParams& params, const std::set<std::string>& explicitKeys) const
{
    if (mSource == Source::SMCIR) {
        configureSMCIRReference(mSMCIR, mRays->sceneScale(), params, explicitKeys);
        return;
    }
    // IR as SMCIR (section 5 compares every method against the same reference). A VPL deposited at
    // hit j carries light reflected j times counting the one at the VPL: at most ir.bounces.
    // Every IR bounce is diffuse (rho_d cosine sampling, core/vpl/ir_sampler.h): diffuse at every vertex >= 1.
    // MIR resamples IR's light paths (core/vpl/mir_sampler.h): the same light, the same reference.
    if (mSource == Source::MIR) {
        configureVPLReference(mMIR.texturedVPLs, clampGeometry(), mMIR.bounces, 2, params, explicitKeys);
        return;
    }
    configureVPLReference(mIR.texturedVPLs, clampGeometry(), mIR.bounces, 2, params, explicitKeys);
}

std::vector<DebugView> VPLTechnique::debugViews() const
{
    const std::string t(name());
    std::vector<DebugView> views;
    const float range = mRays ? mRays->sceneScale() : 1.0f;
    DebugView maps{t + ".maps", "paraboloid shadow maps of every VPL slot: distance [0, scene diagonal]",
                   mShadowMaps ? &mShadowMaps->maps() : nullptr, shared::kDebugViewScalar, {0.0f, range}};
    maps.layerCount = 0;
    views.push_back(maps);
    DebugView map{t + ".map", "the paraboloid shadow map of VPL " + t + ".debugVPL: distance [0, scene diagonal]",
                  mShadowMaps ? &mShadowMaps->maps() : nullptr, shared::kDebugViewScalar, {0.0f, range}};
    if (mShadowMaps) {
        const int size = mShadowMaps->params().mapSize;
        const int slot = std::min(mRender.debugVPL, mShadowMaps->params().slots - 1);
        const glm::ivec3 tile = shared::shadowAtlasTileFromIndex(slot, mShadowMaps->layout().tilesPerRow);
        map.layer = tile.z;
        map.rect = glm::ivec4(tile.x * size, tile.y * size, size, size);
    }
    views.push_back(map);
    DebugView faces{t + ".faces", "hemisphere-cube faces of the last batch of VPLs rendered: window depth",
                    mShadowMaps ? &mShadowMaps->faces().texture() : nullptr, shared::kDebugViewScalar,
                    {0.998f, 1.0f}}; // zNear is 1e-4 of the diagonal: window depth crowds near 1
    faces.layerCount = 0;
    views.push_back(faces);
    views.push_back({t + ".interleaved", "indirect light before the cross-bilateral filter (the 4x4 pattern)",
                     mInterleaved ? &mInterleaved.color(0) : nullptr, shared::kDebugViewColor});
    views.push_back({t + ".splats", "the VPLs as splats coloured by intensity (the brightest at 4) over the indirect light",
                     mSplats ? &mSplats.color(0) : nullptr, shared::kDebugViewColor});
    views.push_back({t + ".overhead",
                     "the scene from above (ceilings culled), the VPLs and the camera frustum (SMCIR Fig. 3)",
                     mOverhead ? &mOverhead.color(0) : nullptr, shared::kDebugViewColor});
    return views;
}

} // namespace vplgi
