#include "vsgl_technique.h"

#include <algorithm>

#include "core/util/error.h"
#include "core/util/params.h"
#include "core/util/power_of_two.h"
#include "gl/api/limits.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/importance.h"
#include "glsl/shared/rsm.h"
#include "glsl/shared/sg.h"

namespace vplgi {

void VSGLParams::visitParams(ParamVisitor& v, const std::string& p, Kind kind)
{
    const bool pointLights = kind != VSGL;
    if (kind == TCAS)
        v.field(p + ".count", count, 1, 65536, "N: VPLs, one Metropolis-Hastings chain each (1024 as vpl-brsm's)");
    else
        v.field(p + ".count", count, 1, 65536, "N: lights drawn from the BRSM per frame (VSGL section 4: 1024)");
    if (!pointLights) {
        v.field(p + ".smoothness", smoothness, 1e-3f, 1e6f,
                "k: the footprints of the N lights cover the RSM k times; picks the mip level (section 3.2; 4)");
        v.choice(p + ".footprint", footprint, {"texel", "cell"},
                 "each light's mip level and flux: texel, the paper's reading (h = 1/2 log2(k / (N P_j)), flux "
                 "Phi_h / (N P_j)); cell (not in the paper): the coarsest mip cell with at most k expected draws, "
                 "flux Phi_cell / (N P_cell) of that cell: unbiased (docs/vsgl.md)");
        v.field(p + ".maxLeaf", maxLeaf, 0, 12,
                "cell footprints: the coarsest mip level a leaf may have, 2 = at most 4 x 4 RSM texels (not in "
                "the paper; a cap keeps the partition, so the estimator stays unbiased; docs/vsgl.md); 12: no cap");
        v.field(p + ".leafEdges", leafEdges,
                "cell footprints: a leaf holds no two neighbouring RSM texels on different surfaces (geometric "
                "normals over 30 degrees apart, or off each other's plane); monotone up the mip chain, so the "
                "leaves stay a partition; leaves then stop at 32 x 32 texels (not in the paper; docs/vsgl.md)");
        v.choice(p + ".leafReads", leafReads, {"bilinear", "cell", "surface"},
                 "cell footprints: position, normal, spread and lobes bilinear at the leaf's level (smooth in the "
                 "draw, blending the neighbouring cells in), the leaf cell's own as its flux, or bilinear over the "
                 "cells on the leaf's surface only (not in the paper; docs/vsgl.md)");
        v.field(p + ".biasAlpha", biasAlpha, 0.0f, 1e6f,
                "alpha of the consistent bias reduction (section 3.3; Fig. 6: 0.001); 0 = keep the SG approximation");
    } else {
        v.field(p + ".clampGeometry", clampGeometry, 0.0f, 1e9f,
                "cap on cos cos / d^2 [1/m^2] of the VPLs; 0 = unclamped (the paper's VPL figures)");
    }
    v.choice(p + ".pdf", pdf, {"sg", "point"},
             "PDF of BRSMs: sg, the VSGL paper's (each RSM texel lit by the view lights as VSGLs); point, the "
             "original BRSM's point formula (MATH.md 10.1 with glTF BRDFs at both ends, the paper's Fig. 4a)");
    v.field(p + ".viewGrid", viewGrid, 2, 4096,
            "PDF of BRSMs: the G-buffer grid acting as the light [texels], a power of two (not in the paper)");
    v.field(p + ".viewLevel", viewLevel, 0, 12,
            "PDF of BRSMs: the grid's mip level whose texels are the view lights ((viewGrid / 2^level)^2 lights)");
    if (kind == TCAS) {
        v.field(p + ".iterations", iterations, 0, 1024,
                "Metropolis-Hastings iterations of every chain per frame (SMCIR section 5.1: 16; Barak et al.: 5)");
        v.field(p + ".globalProbability", proposal.globalProbability, 0.0f, 1.0f,
                "probability of a proposal uniform over the RSMs, else a local step (not in the papers; docs/tcas.md)");
        v.field(p + ".stepRadius", proposal.stepRadius, 1, 64,
                "local proposals: offsets uniform in [-r, r]^2 RSM texels (not in the papers; docs/tcas.md)");
        v.field(p + ".seed", seed, "seed of the chains' first draws and of their steps (new uniforms every frame)");
    } else {
        v.field(p + ".seed", seed, "seed of the draws");
        v.field(p + ".animateSeed", animateSeed, "new draws every frame (default: the same uniforms every frame)");
    }
    v.choice(p + ".visibility", visibility, {"ism", "none"},
             "light visibility: imperfect shadow maps (the paper's AISMs without view adaptation) or none");
    ism.visitParams(v, p + ".ism");
    rsm.visitParams(v);
}

VSGLTechnique::VSGLTechnique(VSGLParams::Kind kind) : mKind(kind) {}

VSGLTechnique::~VSGLTechnique() = default;

void VSGLTechnique::visitParams(ParamVisitor& v)
{
    mParams.visitParams(v, std::string(name()), mKind);
}

void VSGLTechnique::createPasses(const gl::ShaderLoader& shaders)
{
    // Only VSGL's footprints read the RSM's mips; vpl-brsm's VPLs read level 0.
    mRSM = std::make_unique<RSMPass>(shaders, pointLights() ? RSMMips::None : RSMMips::All);
    mSampler = std::make_unique<ImportanceSampler>(shaders, "BRSM sampler");
    if (mKind == VSGLParams::TCAS) {
        mChains = std::make_unique<MetropolisChains>(shaders, "TCAS chains");
        mChainsStarted = false;
    }
    mViewRSMPass = ComputePass(shaders, "G-buffer as light", "passes/vsgl_view_rsm.comp");
    mGeneratePass = ComputePass(shaders, pointLights() ? "VPL generation" : "VSGL generation", "passes/vsgl_generate.comp");
    mNoImportance = gl::Texture::placeholder("no importance", GL_TEXTURE_2D, GL_R32F);
    mImportancePass = ComputePass(shaders, "BRSM importance", "passes/vsgl_importance.comp");
    mShading = std::make_unique<FullscreenPass>(shaders, "radiance estimation", "passes/vsgl_shading.frag");
}

void VSGLTechnique::setScene(const SceneContext& context)
{
    mScene = &context.scene;
    mGpuScene = &context.gpuScene;
    mShaders = &context.shaders;
    mISM.reset();
    createPasses(context.shaders);
    gl::SamplerDesc trilinear;
    trilinear.minFilter = GL_LINEAR_MIPMAP_LINEAR;
    trilinear.magFilter = GL_LINEAR;
    mTrilinear = gl::Sampler("VSGL trilinear RSM", trilinear);
    mViewRSM = makeRSMLayoutTarget("G-buffer as light", false);
    mShaded = gl::RenderTarget("VSGL radiance", gl::RenderTargetDesc::colors({GL_RGBA32F, GL_RGBA32F},
                                                                            {"radiance", "cancelled fraction"}));
}

void VSGLTechnique::reloadShaders(const gl::ShaderLoader& shaders)
{
    if (!mScene) return;
    createPasses(shaders);
    if (mISM) mISM->reloadShaders(shaders);
}

void VSGLTechnique::applyParamChanges(const std::set<std::string>& changedKeys)
{
    // The maps are sized for N lights and hold the point set: remade on the next render().
    const std::string p = std::string(name()) + ".";
    for (const std::string& key : changedKeys) {
        if (key == p + "count" || key.rfind(p + "ism", 0) == 0) mISM.reset();
        // tcas: a new count or seed starts the chains again from draws.
        if (key == p + "count" || key == p + "seed") mChainsStarted = false;
    }
}

void VSGLTechnique::update(const FrameContext&) {}

void VSGLTechnique::render(const FrameContext& frame, const GBuffer& gbuffer, const IndirectTarget& target)
{
    require(isPowerOfTwo(mParams.viewGrid), std::string(name()) + ".viewGrid must be a power of two, not " +
                                                std::to_string(mParams.viewGrid));
    const std::string prefix(name());
    const bool cells = !pointLights() && mParams.footprint == VSGLParams::Cell; // vsgl.footprint
    mValidLights = 0;
    // N lights in one storage block, and a per-pixel shading loop over all N (llvmpipe stops it
    // after 65535 iterations: N = 65536 would drop the last light).
    mCount = gl::clampShaderLoopCount(
        gl::clampStorageCount(mParams.count, sizeof(shared::VSGLight), prefix + ".count"), prefix + ".count");
    // RSMs (section 4: 256^2), every frame: lights move.
    {
        gl::PassTimer::Scope scope(frame.timer, "RSMs");
        mRSM->render(*mGpuScene, frame.lights, mParams.rsm);
    }
    const int layers = mRSM->layerCount();
    const int size = mRSM->size(); // rsm.size within the GL limits
    if (layers == 0) {
        // No spot, point or directional light: no one-bounce light from RSMs.
        mShaded.resize(frame.width, frame.height);
        mShaded.clear();
        return;
    }
    auto bindRSMLayout = [&](const gl::RenderTarget& t, bool filtered) {
        for (int a = 0; a < shared::kRSMAttachmentCount; ++a) {
            glBindTextureUnit(static_cast<GLuint>(shared::kUnitRSMSource + a), t.color(a).id());
            glBindSampler(static_cast<GLuint>(shared::kUnitRSMSource + a), filtered ? mTrilinear.id() : 0);
        }
    };
    {
        gl::PassTimer::Scope scope(frame.timer, "PDF of BRSMs");
        // 1. The G-buffer as the light: a grid in the RSM layout, its mips, level L's texels as lights.
        const int grid = mParams.viewGrid;
        int viewLevel = std::min(mParams.viewLevel, mipLevelCount(grid) - 1);
        // Every RSM texel's importance loops over all view lights, which sit in one storage block:
        // a grid too fine for either is read one level coarser until it fits, with one warning line
        // (issue "VSGL made exact", part 4; viewGrid 4096 at level 0 would be 16.7M lights).
        auto viewLightsAt = [&](int level) { return std::max(grid >> level, 1) * std::max(grid >> level, 1); };
        const int allowedViewLights = gl::clampShaderLoopCount(
            gl::clampStorageCount(viewLightsAt(viewLevel), sizeof(shared::VSGLight), prefix + " view lights"),
            prefix + " view lights ((viewGrid / 2^viewLevel)^2, read at the first coarser level that fits)");
        while (viewLightsAt(viewLevel) > allowedViewLights) ++viewLevel;
        mViewRSM.resize(grid, grid, 1);
        gbuffer.bindForReading();
        for (int a = 0; a < shared::kRSMAttachmentCount; ++a)
            bindImage(shared::kImageRSMTarget + a, mViewRSM.color(a), GL_WRITE_ONLY, 0);
        mViewRSMPass.program().set("uSize", grid);
        mViewRSMPass.program().set("uEye", frame.camera.position);
        mViewRSMPass.dispatch(grid, grid, NextRead::TextureFetch);
        downsampleRSMLayout(mRSM->downsampleKernel(), mViewRSM);
        mViewLightCount = viewLightsAt(viewLevel);
        const auto viewBytes = static_cast<GLsizeiptr>(mViewLightCount) * static_cast<GLsizeiptr>(sizeof(shared::VSGLight));
        if (mViewLights.size() < viewBytes) mViewLights = gl::Buffer("VSGL view lights", viewBytes);
        bindRSMLayout(mViewRSM, false);
        bindStorageBuffer(shared::kBindingVSGLights, mViewLights);
        const gl::Program& generate = mGeneratePass.program();
        generate.set("uMode", 2);
        generate.set("uCount", mViewLightCount);
        generate.set("uSize", grid);
        generate.set("uLevels", mipLevelCount(grid));
        generate.set("uLevel", viewLevel);
        generate.set("uSmoothness", mParams.smoothness);
        glBindTextureUnit(static_cast<GLuint>(shared::kUnitImportanceMips), mNoImportance.id());
        mGeneratePass.dispatch(mViewLightCount, 1, NextRead::StorageBuffer);

        // 2. Importance of every RSM texel (MATH.md 10.1), layers side by side.
        if (!mImportance || mImportance.width() != size * layers || mImportance.height() != size) {
            gl::TextureDesc desc;
            desc.format = GL_R32F;
            desc.width = size * layers;
            desc.height = size;
            desc.levels = mRSM->levelCount(); // box mips within one layer (vsgl.footprint = cell)
            mImportance = gl::Texture("BRSM importance", desc);
            mChainsStarted = false; // tcas: the chains' texels index the old map
        }
        bindRSMLayout(mRSM->target(), false);
        bindImage(shared::kImageImportance, mImportance, GL_WRITE_ONLY);
        bindStorageBuffer(shared::kBindingRSMLayers, mRSM->layerLights());
        mImportancePass.program().set("uSize", size);
        mImportancePass.program().set("uLayers", layers);
        mImportancePass.program().set("uViewCount", mViewLightCount);
        mImportancePass.program().set("uPointFormula", mParams.pdf == VSGLParams::Point ? 1 : 0);
        mImportancePass.program().set("uEye", frame.camera.position);
        mImportancePass.program().set("uClampGeometry", pointLights() ? mParams.clampGeometry : 0.0f);
        mImportancePass.dispatch(size * layers, size, NextRead::Image);

        // 3. The tables and N draws (MATH.md 9.7).
        mSampler->build(mImportance, NextRead::None);
        if (mKind == VSGLParams::TCAS) {
            // tcas: the chains, started once from N draws (the map's size and N fixed since), then
            // tcas.iterations Metropolis-Hastings steps per frame with new uniforms every frame.
            if (mChains->count() != mCount) mChainsStarted = false;
            if (!mChainsStarted) {
                mSampler->sample(mImportance, mCount, mParams.seed, NextRead::StorageBuffer);
                mChains->start(mImportance, *mSampler, mCount, NextRead::StorageBuffer);
                mChainsStarted = true;
            }
            mChains->step(mImportance, *mSampler, mParams.iterations,
                          shared::hashPcg(mParams.seed ^ shared::hashPcg(frame.frameIndex + 1u)), mParams.proposal,
                          NextRead::StorageBuffer, &frame.timer);
        } else {
            const std::uint32_t seed = mParams.animateSeed
                                           ? shared::hashPcg(mParams.seed ^ (frame.frameIndex * 0x9E3779B9u))
                                           : mParams.seed;
            mSampler->sample(mImportance, mCount, seed, NextRead::StorageBuffer);
        }
        if (cells) {
            // The cells' probabilities: 2x2 means up the chain, our own pass (power-of-two layers: no
            // cell straddles two; issue "VSGL made exact", part 4).
            mSampler->buildMips(mImportance, NextRead::TextureFetch);
        }
    }
    {
        gl::PassTimer::Scope scope(frame.timer, "VPL/VSGL generation");
        const auto bytes = static_cast<GLsizeiptr>(mCount) * static_cast<GLsizeiptr>(sizeof(shared::VSGLight));
        if (mLights.size() < bytes) mLights = gl::Buffer(prefix + " lights", bytes);
        bindRSMLayout(mRSM->target(), !pointLights());
        bindStorageBuffer(shared::kBindingImportanceSamples,
                          mKind == VSGLParams::TCAS ? mChains->samples() : mSampler->samples());
        bindStorageBuffer(shared::kBindingVSGLights, mLights);
        const gl::Program& generate = mGeneratePass.program();
        generate.set("uMode", pointLights() ? 1 : 0);
        generate.set("uCount", mCount);
        generate.set("uSize", size);
        generate.set("uLevels", mRSM->levelCount());
        generate.set("uLevel", 0);
        generate.set("uSmoothness", mParams.smoothness);
        generate.set("uFootprint", cells ? 1 : 0);
        generate.set("uMaxLeaf", mParams.maxLeaf);
        generate.set("uLeafEdges", cells && mParams.leafEdges ? 1 : 0);
        generate.set("uLeafReads", cells ? mParams.leafReads : 0);
        generate.set("uLayers", layers);
        glBindTextureUnit(static_cast<GLuint>(shared::kUnitImportanceMips), mImportance.id());
        glBindSampler(static_cast<GLuint>(shared::kUnitImportanceMips), mTrilinear.id());
        mGeneratePass.dispatch(mCount, 1, NextRead::StorageBuffer);
        for (int a = 0; a < shared::kRSMAttachmentCount; ++a)
            glBindSampler(static_cast<GLuint>(shared::kUnitRSMSource + a), 0);
        glBindSampler(static_cast<GLuint>(shared::kUnitImportanceMips), 0);
    }
    const bool visibility = mParams.visibility == VSGLParams::ISM;
    if (visibility) {
        gl::PassTimer::Scope scope(frame.timer, "shadow maps");
        if (!mISM || mISM->maxLights() < mCount) {
            mISM = std::make_unique<ImperfectShadowMaps>(*mShaders, mParams.ism, mCount);
            mISM->setScene(*mScene);
        }
        // VSGLight: r^2 in the position's w (vec4 0), the valid flag in the normal's (vec4 1).
        mISM->update(mLights, mCount, static_cast<int>(sizeof(shared::VSGLight) / sizeof(glm::vec4)), 1, 0, &frame.timer);
    }
    {
        gl::PassTimer::Scope scope(frame.timer, "radiance estimation");
        mShaded.resize(frame.width, frame.height);
        gbuffer.bindForReading();
        bindStorageBuffer(shared::kBindingVSGLights, mLights);
        bindStorageBuffer(shared::kBindingRSMLayers, mRSM->layerLights());
        const gl::Program& shading = mShading->program();
        shading.set("uCount", mCount);
        shading.set("uPointLights", pointLights() ? 1 : 0);
        shading.set("uBiasAlpha", mParams.biasAlpha);
        shading.set("uClampGeometry", pointLights() ? mParams.clampGeometry : 0.0f);
        shading.set("uVisibility", visibility ? 1 : 0);
        if (visibility) mISM->bindForReading(shading);
        mShading->render(mShaded);
    }
    glCopyImageSubData(mShaded.color(0).id(), GL_TEXTURE_2D, 0, 0, 0, 0, target.radiance().id(), GL_TEXTURE_2D, 0, 0,
                       0, 0, frame.width, frame.height, 1);
}

std::vector<std::pair<std::string, double>> VSGLTechnique::frameStats() const
{
    std::vector<std::pair<std::string, double>> stats{{pointLights() ? "vpls" : "vsgls", static_cast<double>(mCount)},
            {"view lights", static_cast<double>(mViewLightCount)},
            {"rsm layers", static_cast<double>(mRSM ? mRSM->layerCount() : 0)}};
    if (mKind == VSGLParams::TCAS && mChains && mChainsStarted)
        stats.emplace_back("vplsMoved", static_cast<double>(mChains->movedInLastStep()));
    return stats;
}

std::vector<DebugView> VSGLTechnique::debugViews() const
{
    const std::string t(name());
    std::vector<DebugView> views;
    const bool haveRSM = mRSM && mRSM->layerCount() > 0;
    views.push_back(rsmFluxDebugView(t + ".rsm", mRSM.get()));
    DebugView normals{t + ".rsmNormal", "the RSMs' normals", haveRSM ? &mRSM->target().color(shared::kRSMNormal) : nullptr,
                      shared::kDebugViewNormal};
    normals.layerCount = 0;
    views.push_back(normals);
    views.push_back({t + ".importance", "the PDF of BRSMs: importance of every RSM texel, layers side by side",
                     mImportance ? &mImportance : nullptr, shared::kDebugViewCount, {0.0f, 1.0f}});
    views.push_back({t + ".viewLights", "the G-buffer grid acting as the light (its flux: coverage)",
                     mViewRSM ? &mViewRSM.color(shared::kRSMNormal) : nullptr, shared::kDebugViewNormal});
    DebugView maps{t + ".ism", "the imperfect shadow maps of every light: distance [0, scene diagonal]",
                   mISM ? &mISM->maps() : nullptr, shared::kDebugViewScalar,
                   {0.0f, mScene ? glm::length(mScene->worldBounds().extent()) : 1.0f}};
    maps.layerCount = 0;
    views.push_back(maps);
    if (!pointLights())
        views.push_back({t + ".cancellation",
                         "fraction of the lights whose SG approximation section 3.3 cancelled (Fig. 6 bottom)",
                         mShaded ? &mShaded.color(1) : nullptr, shared::kDebugViewScalar, {0.0f, 1.0f}});
    return views;
}

} // namespace vplgi
