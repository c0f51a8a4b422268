#include "bilateral_filter.h"

#include <cmath>
#include <limits>
#include <optional>

#include "core/scene/scene.h"
#include "core/util/error.h"
#include "core/util/params.h"
#include "glsl/shared/bindings.h"

namespace vplgi {

void BilateralFilterParams::visitParams(ParamVisitor& v, const std::string& prefix)
{
    v.field(prefix + "enabled", enabled, "cross-bilateral filter over the interleaved result (off: unfiltered)");
    v.field(prefix + "windowTiles", windowTiles, 1, 8,
            "window edge in 4x4 tiles: 4m x 4m pixels, offsets -2m..2m-1, every interleaving class m^2 times");
    v.field(prefix + "sigmaN", sigmaN, 0.0f, 4096.0f, "normal weight cos+(n_p.n_q)^sigmaN [-]; 0: normals ignored");
    v.field(prefix + "sigmaX", sigmaX, 0.01f, 1e30f,
            "in-plane distance sigma in pixel footprints at p [pixels]; >= 1e19: ignored");
    v.field(prefix + "sigmaPlane", sigmaPlane, 0.01f, 1e30f,
            "sigma of the distance off p's geometric plane, in pixel footprints at p (ours); >= 1e19: ignored");
    v.field(prefix + "cosFloor", cosFloor, 0.01f, 1.0f,
            "in-plane distance scaled by max(|n_geometric . view|, cosFloor) (ours: grazing walls); 1: not scaled");
    v.field(prefix + "grazingMinRoughness", grazingMinRoughness, 0.0f, 2.0f,
            "surfaces at least this rough (perceptual) get the grazing rescale (ours); smoother ones keep c = 1");
    v.choice(prefix + "normals", normals, {"interpolated", "shading"},
             "normal of the normal term: interpolated without the normal map (ours) | shading (normal-mapped)");
}

BilateralFilterView BilateralFilterView::fromCamera(const Camera& camera)
{
    return {camera.position, std::tan(0.5f * camera.fovY)};
}

CrossBilateralFilter::CrossBilateralFilter(const gl::ShaderLoader& shaders)
    : mGuidePass(shaders, "bilateral filter guide", "passes/bilateral_guide.frag"),
      mPass(shaders, "bilateral filter", "passes/bilateral_filter.frag"),
      mGuide("bilateral filter guide", gl::RenderTargetDesc::colors({GL_RGBA32F}))
{
}

void CrossBilateralFilter::reloadShaders(const gl::ShaderLoader& shaders)
{
    mGuidePass.reloadShaders(shaders);
    mPass.reloadShaders(shaders);
}

void CrossBilateralFilter::apply(const GBuffer& gbuffer, const gl::Texture& input, const gl::RenderTarget& output,
                                 const BilateralFilterView& view, const BilateralFilterParams& params,
                                 FullscreenDraw::Blend blend, gl::PassTimer* timer) const
{
    const int width = gbuffer.width();
    const int height = gbuffer.height();
    require(input.width() == width && input.height() == height && output.width() == width &&
                output.height() == height,
            "bilateral filter: input " + std::to_string(input.width()) + "x" + std::to_string(input.height()) +
                " and output " + output.name() + " " + std::to_string(output.width()) + "x" +
                std::to_string(output.height()) + " must have the G-buffer's size " + std::to_string(width) + "x" +
                std::to_string(height));
    require(params.windowTiles >= 1 && params.windowTiles <= 8, "bilateral filter: windowTiles must be in [1, 8]");
    require(params.sigmaN >= 0.0f, "bilateral filter: sigmaN must be >= 0");
    require(params.sigmaX > 0.0f, "bilateral filter: sigmaX must be > 0");
    require(params.sigmaPlane > 0.0f, "bilateral filter: sigmaPlane must be > 0");
    require(params.cosFloor > 0.0f && params.cosFloor <= 1.0f, "bilateral filter: cosFloor must be in (0, 1]");
    require(params.normals == BilateralFilterParams::Interpolated || params.normals == BilateralFilterParams::Shading,
            "bilateral filter: normals must be interpolated or shading");

    std::optional<gl::PassTimer::Scope> scope;
    if (timer) scope.emplace(*timer, "bilateral filter");

    // 1 / (2 sigmaX^2) in double; below the smallest normal float (sigmaX above about 6.5e18, or
    // infinity) it is set to exactly 0, which the shader reads as "no distance term" (a denormal
    // would be flushed or not depending on the driver).
    auto invTwoSigma2 = [](double sigma) {
        const double value = 1.0 / (2.0 * sigma * sigma);
        return value < std::numeric_limits<float>::min() ? 0.0f : static_cast<float>(value);
    };

    const float footprintScale = 2.0f * view.tanHalfFovY / static_cast<float>(height);
    gbuffer.bindForReading();
    if (params.enabled) {
        // Per-pixel normal and in-plane scale, once (the filter's taps read them (4m)^2 times).
        mGuide.resize(width, height);
        const gl::Program& guide = mGuidePass.program();
        guide.set("uNormalSource", params.normals);
        guide.set("uCosFloor", params.cosFloor);
        guide.set("uGrazingMinRoughness", params.grazingMinRoughness);
        guide.set("uEye", view.eye);
        guide.set("uFootprintScale", footprintScale);
        mGuidePass.render(mGuide);
    }

    const gl::Program& program = mPass.program();
    glProgramUniform2i(program.id(), program.uniformLocation("uSize"), width, height);
    program.set("uEnabled", params.enabled ? 1 : 0);
    program.set("uWindowTiles", params.windowTiles);
    program.set("uSigmaN", params.sigmaN);
    program.set("uInvTwoSigmaX2", invTwoSigma2(params.sigmaX));
    program.set("uInvTwoSigmaPlane2", invTwoSigma2(params.sigmaPlane));
    program.set("uEye", view.eye);
    program.set("uFootprintScale", footprintScale);

    glBindTextureUnit(shared::kUnitBilateralInput, input.id());
    glBindSampler(shared::kUnitBilateralInput, 0);
    if (params.enabled) { // (disabled, the filter copies its input and reads no guide)
        glBindTextureUnit(shared::kUnitBilateralGuide, mGuide.color(0).id());
        glBindSampler(shared::kUnitBilateralGuide, 0);
    }
    FullscreenDraw draw;
    draw.blend = blend;
    mPass.render(output, draw);
}

} // namespace vplgi
