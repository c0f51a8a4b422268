#include "rsm_pass.h"

#include <algorithm>
#include <cmath>

#include <cstdio>

#include "core/util/error.h"
#include "core/util/params.h"
#include "core/util/power_of_two.h"
#include "gl/api/limits.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/light_view.h"
#include "glsl/shared/rsm.h"

namespace vplgi {

void RSMParams::visitParams(ParamVisitor& v)
{
    v.field("rsm.size", size, 2, 4096,
            "RSM resolution per spot light, point-light cube face and directional light [texels], a power of two");
    v.field("rsm.areaSources", areaSources, 0, 64,
            "emissive triangles become at most this many cosine RSM sources, rendered like point lights over "
            "their hemisphere (not in the papers); 0: emissive light gives no indirect light (a warning)");
}

namespace {

SceneProgram loadProgram(const gl::ShaderLoader& shaders)
{
    return SceneProgram(shaders, "rsm", {{GL_VERTEX_SHADER, "passes/rsm.vert"}, {GL_FRAGMENT_SHADER, "passes/rsm.frag"}});
}

float texelFactor(const glm::mat4& clipFromView, int size)
{
    const float texels = static_cast<float>(size) * static_cast<float>(size);
    return 4.0f / (clipFromView[0][0] * clipFromView[1][1] * texels);
}

} // namespace

gl::RenderTarget makeRSMLayoutTarget(const std::string& name, bool withDepth, bool mips)
{
    gl::RenderTargetDesc desc;
    desc.colorFormats.assign(shared::kRSMAttachmentCount, GL_RGBA32F);
    desc.colorNames = {"position", "normal", "flux", "diffuse", "specular", "lobe"};
    desc.depthFormat = withDepth ? GL_DEPTH_COMPONENT32F : GL_NONE;
    desc.textureTarget = GL_TEXTURE_2D_ARRAY;
    desc.levels = mips ? 0 : 1;
    return gl::RenderTarget(name, desc);
}

void downsampleRSMLayout(const ComputePass& kernel, const gl::RenderTarget& target, gl::PassTimer* timer)
{
    const int levels = target.color(0).desc().levels; // 1 (RSMMips::None): nothing to do
    const int layers = target.color(0).desc().layers;
    for (int level = 1; level < levels; ++level) {
        const int size = std::max(1, target.width() >> level);
        // Level l through texelFetch (no sampler object: texelFetch ignores filtering), level l+1 as
        // images; different levels of one texture are different memory.
        for (int a = 0; a < shared::kRSMAttachmentCount; ++a) {
            glBindTextureUnit(static_cast<GLuint>(shared::kUnitRSMSource + a), target.color(a).id());
            glBindSampler(static_cast<GLuint>(shared::kUnitRSMSource + a), 0);
            bindImage(shared::kImageRSMTarget + a, target.color(a), GL_WRITE_ONLY, level);
        }
        glProgramUniform2i(kernel.program().id(), kernel.program().uniformLocation("uTargetSize"), size, size);
        kernel.program().set("uSourceLevel", level - 1);
        // The next level reads this one with texelFetch; after the last, consumers sample the mips,
        // read them back or load them as images.
        const NextRead next = level + 1 < levels ? NextRead::TextureFetch
                                                 : NextRead::TextureFetch | NextRead::TextureReadback | NextRead::Image;
        kernel.dispatch(glm::ivec3(size, size, layers), next, timer);
    }
}

RSMPass::RSMPass(const gl::ShaderLoader& shaders, RSMMips mips)
    : mProgram(loadProgram(shaders)), mDownsample(shaders, "rsm downsample", "passes/rsm_downsample.comp"),
      mMips(mips), mTarget(makeRSMLayoutTarget("rsm", true, mips == RSMMips::All))
{
}

void RSMPass::reloadShaders(const gl::ShaderLoader& shaders)
{
    mProgram = loadProgram(shaders);
    mDownsample.reloadShaders(shaders);
}

std::vector<RSMView> RSMPass::makeViews(const AABB& bounds, const DirectLightSet& lights, int areaSources, int size,
                                        RSMCubeFaces faces)
{
    const glm::vec3 lower = bounds.empty() ? glm::vec3(0.0f) : bounds.lower;
    const glm::vec3 upper = bounds.empty() ? glm::vec3(0.0f) : bounds.upper;
    const float diagonal = std::max(1e-3f, glm::length(upper - lower));
    std::vector<RSMView> views;
    // Far: past the farthest bounds corner; near: a fixed fraction of it (DEPTH32F has the
    // precision for 1e-4).
    auto zFarFrom = [&](const glm::vec3& position) {
        float farthest = 0.0f;
        for (int c = 0; c < 8; ++c) {
            const glm::vec3 corner((c & 1) ? upper.x : lower.x, (c & 2) ? upper.y : lower.y,
                                   (c & 4) ? upper.z : lower.z);
            farthest = std::max(farthest, glm::length(corner - position));
        }
        return 1.01f * std::max(farthest, diagonal * 1e-3f);
    };
    // The six cube faces around `source`; with `hemisphere`, only those reaching in front of its
    // axis (a face whose four corner directions all lie behind would hold no flux). With
    // RSMCubeFaces::LightBudget the light's faces share size^2 texels.
    auto addCubeFaces = [&](RSMView view, bool hemisphere) {
        const glm::vec3 position(view.source.positionProfile);
        const float zFar = zFarFrom(position);
        const std::size_t first = views.size();
        for (int face = 0; face < shared::kLightViewCubeFaceCount; ++face) {
            if (hemisphere) {
                // The face's corner directions are axis +/- u +/- v (u, v the other two unit axes):
                // n . corner peaks at n . axis + |n . u| + |n . v|.
                const glm::vec3 axis = shared::lightViewCubeFaceDirection(face);
                const int k = axis.x != 0.0f ? 0 : axis.y != 0.0f ? 1 : 2;
                const glm::vec3 n(view.source.axisCosOuter);
                if (n[k] * axis[k] + std::abs(n[(k + 1) % 3]) + std::abs(n[(k + 2) % 3]) <= 0.0f) continue;
            }
            view.face = face;
            view.viewFromWorld = shared::lightViewCubeFaceViewFromWorld(position, face);
            view.clipFromView = shared::lightViewCubeFaceClipFromView(1e-4f * zFar, zFar);
            views.push_back(view);
        }
        const double count = static_cast<double>(views.size() - first);
        const int faceSize = faces == RSMCubeFaces::LightBudget && count > 0.0
                                 ? std::max(1, static_cast<int>(std::floor(size / std::sqrt(count))))
                                 : size;
        for (std::size_t v = first; v < views.size(); ++v) views[v].size = faceSize;
    };
    for (std::size_t i = 0; i < lights.points.size(); ++i) {
        const shared::PointEmitter& e = lights.points[i];
        const int profile = static_cast<int>(e.positionProfile.w + 0.5f);
        if (profile != shared::kProfileSpot && profile != shared::kProfileIsotropic) continue;
        RSMView view;
        view.emitter = static_cast<int>(i);
        view.source = e;
        if (profile == shared::kProfileIsotropic) {
            view.kind = shared::kRSMLightPoint;
            addCubeFaces(view, false);
            continue;
        }
        const glm::vec3 position(e.positionProfile);
        const float zFar = zFarFrom(position);
        const glm::vec3 axis = glm::normalize(glm::vec3(e.axisCosOuter));
        const float halfAngle = std::min(std::acos(std::clamp(e.axisCosOuter.w, -1.0f, 1.0f)), kRSMMaxSpotHalfAngle);
        view.kind = shared::kRSMLightSpot;
        view.size = size;
        view.viewFromWorld = shared::lightViewSpotViewFromWorld(position, axis);
        view.clipFromView = shared::lightViewSpotClipFromView(halfAngle, 1e-4f * zFar, zFar);
        views.push_back(view);
    }
    const std::vector<shared::PointEmitter> groups = groupCosineEmitters(lights, areaSources);
    for (std::size_t g = 0; g < groups.size(); ++g) {
        RSMView view;
        view.kind = shared::kRSMLightArea;
        view.emitter = static_cast<int>(g);
        view.source = groups[g];
        addCubeFaces(view, true);
    }
    for (std::size_t i = 0; i < lights.directionals.size(); ++i) {
        // lightViewDirectionalFit's sphere, kept in its two factors for the texel area.
        const glm::vec3 center = 0.5f * (lower + upper);
        const float radius = 0.5f * diagonal * 1.01f;
        RSMView view;
        view.kind = shared::kRSMLightDirectional;
        view.size = size;
        view.emitter = static_cast<int>(i);
        view.viewFromWorld =
            shared::lightViewDirectionalViewFromWorld(glm::vec3(lights.directionals[i].direction), center, radius);
        view.clipFromView = shared::lightViewDirectionalClipFromView(radius);
        views.push_back(view);
    }
    for (RSMView& view : views) {
        view.clipFromWorld = view.clipFromView * view.viewFromWorld;
        view.texelFactor = texelFactor(view.clipFromView, view.size);
    }
    return views;
}

void RSMPass::render(const GpuScene& scene, const DirectLightSet& lights, const RSMParams& params,
                     gl::PassTimer* timer, RSMCubeFaces faces)
{
    require(isPowerOfTwo(params.size), "rsm.size must be a power of two, not " + std::to_string(params.size));
    require(faces == RSMCubeFaces::FaceEach || mMips == RSMMips::None,
            "RSM cube faces within one light's budget need an RSM without mips");
    if (params.areaSources == 0 && !mWarnedArea) {
        for (const shared::PointEmitter& e : lights.points)
            if (static_cast<int>(e.positionProfile.w + 0.5f) == shared::kProfileCosine) {
                std::fprintf(stderr, "vplgi: warning: rsm.areaSources = 0: the emissive triangles give no indirect "
                                     "light in the RSM techniques\n");
                mWarnedArea = true;
                break;
            }
    }
    mViews = makeViews(scene.scene().worldBounds(), lights, params.areaSources, params.size, faces);
    if (mViews.empty()) return;
    // The techniques lay the layers side by side in one texture (the importance maps), so size x
    // layers must fit GL_MAX_TEXTURE_SIZE: the largest power of two that does.
    int fit = 1;
    while (2 * fit <= gl::queryLimits().maxTextureSize / layerCount()) fit *= 2;
    mSize = gl::clampToLimit(params.size, fit, "rsm.size",
                             "GL_MAX_TEXTURE_SIZE / RSM layers (" + std::to_string(layerCount()) +
                                 " layers side by side in the importance maps)");
    if (mSize != params.size) mViews = makeViews(scene.scene().worldBounds(), lights, params.areaSources, mSize, faces);
    std::vector<shared::RSMLayerLight> layerLights;
    for (const RSMView& view : mViews) {
        const glm::vec3 where = view.kind == shared::kRSMLightDirectional
                                    ? glm::vec3(lights.directionals[static_cast<std::size_t>(view.emitter)].direction)
                                    : glm::vec3(view.source.positionProfile);
        layerLights.push_back({glm::vec4(where, static_cast<float>(view.kind))});
    }
    gl::uploadVector(mLayerLights, "rsm layer lights", layerLights);
    glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, "rsm");
    mTarget.resize(mSize, mSize, layerCount());
    mLevels = mMips == RSMMips::All ? mipLevelCount(mSize) : 1;
    mTarget.bindForDrawing();
    mTarget.clear(glm::vec4(0.0f), 1.0f);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    for (int layer = 0; layer < layerCount(); ++layer) {
        const RSMView& view = mViews[static_cast<std::size_t>(layer)];
        mProgram.set("uLayer", layer);
        mProgram.set("uClipFromWorld", view.clipFromWorld);
        mProgram.set("uLightKind", view.kind);
        mProgram.set("uTexelFactor", view.texelFactor);
        glViewport(0, 0, view.size, view.size); // the layer's square (RSMCubeFaces)
        if (view.kind != shared::kRSMLightDirectional) {
            const shared::PointEmitter& e = view.source;
            const glm::vec3 axis = view.kind == shared::kRSMLightSpot ? glm::normalize(glm::vec3(e.axisCosOuter))
                                                                      : shared::lightViewCubeFaceDirection(view.face);
            mProgram.set("uLightPosition", glm::vec4(glm::vec3(e.positionProfile), 1.0f));
            mProgram.set("uLightDirection", glm::vec4(axis, 0.0f));
            const glm::vec3 emitterAxis(e.axisCosOuter); // zero for a point light (isotropic)
            mProgram.set("uEmitterAxis", glm::vec4(glm::length(emitterAxis) > 0.0f ? glm::normalize(emitterAxis)
                                                                                  : glm::vec3(0.0f),
                                                   0.0f));
            mProgram.set("uLightPower", glm::vec4(glm::vec3(e.intensity), 0.0f));
            mProgram.set("uLightCone", glm::vec4(e.axisCosOuter.w, e.cosInner.x, 0.0f, 0.0f));
        } else {
            const shared::DirectionalEmitter& d = lights.directionals[static_cast<std::size_t>(view.emitter)];
            mProgram.set("uLightPosition", glm::vec4(0.0f));
            mProgram.set("uLightDirection", glm::vec4(glm::normalize(glm::vec3(d.direction)), 0.0f));
            mProgram.set("uEmitterAxis", glm::vec4(0.0f));
            mProgram.set("uLightPower", glm::vec4(glm::vec3(d.irradiance), 0.0f));
            mProgram.set("uLightCone", glm::vec4(0.0f));
        }
        scene.draw(mProgram, GpuScene::Bind::GeometryAndMaterial);
    }
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    if (mMips == RSMMips::All) downsample(timer);
    glPopDebugGroup();
}

void RSMPass::downsample(gl::PassTimer* timer)
{
    downsampleRSMLayout(mDownsample, mTarget, timer);
}

DebugView rsmFluxDebugView(const std::string& name, const RSMPass* rsm)
{
    const bool haveRSM = rsm && rsm->layerCount() > 0;
    DebugView view{name, "the RSMs' incident flux, every layer (renderer.displayLayer picks one)",
                   haveRSM ? &rsm->target().color(shared::kRSMFlux) : nullptr, shared::kDebugViewColor};
    view.layerCount = 0;
    return view;
}

} // namespace vplgi
