#include "shadow_pass.h"

#include <algorithm>

#include "../api/limits.h"
#include "core/util/params.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/light_view.h"

namespace vplgi {

void ShadowParams::visitParams(ParamVisitor& v)
{
    v.field("shadow.cubeSize", cubeSize, 8, 4096, "cube shadow face resolution for point emitters [texels]");
    v.field("shadow.mapSize", mapSize, 16, 16384, "directional shadow map resolution [texels]");
    v.field("shadow.normalOffset", normalOffset, 0.0f, 16.0f, "receiver offset along the normal [shadow texels]");
    v.field("shadow.depthBias", depthBias, 0.0f, 10.0f, "constant distance bias [m]");
    v.field("shadow.pcfRadius", pcfRadius, 0, 4, "directional PCF kernel radius [texels]");
    v.field("shadow.updateMovedOnly", updateMovedOnly, "re-render only the cube maps of emitters that moved");
}

namespace {

SceneProgram loadPoint(const gl::ShaderLoader& shaders)
{
    return SceneProgram(shaders, "shadow point",
                        {{GL_VERTEX_SHADER, "passes/shadow.vert"}, {GL_FRAGMENT_SHADER, "passes/shadow_point.frag"}});
}

SceneProgram loadDirectional(const gl::ShaderLoader& shaders)
{
    return SceneProgram(shaders, "shadow directional",
                        {{GL_VERTEX_SHADER, "passes/shadow.vert"}, {GL_FRAGMENT_SHADER, "passes/shadow_directional.frag"}});
}

} // namespace

ShadowPass::ShadowPass(const gl::ShaderLoader& shaders)
    : mPointProgram(loadPoint(shaders)), mDirectionalProgram(loadDirectional(shaders))
{
    gl::SamplerDesc desc;
    desc.minFilter = GL_NEAREST;
    desc.magFilter = GL_NEAREST;
    mSampler = gl::Sampler("shadow sampler", desc);
    mNoPoint = gl::Texture::placeholder("no point shadows", GL_TEXTURE_CUBE_MAP_ARRAY, GL_DEPTH_COMPONENT32F);
    mNoDirectional = gl::Texture::placeholder("no directional shadows", GL_TEXTURE_2D_ARRAY, GL_DEPTH_COMPONENT32F);
    gl::RenderTargetDesc cubes;
    cubes.depthFormat = GL_DEPTH_COMPONENT32F;
    cubes.textureTarget = GL_TEXTURE_CUBE_MAP_ARRAY;
    mCubes = gl::RenderTarget("point shadows", cubes);
    gl::RenderTargetDesc directional;
    directional.depthFormat = GL_DEPTH_COMPONENT32F;
    directional.textureTarget = GL_TEXTURE_2D_ARRAY;
    mDirectional = gl::RenderTarget("directional shadows", directional);
}

void ShadowPass::reloadShaders(const gl::ShaderLoader& shaders)
{
    mPointProgram = loadPoint(shaders);
    mDirectionalProgram = loadDirectional(shaders);
}

void ShadowPass::render(const GpuScene& scene, DirectLightSet& lights, const ShadowParams& params)
{
    const AABB bounds = scene.scene().worldBounds();
    const float diagonal = bounds.empty() ? 1.0f : std::max(1e-3f, glm::length(bounds.extent()));
    mFar = 1.01f * diagonal;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    renderCubes(scene, lights, params, 1e-4f * diagonal);
    renderDirectional(scene, lights, params);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
}

void ShadowPass::renderCubes(const GpuScene& scene, DirectLightSet& lights, const ShadowParams& params, float near)
{
    // The cube faces are layers of one array texture: the emitters beyond its layer limit / 6 are
    // unshadowed (with one warning).
    const int cubeCount = gl::clampToLimit(static_cast<int>(lights.points.size()),
                                           gl::queryLimits().maxArrayTextureLayers / 6, "shadowed point emitters",
                                           "GL_MAX_ARRAY_TEXTURE_LAYERS / 6 cube faces");

    // Point emitters: cube faces, layer = emitter * 6 + face.
    std::vector<glm::mat4> cubeMatrices;
    for (int i = 0; i < static_cast<int>(lights.points.size()); ++i) {
        shared::PointEmitter& e = lights.points[i];
        e.intensity.w = i < cubeCount ? static_cast<float>(i) : -1.0f;
        if (i >= cubeCount) continue;
        const glm::vec3 p(e.positionProfile);
        for (int face = 0; face < shared::kLightViewCubeFaceCount; ++face)
            cubeMatrices.push_back(shared::lightViewCubeFaceClipFromWorld(p, face, near, mFar));
    }
    gl::uploadVector(mEmitters, "shadow emitters", lights.points);
    if (cubeCount == 0) return;
    gl::uploadVector(mCubeMatrices, "shadow cube matrices", cubeMatrices);
    const bool reallocated = mCubes.resize(params.cubeSize, params.cubeSize, cubeCount * 6);
    // Only cubes whose emitter moved are re-rendered, in runs of consecutive emitters.
    std::vector<bool> dirty(static_cast<std::size_t>(cubeCount), true);
    if (!reallocated && params.updateMovedOnly && mRenderedPositions.size() == lights.points.size())
        for (int i = 0; i < cubeCount; ++i)
            dirty[i] = mRenderedPositions[i] != glm::vec3(lights.points[i].positionProfile);
    mRenderedPositions.clear();
    for (const shared::PointEmitter& e : lights.points) mRenderedPositions.push_back(glm::vec3(e.positionProfile));
    mLastRenderedCubes = 0;
    mCubes.bindForDrawing();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kBindingShadowMatrices, mCubeMatrices.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kBindingPointEmitters, mEmitters.id());
    mPointProgram.set("uFarDistance", mFar);
    const float one = 1.0f;
    for (int first = 0; first < cubeCount;) {
        if (!dirty[first]) {
            ++first;
            continue;
        }
        int last = first;
        while (last < cubeCount && dirty[last]) ++last;
        const int layers = (last - first) * 6;
        glClearTexSubImage(mCubes.depth().id(), 0, 0, 0, first * 6, params.cubeSize, params.cubeSize, layers,
                           GL_DEPTH_COMPONENT, GL_FLOAT, &one);
        mPointProgram.set("uFirstLayer", first * 6);
        scene.draw(mPointProgram, GpuScene::Bind::Geometry, layers);
        mLastRenderedCubes += last - first;
        first = last;
    }
}

void ShadowPass::renderDirectional(const GpuScene& scene, DirectLightSet& lights, const ShadowParams& params)
{
    // Orthographic maps around the scene's bounding sphere (an empty scene has nothing to shadow:
    // any finite box will do).
    const AABB bounds = scene.scene().worldBounds();
    std::vector<glm::mat4> directionalMatrices;
    const glm::vec3 lower = bounds.empty() ? glm::vec3(0.0f) : bounds.lower;
    const glm::vec3 upper = bounds.empty() ? glm::vec3(0.0f) : bounds.upper;
    for (std::size_t i = 0; i < lights.directionals.size(); ++i) {
        shared::DirectionalEmitter& d = lights.directionals[i];
        directionalMatrices.push_back(shared::lightViewDirectionalFit(glm::vec3(d.direction), lower, upper));
        d.direction.w = static_cast<float>(i);
    }
    gl::uploadVector(mDirectionalMatrices, "shadow directional matrices", directionalMatrices);
    if (lights.directionals.empty()) return;
    const int count = static_cast<int>(lights.directionals.size());
    mDirectional.resize(params.mapSize, params.mapSize, count);
    mDirectional.bindForDrawing();
    mDirectional.clear();
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kBindingShadowMatrices, mDirectionalMatrices.id());
    mDirectionalProgram.set("uFirstLayer", 0);
    scene.draw(mDirectionalProgram, GpuScene::Bind::Geometry, count);
}

std::vector<DebugView> ShadowPass::debugViews() const
{
    DebugView point{kShadowPointView, "point-emitter shadow cubes: distance / far, layer = emitter * 6 + face",
                    mCubes ? &mCubes.depth() : nullptr, shared::kDebugViewScalar};
    point.layerCount = 0;
    DebugView directional{kShadowDirectionalView, "directional shadow maps: depth, layer = directional emitter",
                          mDirectional ? &mDirectional.depth() : nullptr, shared::kDebugViewScalar};
    directional.layerCount = 0;
    return {point, directional};
}

void ShadowPass::bindForReading() const
{
    // Units of an absent kind get a placeholder of the right type, never texture 0 (gl::Texture::placeholder).
    glBindTextureUnit(shared::kUnitPointShadows, mCubes ? mCubes.depth().id() : mNoPoint.id());
    glBindTextureUnit(shared::kUnitDirectionalShadows, mDirectional ? mDirectional.depth().id() : mNoDirectional.id());
    glBindSampler(shared::kUnitPointShadows, mSampler.id());
    glBindSampler(shared::kUnitDirectionalShadows, mSampler.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kBindingShadowMatrices, mDirectionalMatrices.id());
}

} // namespace vplgi
