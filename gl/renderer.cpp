#include "renderer.h"

#include <algorithm>

#include "api/context.h"
#include "core/util/error.h"
#include "api/debug.h"
#include "core/util/params.h"

namespace vplgi {

namespace {

// renderer.display's views of the frame, in kDisplay* order.
const std::vector<std::string>& frameViewNames()
{
    static const std::vector<std::string> names = {"final", "direct", "indirect", "albedo", "normal", "depth"};
    return names;
}

} // namespace

std::vector<std::string> displayViewNames(const std::vector<DebugView>& techniqueViews)
{
    std::vector<std::string> names = frameViewNames();
    names.push_back(kShadowPointView);
    names.push_back(kShadowDirectionalView);
    for (const DebugView& view : techniqueViews) {
        require(std::find(names.begin(), names.end(), view.name) == names.end(),
                "debug view \"" + view.name + "\" is named twice");
        names.push_back(view.name);
    }
    return names;
}

void RendererParams::visitParams(ParamVisitor& v, const std::vector<std::string>& viewNames)
{
    v.field("renderer.exposure", exposure, 0.0f, 1e6f, "radiance scale before Reinhard tone mapping");
    v.choice("renderer.display", display, viewNames,
             "what the display image shows (PNG output, window): a view of the frame or a texture view "
             "(gl/debug_view.h); EXR output stays the final radiance");
    v.choice("renderer.antialias", antialias, {"fxaa", "none"},
             "antialiasing of the display image (PNG output, window; frame views, not texture views) after tone "
             "mapping: FXAA (Lottes 2009) or none; the radiance (EXR, every metric) never has it, and compare, "
             "bench and conform set none");
    v.field("renderer.displayLayer", displayLayer, -1, 1 << 20,
            "layer of a texture view (renderer.display) shown alone, from its first; -1: all its layers tiled");
    v.field("lights.emitterSamples", lights.emitterSamples, 1, 4096,
            "cosine point samples representing all emissive triangles");
    v.field("lights.seed", lights.seed, "seed of the emissive-triangle sample placement");
    shadow.visitParams(v);
}

Renderer::Renderer(const gl::ShaderLoader& shaders, const Scene& scene, const RendererParams& params,
                   std::unique_ptr<Technique> technique, ProgressSink progress)
    : mShaders(shaders), mScene(scene), mParams(params), mGpuScene(scene), mRays(scene), mTechnique(std::move(technique)),
      mShadows(shaders), mGBuffer(shaders), mDirect(shaders, "direct light", "passes/direct.frag"),
      mToneMap(shaders, "tone map", "passes/tonemap.frag"), mAntialias(shaders, "antialias", "passes/fxaa.frag"),
      mDirectTarget("direct light", gl::RenderTargetDesc::colors({GL_RGBA32F}, {"radiance"})),
      mIndirectTarget("indirect", gl::RenderTargetDesc::colors({GL_RGBA32F}, {"radiance"})),
      mOutput("output", gl::RenderTargetDesc::colors({GL_RGBA8, GL_RGBA32F}, {"display", "radiance"})),
      mInset("inset", gl::RenderTargetDesc::colors({GL_RGBA8, GL_RGBA32F}, {"display", "radiance"})),
      mAntialiased("antialiased", gl::RenderTargetDesc::colors({GL_RGBA8}, {"display"})),
      mAntialiasSampler("antialias sampler", gl::SamplerDesc{}),
      mNoDisplayView(gl::Texture::placeholder("no display view", GL_TEXTURE_2D_ARRAY, GL_RGBA8)),
      mFrameUniforms("frame uniforms", sizeof(shared::FrameUniforms)),
      mTimer(gl::PassTimer::defaultMode())
{
    mTechnique->setScene(SceneContext{mScene, mGpuScene, mShaders, mRays, std::move(progress)});
}

void Renderer::visitParams(ParamVisitor& visitor)
{
    mParams.visitParams(visitor, displayViewNames(mTechnique->debugViews()));
    mTechnique->visitParams(visitor);
}

std::set<std::string> Renderer::applySettings(const Settings& settings)
{
    ParamSetter setter(settings);
    visitParams(setter);
    setter.finish();
    const std::set<std::string>& changed = setter.changedKeys();
    for (const std::string& key : changed)
        if (key.rfind("shadow.", 0) == 0 || key.rfind("lights.", 0) == 0) mLightsChanged = true;
    mTechnique->applyParamChanges(changed);
    return changed;
}

void Renderer::reloadShaders()
{
    mShadows.reloadShaders(mShaders);
    mGBuffer.reloadShaders(mShaders);
    mDirect.reloadShaders(mShaders);
    mToneMap.reloadShaders(mShaders);
    mAntialias.reloadShaders(mShaders);
    mTechnique->reloadShaders(mShaders);
}

void Renderer::updateFrameUniforms(const Camera& camera, int width, int height)
{
    const float aspect = static_cast<float>(width) / static_cast<float>(height);
    mFrame.viewFromWorld = camera.viewFromWorld();
    mFrame.clipFromWorld = camera.clipFromView(aspect) * mFrame.viewFromWorld;
    mFrame.worldFromClip = glm::inverse(mFrame.clipFromWorld);
    mFrame.cameraPosition = glm::vec4(camera.position, 1.0f);
    mFrame.viewport = glm::vec4(width, height, 1.0f / width, 1.0f / height);
    mFrame.counts = glm::ivec4(static_cast<int>(mLights.points.size()), static_cast<int>(mLights.directionals.size()),
                               static_cast<int>(mFrameIndex), 0);
    mFrame.shadow = glm::vec4(mShadows.cubeFarDistance(), mParams.shadow.normalOffset, mParams.shadow.depthBias,
                              static_cast<float>(mParams.shadow.pcfRadius));
    mFrame.toneMap = glm::vec4(mParams.exposure, 0.0f, 0.0f, 0.0f);
    mFrameUniforms.upload(0, sizeof(mFrame), &mFrame);
    glBindBufferBase(GL_UNIFORM_BUFFER, shared::kBindingFrame, mFrameUniforms.id());
}

void Renderer::renderFrame(const Camera& camera, int width, int height, float time)
{
    require(width > 0 && height > 0, "render size must be positive");
    mTimer.beginFrame();
    const bool lightsChanged = mLightsChanged;
    if (mLightsChanged) {
        gl::PassTimer::Scope scope(mTimer, "shadow maps");
        mLights = buildDirectLights(mScene, mParams.lights);
        mShadows.render(mGpuScene, mLights, mParams.shadow);
        gl::uploadVector(mPointEmitters, "point emitters", mLights.points);
        gl::uploadVector(mDirectionalEmitters, "directional emitters", mLights.directionals);
        mLightsChanged = false;
    }
    updateFrameUniforms(camera, width, height);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kBindingPointEmitters, mPointEmitters.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kBindingDirectionalEmitters, mDirectionalEmitters.id());

    FrameContext frame{camera, width, height, time, mFrameIndex, lightsChanged, mLights, mTimer};
    frame.viewFromWorld = mFrame.viewFromWorld;
    frame.clipFromWorld = mFrame.clipFromWorld;
    frame.display = mParams.display;
    mTechnique->update(frame);
    {
        gl::PassTimer::Scope scope(mTimer, "gbuffer");
        mGBuffer.render(mGpuScene, width, height);
    }
    {
        gl::PassTimer::Scope scope(mTimer, "direct light");
        mGBuffer.gbuffer().bindForReading();
        mShadows.bindForReading();
        mDirectTarget.resize(width, height);
        mDirect.render(mDirectTarget);
    }
    mIndirectTarget.resize(width, height);
    mIndirectTarget.clear();
    {
        gl::PassTimer::Scope scope(mTimer, std::string(mTechnique->name()));
        mTechnique->render(frame, mGBuffer.gbuffer(), IndirectTarget{mIndirectTarget});
    }
    {
        gl::PassTimer::Scope scope(mTimer, "tone map");
        glBindTextureUnit(shared::kUnitDirect, mDirectTarget.color(0).id());
        glBindTextureUnit(shared::kUnitIndirect, mIndirectTarget.color(0).id());
        glBindSampler(shared::kUnitDirect, 0);
        glBindSampler(shared::kUnitIndirect, 0);
        mGBuffer.gbuffer().bindForReading(); // the albedo, normal and depth views
        bindDisplayView();
        mOutput.resize(width, height);
        mToneMap.render(mOutput);
    }
    // The frame views (final, direct, indirect, albedo, normal, depth), not the texture views, which
    // show their texels as they are.
    static const std::vector<std::string> frameViews = frameViewNames();
    if (mParams.antialias == "fxaa" &&
        std::find(frameViews.begin(), frameViews.end(), mParams.display) != frameViews.end()) {
        gl::PassTimer::Scope scope(mTimer, "antialias");
        glBindTextureUnit(shared::kUnitAntialiasInput, mOutput.color(0).id());
        glBindSampler(shared::kUnitAntialiasInput, mAntialiasSampler.id());
        mAntialiased.resize(width, height);
        mAntialias.render(mAntialiased);
        glCopyImageSubData(mAntialiased.color(0).id(), GL_TEXTURE_2D, 0, 0, 0, 0, mOutput.color(0).id(), GL_TEXTURE_2D,
                           0, 0, 0, 0, width, height, 1);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    mTimer.endFrame();
    ++mFrameIndex;
    gl::checkDebugMessages();
}

const gl::Texture& Renderer::renderInset(const std::string& view)
{
    require(mOutput.width() > 0, "renderInset: no frame rendered yet");
    const std::vector<std::string> names = displayViewNames(mTechnique->debugViews());
    require(std::find(names.begin(), names.end(), view) != names.end(), "no display view \"" + view + "\"");
    // The frame's inputs are still there (direct, indirect, G-buffer, frame uniforms); only the
    // tone-map pass's view changes, so the inset costs one full-screen pass.
    const std::string shown = mParams.display;
    mParams.display = view;
    glBindTextureUnit(shared::kUnitDirect, mDirectTarget.color(0).id());
    glBindTextureUnit(shared::kUnitIndirect, mIndirectTarget.color(0).id());
    glBindSampler(shared::kUnitDirect, 0);
    glBindSampler(shared::kUnitIndirect, 0);
    mGBuffer.gbuffer().bindForReading();
    try {
        bindDisplayView();
    } catch (...) {
        mParams.display = shown;
        throw;
    }
    mParams.display = shown;
    mInset.resize(mOutput.width(), mOutput.height());
    mToneMap.render(mInset);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return mInset.color(0);
}

std::vector<DebugView> Renderer::debugViews() const
{
    std::vector<DebugView> views = mShadows.debugViews();
    for (DebugView& view : mTechnique->debugViews())
        views.push_back(std::move(view));
    return views;
}

void Renderer::bindDisplayView()
{
    const GLuint program = mToneMap.program().id();
    mDisplayView.reset();
    const std::vector<std::string>& frameViews = frameViewNames();
    const auto frameView = std::find(frameViews.begin(), frameViews.end(), mParams.display);
    if (frameView != frameViews.end()) {
        glProgramUniform1i(program, shared::kLocationDisplayView, static_cast<int>(frameView - frameViews.begin()));
        glBindTextureUnit(shared::kUnitDisplayView, mNoDisplayView.id());
        return;
    }
    const std::vector<DebugView> views = debugViews();
    const auto view =
        std::find_if(views.begin(), views.end(), [&](const DebugView& v) { return v.name == mParams.display; });
    require(view != views.end(), "renderer.display: no view \"" + mParams.display + "\"");
    int layersShown = 0; // 0: nothing to show (black)
    glm::ivec4 rect(0);
    if (view->texture && *view->texture) {
        const gl::TextureDesc& desc = view->texture->desc();
        require(desc.target != GL_TEXTURE_3D, "debug view " + view->name + ": 3D textures cannot be shown");
        const int total = desc.target == GL_TEXTURE_CUBE_MAP ? 6 : desc.layers;
        require(view->layer >= 0 && view->layer < total && view->level >= 0 && view->level < desc.levels,
                "debug view " + view->name + ": layer or level outside its texture");
        int first = view->layer;
        int count = view->layerCount > 0 ? std::min(view->layerCount, total - first) : total - first;
        if (mParams.displayLayer >= 0) {
            require(mParams.displayLayer < count, "renderer.displayLayer = " + std::to_string(mParams.displayLayer) +
                                                      ": view " + view->name + " has " + std::to_string(count) +
                                                      " layers (0.." + std::to_string(count - 1) + ")");
            first += mParams.displayLayer;
            count = 1;
        }
        // One texture type for every source (2D, arrays, cubes, cube arrays): a 2D-array view.
        mDisplayView = gl::Texture::makeView("display view " + view->name, *view->texture, GL_TEXTURE_2D_ARRAY,
                                             view->level, first, count);
        rect = view->rect.z > 0 ? view->rect : glm::ivec4(0, 0, mDisplayView.width(), mDisplayView.height());
        require(rect.x >= 0 && rect.y >= 0 && rect.z > 0 && rect.w > 0 && rect.x + rect.z <= mDisplayView.width() &&
                    rect.y + rect.w <= mDisplayView.height(),
                "debug view " + view->name + ": rectangle outside its texture level");
        layersShown = count;
    }
    glProgramUniform1i(program, shared::kLocationDisplayView, shared::kDisplayTextureView);
    glProgramUniform4i(program, shared::kLocationDisplayViewInfo, view->kind, layersShown, 0, 0);
    glProgramUniform4i(program, shared::kLocationDisplayViewRect, rect.x, rect.y, rect.z, rect.w);
    glProgramUniform2f(program, shared::kLocationDisplayViewRange, view->range.x, view->range.y);
    glBindTextureUnit(shared::kUnitDisplayView, mDisplayView.id());
    glBindSampler(shared::kUnitDisplayView, 0);
}

ImageRGBA32F Renderer::readLinear(const gl::Texture& texture) const
{
    std::vector<float> pixels = gl::readTextureRGBA32F(texture);
    ImageRGBA32F image;
    image.width = texture.width();
    image.height = texture.height();
    image.pixels.resize(pixels.size());
    const std::size_t row = static_cast<std::size_t>(image.width) * 4;
    for (int y = 0; y < image.height; ++y) // GL rows are bottom to top
        std::copy_n(&pixels[static_cast<std::size_t>(image.height - 1 - y) * row], row, &image.pixels[y * row]);
    return image;
}

ImageRGBA32F Renderer::readRadiance() const
{
    return readLinear(mOutput.color(1));
}

ImageRGBA32F Renderer::readDirect() const
{
    return readLinear(mDirectTarget.color(0));
}

ImageRGBA8 Renderer::readDisplay() const
{
    const gl::Texture& texture = mOutput.color(0);
    ImageRGBA8 image;
    image.width = texture.width();
    image.height = texture.height();
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(image.width) * image.height * 4);
    glGetTextureImage(texture.id(), 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(pixels.size()), pixels.data());
    image.pixels.resize(pixels.size());
    const std::size_t row = static_cast<std::size_t>(image.width) * 4;
    for (int y = 0; y < image.height; ++y)
        std::copy_n(&pixels[static_cast<std::size_t>(image.height - 1 - y) * row], row, &image.pixels[y * row]);
    return image;
}

} // namespace vplgi
