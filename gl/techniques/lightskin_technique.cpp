#include "lightskin_technique.h"

#include <algorithm>

#include "core/lightskin/traced_visibility.h"
#include "core/util/content_hash.h"
#include "core/util/error.h"
#include "core/util/params.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/importance.h"
#include "glsl/shared/lightskin.h"
#include "glsl/shared/lightskin_gpu.h"
#include "glsl/shared/normals.h"
#include "glsl/shared/rsm.h"
#include "glsl/shared/tonemap.h"

namespace vplgi {

namespace {

// The dispatch that runs one work-group of kLightSkinGroupSize invocations per cache: caches along
// y, in rows of kLightSkinGroupRows (the GL minimum of work-groups per axis is 65535).
glm::ivec3 perCacheInvocations(int caches)
{
    const int rows = std::min(caches, shared::kLightSkinGroupRows);
    const int slices = (caches + shared::kLightSkinGroupRows - 1) / shared::kLightSkinGroupRows;
    return glm::ivec3(shared::kLightSkinGroupSize, std::max(rows, 1), std::max(slices, 1));
}

// A buffer holding `data`; one element's room when it is empty (GL has no empty buffer).
template <typename T> gl::Buffer storageBufferOf(const std::string& name, const std::vector<T>& data)
{
    const auto bytes = static_cast<GLsizeiptr>(std::max<std::size_t>(data.size(), 1) * sizeof(T));
    return gl::Buffer(name, bytes, data.empty() ? nullptr : data.data());
}

} // namespace

void LightSkinParams::visitParams(ParamVisitor& v, bool selection)
{
    if (selection) {
        v.field("lightskin.valCount", valCount, 1, 65536,
                "N_sVAL: virtual area lights selected from the RSM per frame (section 5: 2048, 4096, 8192)");
        // At most 32768: the importance pass loops over them per texel, and llvmpipe ends a shader's
        // loops after 65535 iterations in all (lightskin_proxy.comp).
        v.field("lightskin.viewSamples", viewSamples, 1, 32768,
                "N_VS: Halton view samples of the importance, eq. (10) (section 4: 512; 256 as an option)");
        v.field("lightskin.importanceClamp", importanceClamp, 0.0f, 1e6f,
                "eq. (11): the squared distance in the importance is clamped to at least clamp^2 [m] (the paper: 1); "
                "0 = scaled with the scene: 1 m on a street like the paper's (our street's 93,148 m^2 of surface), "
                "sqrt(A / 93148 m^2) for surface area A, e.g. for a scene in millimetres (ours; docs/lightskin.md)");
        v.field("lightskin.seed", seed, "seed of the selection");
        v.field("lightskin.animateSeed", animateSeed,
                "new selection uniforms every frame (default: the same every frame)");
    }
    v.field("lightskin.weightEpsilon", weightEpsilon, 0.0f, 1.0f,
            "epsilon_p of eq. (6), keeps the proxy position defined where no VAL reaches the cache");
    v.field("lightskin.fluxWeights", fluxWeights,
            "weight the proxy position (eq. 5/13) by the VALs' flux too (MATH.md 9.3; not in the paper)");
    v.field("lightskin.interpolationExponent", interpolationExponent, 0.0f, 16.0f,
            "p of eq. (8): the distance falloff of the cache weights (the paper gives none; 1 = linear)");
    v.field("lightskin.fixedRadius", fixedRadius,
            "eq. (8)'s d_max is the search radius d_eps (not in the paper); false: the distance of the farthest "
            "cache of the set (the paper)");
    v.field("lightskin.reach", reach,
            "a cache lights only points within its reach, traced with Embree when the caches are made: not "
            "behind a wall, above a ceiling or behind its own surface (not in the paper; light_cache_lookup.h)");
    v.field("lightskin.viewCulling", viewCulling,
            "proxies and occlusion only for the caches a pixel can use, those whose d_eps ball meets the view "
            "frustum (not in the paper; the image is bit-identical without it)");
    v.field("lightskin.occlusion", occlusion,
            "indirect occlusion: by the visibility maps (the default), or with lightskin.visibilityMaps=false by double "
            "projection (section 3)");
    v.field("lightskin.occlusionCells", occlusionCells,
            "with lightskin.visibilityMaps=false, the double projection per cell of the cache's unit disk (its VALs' "
            "footprint in 5 cells; not in the paper); false: one sphere per proxy (the paper)");
    v.field("lightskin.occluderLight", occluderLight,
            "with the double projection's cells, an occluder that the light reaches (the RSM sees it) blocks only what "
            "lies behind it, not the light it reflects itself towards the cache (not in the paper)");
    v.field("lightskin.tracedOcclusion", tracedOcclusion,
            "each cache's visibility traced with Embree instead (the reference for the double projection; "
            "CPU, not real-time; not in the paper)");
    v.field("lightskin.visibilityMaps", visibilityMaps,
            "occlusion by visibility maps: each cache's hemisphere traced once with Embree when the caches are made "
            "(distance and plane per texel), each VAL weighted by what its map says (not in the paper; "
            "glsl/shared/lightskin_visibility.h); false: the paper's double projection (section 3)");
    v.field("lightskin.visibilityMapSize", visibilityMapSize, 2, 256,
            "texels along each side of a cache's visibility map (8 bytes each, per cache)");
    v.field("lightskin.exactArea", exactArea,
            "VAL area: the texel's tilted footprint (MATH.md 9.1) instead of eq. (1)'s disk across the light's view");
    v.field("lightskin.cubeFaceBudget", cubeFaceBudget,
            "the cube faces of a point light (or an emissive source) share one rsm.size^2 RSM, each floor(rsm.size / "
            "sqrt(faces)) texels wide (not in the paper, whose lights are spots and the sun); false: every face "
            "rsm.size^2, six times a spot light's VALs");
    caches.visitParams(v);
    rsm.visitParams(v);
}

LightSkinTechnique::LightSkinTechnique(bool full) : mFull(full) {}

LightSkinTechnique::~LightSkinTechnique() = default;

void LightSkinTechnique::visitParams(ParamVisitor& v)
{
    mParams.visitParams(v, !mFull);
}

void LightSkinTechnique::createPasses(const gl::ShaderLoader& shaders)
{
    // The VALs are level-0 texels: no mips (RSMMips).
    mRSM = std::make_unique<RSMPass>(shaders, RSMMips::None);
    mSampler = std::make_unique<ImportanceSampler>(shaders, "VAL selection");
    mViewSamplePass = ComputePass(shaders, "view samples", "passes/lightskin_view_samples.comp");
    mImportancePass = ComputePass(shaders, "VAL importance", "passes/lightskin_importance.comp");
    mMarkPass = ComputePass(shaders, "selected VALs", "passes/lightskin_mark_selected.comp");
    mProxyPass = ComputePass(shaders, "proxy sums", "passes/lightskin_proxy.comp");
    mFinalizePass = ComputePass(shaders, "proxy lights from sums", "passes/lightskin_proxy_finalize.comp");
    mOcclusionPass = ComputePass(shaders, "double projection", "passes/lightskin_occlusion.comp");
    mShading = std::make_unique<FullscreenPass>(shaders, "interpolation", "passes/lightskin_shading.frag");
    mCacheViewProgram = shaders.load("LightSkin cache view", {{GL_VERTEX_SHADER, "passes/lightskin_caches.vert"},
                                                              {GL_FRAGMENT_SHADER, "passes/lightskin_caches.frag"}});
}

void LightSkinTechnique::setScene(const SceneContext& context)
{
    mScene = &context.scene;
    mGpuScene = &context.gpuScene;
    mRays = &context.rays;
    mProgress = context.progress;
    createPasses(context.shaders);
    mEmptyVertexArray = gl::VertexArray("LightSkin cache points");
    mShaded = gl::RenderTarget("LightSkin radiance", gl::RenderTargetDesc::colors({GL_RGBA32F}, {"radiance"}));
    mCacheView = gl::RenderTarget("LightSkin caches", gl::RenderTargetDesc::colors({GL_RGBA32F}, {"caches"}));
    mCachesStale = true;
    mAutomaticClamp = resolveImportanceClamp(context.scene, 0.0f);
    uploadCaches();
}

void LightSkinTechnique::uploadCaches()
{
    if (!mCachesStale || !mScene) return;
    // $VPLGI_CACHE_DIR or out/cache; core/lightskin/light_caches.h adds its own subfolder.
    mCaches = distributeLightCaches(*mScene, mParams.caches, mProgress, cacheDirectory("out/cache"));
    mCachesStale = false;
    // The reach records (issue "LightSkin's indirect shadows", part 2; not in the paper) for the
    // grid's search radius; without lightskin.reach the lookup skips the test, as the paper.
    if (mParams.reach) mCaches.reach = traceLightCacheReach(mRays->get(), mCaches.caches, mCaches.grid.cellSize);
    // The visibility maps (not in the paper): traced once, like the reach.
    mVisibilityMaps.clear();
    if (mParams.visibilityMaps) {
        const double bytes = static_cast<double>(mCaches.caches.size()) * mParams.visibilityMapSize *
                             mParams.visibilityMapSize * sizeof(glm::uvec2);
        if (bytes > static_cast<double>(kMaxVisibilityMapBytes))
            throw Error("lightskin.visibilityMapSize " + std::to_string(mParams.visibilityMapSize) + " needs " +
                        std::to_string(static_cast<long long>(bytes / (1 << 20))) + " MiB for " +
                        std::to_string(mCaches.caches.size()) + " caches, more than " +
                        std::to_string(kMaxVisibilityMapBytes >> 20) + " MiB: lower it or lightskin.cacheDistance");
        if (mProgress) mProgress("lightskin visibility maps", 0, 1);
        mVisibilityMaps = traceLightCacheVisibilityMaps(mRays->get(), mCaches.caches, mParams.visibilityMapSize);
        if (mProgress) mProgress("lightskin visibility maps", 1, 1);
    }
    const auto count = static_cast<GLsizeiptr>(std::max<std::size_t>(mCaches.caches.size(), 1));
    static_assert(sizeof(LightCache) == sizeof(shared::GpuLightCache), "LightCache is uploaded as GpuLightCache");
    mCacheBuffer = storageBufferOf("light caches", mCaches.caches);
    mCellBuffer = storageBufferOf("light cache cells", mCaches.grid.slots);
    mIndexBuffer = storageBufferOf("light cache indices", mCaches.grid.cacheIndices);
    mReachBuffer = storageBufferOf("light cache reach", mCaches.reach);
    mVisibilityBuffer = storageBufferOf("light cache visibility maps", mVisibilityMaps);
    mProxies = gl::Buffer("proxy lights", count * static_cast<GLsizeiptr>(sizeof(shared::ProxyLight)));
    mCacheRadiance = gl::Buffer("cache radiance", count * static_cast<GLsizeiptr>(sizeof(float)));
    mOcclusionTargets = gl::Buffer("occlusion targets", count * shared::kOcclusionCells *
                                                            static_cast<GLsizeiptr>(sizeof(shared::OcclusionTarget)));
}

void LightSkinTechnique::reloadShaders(const gl::ShaderLoader& shaders)
{
    if (!mScene) return;
    createPasses(shaders);
}

void LightSkinTechnique::applyParamChanges(const std::set<std::string>& changedKeys)
{
    // A changed distribution parameter redistributes the caches (from the disk cache when it has them).
    for (const std::string& key : changedKeys)
        if (key.rfind("lightskin.cache", 0) == 0 || key == "lightskin.reach" || key == "lightskin.visibilityMaps" ||
            key == "lightskin.visibilityMapSize")
            mCachesStale = true;
}

void LightSkinTechnique::update(const FrameContext&)
{
    uploadCaches();
}

void LightSkinTechnique::render(const FrameContext& frame, const GBuffer& gbuffer, const IndirectTarget& target)
{
    const int cacheCount = static_cast<int>(mCaches.caches.size());
    {
        gl::PassTimer::Scope scope(frame.timer, "RSM");
        mRSM->render(*mGpuScene, frame.lights, mParams.rsm, nullptr,
                     mParams.cubeFaceBudget ? RSMCubeFaces::LightBudget : RSMCubeFaces::FaceEach);
    }
    const int layers = mRSM->layerCount();
    const int size = mRSM->size(); // rsm.size within the GL limits
    mShaded.resize(frame.width, frame.height);
    mVALsPerCache = 0;
    // What the passes' view culling keeps (the same test, counted here for the stats).
    mInView.assign(mCaches.caches.size(), 1);
    for (std::size_t i = 0; i < mInView.size() && mParams.viewCulling; ++i)
        mInView[i] = shared::lightCacheInView(frame.clipFromWorld, mCaches.caches[i].position, mCaches.grid.cellSize);
    mCachesInView = std::count(mInView.begin(), mInView.end(), std::uint8_t(1));
    if (layers == 0 || cacheCount == 0) {
        // No spot, point or directional light (or no surface): no one-bounce light from RSMs.
        mShaded.clear();
        glCopyImageSubData(mShaded.color(0).id(), GL_TEXTURE_2D, 0, 0, 0, 0, target.radiance().id(), GL_TEXTURE_2D, 0,
                           0, 0, 0, frame.width, frame.height, 1);
        return;
    }

    // Eq. (1)'s inputs per layer.
    std::vector<shared::RSMLayerView> views;
    for (const RSMView& view : mRSM->views()) {
        const glm::mat4& m = view.viewFromWorld; // column-major: the view-space z row is m[i][2]
        shared::RSMLayerView record;
        record.depthRow = -glm::vec4(m[0][2], m[1][2], m[2][2], m[3][2]); // the view looks down -z
        record.info = glm::vec4(view.texelFactor, view.kind == shared::kRSMLightDirectional ? 1.0f : 0.0f,
                                static_cast<float>(view.size), 0.0f);
        record.clip0 = view.clipFromWorld[0];
        record.clip1 = view.clipFromWorld[1];
        record.clip2 = view.clipFromWorld[2];
        record.clip3 = view.clipFromWorld[3];
        views.push_back(record);
    }
    const auto viewBytes = static_cast<GLsizeiptr>(views.size() * sizeof(shared::RSMLayerView));
    if (mLayerViews.size() < viewBytes) mLayerViews = gl::Buffer("RSM layer views", viewBytes);
    mLayerViews.upload(0, viewBytes, views.data());

    for (int a = 0; a < shared::kRSMAttachmentCount; ++a) {
        glBindTextureUnit(static_cast<GLuint>(shared::kUnitRSMSource + a), mRSM->target().color(a).id());
        glBindSampler(static_cast<GLuint>(shared::kUnitRSMSource + a), 0);
    }
    bindStorageBuffer(shared::kBindingRSMLayerViews, mLayerViews);
    bindStorageBuffer(shared::kBindingRSMLayers, mRSM->layerLights());

    // lightskin-full: every texel of the layers' squares (RSMView::size), laid end to end.
    int texelsInUse = 0;
    for (const RSMView& view : mRSM->views()) texelsInUse += view.size * view.size;
    const int valCount = mFull ? texelsInUse : mParams.valCount;
    if (!mFull) {
        {
            gl::PassTimer::Scope scope(frame.timer, "importance");
            // Eq. (10)'s view samples: the G-buffer at Halton points (MATH.md 9.8).
            const auto sampleBytes =
                static_cast<GLsizeiptr>(mParams.viewSamples) * static_cast<GLsizeiptr>(sizeof(shared::ViewSample));
            if (mViewSamples.size() < sampleBytes) mViewSamples = gl::Buffer("view samples", sampleBytes);
            gbuffer.bindForReading();
            bindStorageBuffer(shared::kBindingViewSamples, mViewSamples);
            mViewSamplePass.program().set("uCount", mParams.viewSamples);
            mViewSamplePass.dispatch(mParams.viewSamples, 1, NextRead::StorageBuffer);

            // Eq. (10)-(11) for every RSM texel, layers side by side.
            if (!mImportance || mImportance.width() != size * layers || mImportance.height() != size) {
                gl::TextureDesc desc;
                desc.format = GL_R32F;
                desc.width = size * layers;
                desc.height = size;
                mImportance = gl::Texture("VAL importance", desc);
                mSelected = gl::Texture("selected VALs", desc);
            }
            bindImage(shared::kImageImportance, mImportance, GL_WRITE_ONLY);
            const gl::Program& importance = mImportancePass.program();
            importance.set("uSize", size);
            importance.set("uLayers", layers);
            importance.set("uViewCount", mParams.viewSamples);
            importance.set("uClampDistance", mParams.importanceClamp > 0.0f ? mParams.importanceClamp : mAutomaticClamp);
            mImportancePass.dispatch(size * layers, size, NextRead::Image);
        }
        {
            gl::PassTimer::Scope scope(frame.timer, "SAT");
            mSampler->build(mImportance, NextRead::None);
        }
        {
            gl::PassTimer::Scope scope(frame.timer, "selection");
            const std::uint32_t seed =
                mParams.animateSeed ? shared::hashPcg(mParams.seed ^ (frame.frameIndex * 0x9E3779B9u)) : mParams.seed;
            mSampler->sample(mImportance, mParams.valCount, seed, NextRead::StorageBuffer);
        }
        // The importance view's range: 20x the mean texel importance, read back only while it is shown.
        if (frame.display == std::string(name()) + ".importance") {
            float total = 0.0f;
            glGetNamedBufferSubData(mSampler->marginal().id(),
                                    static_cast<GLintptr>((size * layers - 1) * static_cast<int>(sizeof(float))),
                                    sizeof(float), &total);
            mImportanceRange = 20.0f * total / static_cast<float>(size * size * layers);
        }
        // The selected texels for the debug view (a few thousand image stores).
        if (frame.display == std::string(name()) + ".selected") {
            const float zero = 0.0f;
            glClearTexImage(mSelected.id(), 0, GL_RED, GL_FLOAT, &zero);
            bindImage(shared::kImageSelectedVALs, mSelected, GL_WRITE_ONLY);
            bindStorageBuffer(shared::kBindingImportanceSamples, mSampler->samples());
            mMarkPass.program().set("uCount", mParams.valCount);
            mMarkPass.dispatch(mParams.valCount, 1, NextRead::TextureFetch);
        }
    }
    mVALsPerCache = valCount;

    bindStorageBuffer(shared::kBindingLightCaches, mCacheBuffer);
    bindStorageBuffer(shared::kBindingProxyLights, mProxies);
    {
        gl::PassTimer::Scope scope(frame.timer, "proxy lights");
        // The VALs in chunks of at most 64 x 16384 (lightskin_proxy.comp says why), at most 64
        // chunks while that suffices; one chunk for the selected few thousand.
        const int group = shared::kLightSkinGroupSize;
        const int perLane = std::clamp((valCount + group * 64 - 1) / (group * 64), 256, 16384);
        const int chunkSize = group * perLane;
        const int chunks = (valCount + chunkSize - 1) / chunkSize;
        const auto sumBytes = static_cast<GLsizeiptr>(cacheCount) * chunks * shared::kProxySumVec4s *
                              static_cast<GLsizeiptr>(sizeof(glm::vec4));
        if (mProxySums.size() < sumBytes) mProxySums = gl::Buffer("proxy sums", sumBytes);
        if (!mFull) bindStorageBuffer(shared::kBindingImportanceSamples, mSampler->samples());
        bindStorageBuffer(shared::kBindingProxySums, mProxySums);
        const gl::Program& proxy = mProxyPass.program();
        proxy.set("uAllTexels", mFull ? 1 : 0);
        proxy.set("uValCount", valCount);
        proxy.set("uSelectionCount", mParams.valCount);
        proxy.set("uSize", size);
        proxy.set("uLayers", layers);
        proxy.set("uCacheCount", cacheCount);
        proxy.set("uChunkSize", chunkSize);
        proxy.set("uEpsilon", mParams.weightEpsilon);
        proxy.set("uFluxWeights", mParams.fluxWeights ? 1 : 0);
        proxy.set("uExactArea", mParams.exactArea ? 1 : 0);
        proxy.set("uChunks", chunks);
        proxy.set("uViewCulling", mParams.viewCulling ? 1 : 0);
        proxy.set("uCullRadius", mCaches.grid.cellSize);
        const bool maps = mParams.occlusion && mParams.visibilityMaps && !mParams.tracedOcclusion;
        bindStorageBuffer(shared::kBindingLightCacheVisibility, mVisibilityBuffer);
        proxy.set("uVisibilityMaps", maps ? 1 : 0);
        proxy.set("uVisibilityMapSize", mParams.visibilityMapSize);
        proxy.set("uVisibilityLift", lightCacheVisibilityLift(mRays->get()));
        // lightskin-full's pass can take minutes (every texel for every cache): chunk by chunk with
        // progress when it is that large (caches x VALs above 1e9), in one dispatch otherwise.
        const bool showProgress = mFull && static_cast<double>(cacheCount) * valCount > 1e9 && mProgress;
        const int perDispatch = showProgress ? 1 : chunks;
        if (showProgress) mProgress("lightskin-full proxy lights", 0, chunks);
        for (int first = 0; first < chunks; first += perDispatch) {
            proxy.set("uChunkFirst", first);
            glm::ivec3 invocations = perCacheInvocations(cacheCount);
            invocations.x *= std::min(perDispatch, chunks - first);
            mProxyPass.dispatch(invocations, NextRead::StorageBuffer);
            if (showProgress) {
                glFinish();
                mProgress("lightskin-full proxy lights", first + perDispatch, chunks);
            }
        }
        bindStorageBuffer(shared::kBindingOcclusionTargets, mOcclusionTargets);
        bindStorageBuffer(shared::kBindingCacheRadiance, mCacheRadiance);
        // Each cache's own radiance only where the double projection's cells will read it.
        const bool ownRadiance = mParams.occlusion && !mParams.tracedOcclusion && !mParams.visibilityMaps &&
                                 mParams.occlusionCells && mParams.occluderLight;
        mFinalizePass.program().set("uOwnRadiance", ownRadiance ? 1 : 0);
        mFinalizePass.program().set("uLayers", layers);
        mFinalizePass.program().set("uCacheCount", cacheCount);
        mFinalizePass.program().set("uChunks", chunks);
        mFinalizePass.program().set("uOcclusionCells", mParams.occlusionCells ? 1 : 0);
        mFinalizePass.program().set("uViewCulling", mParams.viewCulling ? 1 : 0);
        mFinalizePass.program().set("uCullRadius", mCaches.grid.cellSize);
        mFinalizePass.dispatch(cacheCount, 1, NextRead::StorageBuffer);
    }
    if (mParams.tracedOcclusion) {
        gl::PassTimer::Scope scope(frame.timer, "occlusion (traced)");
        traceOcclusion(size, layers);
    } else if (mParams.occlusion && !mParams.visibilityMaps) {
        gl::PassTimer::Scope scope(frame.timer, "occlusion");
        mOcclusionPass.program().set("uCacheCount", cacheCount);
        mOcclusionPass.program().set("uOccluderLight", mParams.occluderLight ? 1 : 0);
        mOcclusionPass.program().set("uViewCulling", mParams.viewCulling ? 1 : 0);
        mOcclusionPass.program().set("uCullRadius", mCaches.grid.cellSize);
        mOcclusionPass.dispatch(perCacheInvocations(cacheCount), NextRead::StorageBuffer);
    }
    {
        gl::PassTimer::Scope scope(frame.timer, "interpolation");
        gbuffer.bindForReading();
        bindStorageBuffer(shared::kBindingLightCacheCells, mCellBuffer);
        bindStorageBuffer(shared::kBindingLightCacheIndices, mIndexBuffer);
        bindStorageBuffer(shared::kBindingLightCacheReach, mReachBuffer);
        const gl::Program& shading = mShading->program();
        const LightCacheGrid& grid = mCaches.grid;
        shading.set("uGridOrigin", grid.origin);
        shading.set("uGridCellSize", grid.cellSize);
        glProgramUniform1ui(shading.id(), shading.uniformLocation("uGridSlotMask"), grid.slotMask);
        shading.set("uGridMaxProbe", grid.maxProbe);
        shading.set("uExponent", mParams.interpolationExponent);
        shading.set("uReach", mCaches.reach.empty() ? 0 : 1);
        shading.set("uFixedRadius", mParams.fixedRadius ? 1 : 0);
        mShading->render(mShaded);
    }
    glCopyImageSubData(mShaded.color(0).id(), GL_TEXTURE_2D, 0, 0, 0, 0, target.radiance().id(), GL_TEXTURE_2D, 0, 0, 0,
                       0, frame.width, frame.height, 1);
    for (int a = 0; a < shared::kRSMAttachmentCount; ++a)
        glBindTextureUnit(static_cast<GLuint>(shared::kUnitRSMSource + a), 0);
    if (frame.display == std::string(name()) + ".caches") drawCacheView(frame);
}

void LightSkinTechnique::traceOcclusion(int size, int layers)
{
    // The RSM's level 0 and its layers' lights, read back (a reference: its cost is not the point).
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    const std::size_t layerTexels = static_cast<std::size_t>(size) * static_cast<std::size_t>(size);
    const std::size_t texels = layerTexels * static_cast<std::size_t>(layers);
    auto read = [&](int attachment) {
        std::vector<glm::vec4> data(texels);
        glGetTextureSubImage(mRSM->target().color(attachment).id(), 0, 0, 0, 0, size, size, layers, GL_RGBA, GL_FLOAT,
                             static_cast<GLsizei>(texels * sizeof(glm::vec4)), data.data());
        return data;
    };
    const std::vector<glm::vec4> position = read(shared::kRSMPosition), normal = read(shared::kRSMNormal),
                                 flux = read(shared::kRSMFlux), diffuse = read(shared::kRSMDiffuse);
    std::vector<shared::RSMLayerLight> lights(static_cast<std::size_t>(layers));
    glGetNamedBufferSubData(mRSM->layerLights().id(), 0,
                            static_cast<GLsizeiptr>(lights.size() * sizeof(shared::RSMLayerLight)), lights.data());
    const std::vector<RSMView>& views = mRSM->views();
    // The VALs as lightskin_proxy.comp takes them (flux x albedo, the shading-normal correction,
    // eq. (1)'s area), for lightskin-full's every texel; the selection does not enter visibility.
    std::vector<TracedVAL> vals;
    for (std::size_t i = 0; i < texels; ++i) {
        if (normal[i].w == 0.0f) continue;
        glm::vec3 reflected = glm::vec3(flux[i]) * glm::vec3(diffuse[i]);
        if (reflected == glm::vec3(0.0f)) continue;
        const std::size_t layer = i / layerTexels;
        const glm::vec3 x(position[i]);
        const glm::vec3 ns = glm::normalize(glm::vec3(normal[i]));
        const glm::vec3 ng = shared::octDecode(glm::vec2(flux[i].w, diffuse[i].w));
        const glm::vec3 toLight = shared::rsmDirectionToLight(lights[layer], x);
        const float cosGeometricIn = glm::dot(ng, toLight);
        if (!(cosGeometricIn > 1e-3f)) continue;
        reflected *= std::max(glm::dot(ns, toLight), 0.0f) / cosGeometricIn;
        const RSMView& view = views[layer];
        const float depth = -(view.viewFromWorld * glm::vec4(x, 1.0f)).z;
        TracedVAL val;
        val.position = x;
        val.normal = ng;
        val.area = shared::lightskinValArea(depth, view.texelFactor, view.kind == shared::kRSMLightDirectional);
        val.power = shared::luminanceRec709(reflected);
        vals.push_back(val);
    }
    const std::vector<float> visibility = traceCacheVisibility(mRays->get(), mCaches.caches, vals, 256, mParams.seed, mInView);
    std::vector<shared::ProxyLight> proxies(mCaches.caches.size());
    const auto bytes = static_cast<GLsizeiptr>(proxies.size() * sizeof(shared::ProxyLight));
    glGetNamedBufferSubData(mProxies.id(), 0, bytes, proxies.data());
    for (std::size_t i = 0; i < proxies.size(); ++i)
        proxies[i].diffuseFlux.w = proxies[i].glossyFlux.w = visibility[i];
    mProxies.upload(0, bytes, proxies.data());
}

void LightSkinTechnique::drawCacheView(const FrameContext& frame)
{
    // The caches as points over the indirect image, coloured by the radiance their proxies give
    // them (hidden ones dropped against the G-buffer's depth in the fragment shader).
    gl::DebugGroup group(std::string(name()) + " cache view");
    mCacheView.resize(frame.width, frame.height);
    glCopyImageSubData(mShaded.color(0).id(), GL_TEXTURE_2D, 0, 0, 0, 0, mCacheView.color(0).id(), GL_TEXTURE_2D, 0, 0,
                       0, 0, frame.width, frame.height, 1);
    mCacheView.bindForDrawing();
    glUseProgram(mCacheViewProgram.id());
    bindStorageBuffer(shared::kBindingLightCaches, mCacheBuffer);
    bindStorageBuffer(shared::kBindingProxyLights, mProxies);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(mEmptyVertexArray.id());
    glDrawArrays(GL_POINTS, 0, static_cast<GLsizei>(mCaches.caches.size()));
    glBindVertexArray(0);
    glDisable(GL_PROGRAM_POINT_SIZE);
}

std::vector<std::pair<std::string, double>> LightSkinTechnique::frameStats() const
{
    return {{"caches", static_cast<double>(mCaches.caches.size())},
            {"caches in view", static_cast<double>(mCachesInView)},
            {"vals", static_cast<double>(mVALsPerCache)},
            {"rsm layers", static_cast<double>(mRSM ? mRSM->layerCount() : 0)}};
}

std::vector<DebugView> LightSkinTechnique::debugViews() const
{
    const std::string t(name());
    std::vector<DebugView> views;
    views.push_back(rsmFluxDebugView(t + ".rsm", mRSM.get()));
    views.push_back({t + ".caches", "the light caches as points coloured by the radiance of their diffuse proxy",
                     mCacheView ? &mCacheView.color(0) : nullptr, shared::kDebugViewColor});
    if (!mFull) {
        views.push_back({t + ".importance",
                         "eq. (10): importance of every RSM texel, layers side by side",
                         mImportance ? &mImportance : nullptr,
                         shared::kDebugViewCount,
                         {0.0f, mImportanceRange > 0.0f ? mImportanceRange : 1.0f}});
        views.push_back({t + ".selected",
                         "the VALs selected this frame (1), layers side by side",
                         mSelected ? &mSelected : nullptr,
                         shared::kDebugViewScalar,
                         {0.0f, 1.0f}});
    }
    return views;
}

} // namespace vplgi
