// The cross-bilateral filter that removes the structured noise of 4x4 interleaved sampling
// (SMCIR section 4; the idea is Keller & Heidrich 2001). Shared by every VPL technique that shades
// with interleaved sampling (`smcir`, `ir`).
//
// Intro
// -----
// Interleaved shading gives pixel class c = (x mod 4) + 4 (y mod 4) only the VPL subset
// {i : i mod 16 = c}, scaled by 16/n. Each pixel's estimate is unbiased but the 16 classes differ,
// which shows as a 4x4 pattern. Averaging over a window that holds every class recombines the
// subsets; the weights keep the average on the surface the pixel sees. SMCIR says only that the
// weights "are determined by the dot product between the normals and the distance between the
// world-space locations of the pixel samples"; the formula is MATH.md section 7's convention:
//
//     I~(p) = sum_{q in W(p)} w(p,q) I(q) / sum_q w(p,q)
//     w(p,q) = [q is geometry] (cos+(n_p . n_q))^sigmaN
//              exp(-c_p c_q |d_t|^2 / (2 sigmaX^2 f_p f_q) - (d . g_p)^2 / (2 sigmaPlane^2 f_p^2))
//     d = x_q - x_p,  d_t = d - (d . g_p) g_p,  c_p = max(|g_p . v_p|, cosFloor)
//     f_p = footprint(p) = |x_p - eye| 2 tan(fovY/2) / height
//
// footprint(p) is the width of a pixel, in metres, on a surface facing the camera at p's distance,
// so the sigmas are in pixels and the filter behaves the same at every distance and resolution.
// g_p is p's geometric normal (the triangle's plane), v_p the direction to the eye, n the
// interpolated normal without the normal map (`normals=shading`: the normal-mapped one).
// The paper's convention (MATH.md 7), exp(-|x_p - x_q|^2 / (2 (sigmaX footprint(p))^2)), is
// sigmaPlane = sigmaX, cosFloor = 1, normals = shading, up to footprint(p)^2 -> f_p f_q in-plane.
// The split is ours (#23 part 3): on a wall seen at a grazing angle, neighbouring pixels are up to
// 1/|g.v| farther apart along the wall, so the paper's isotropic term smoothed such walls less than
// walls seen face on and left the 4x4 pattern there; c_p undoes that (at most 1/cosFloor = 5x). The
// distance off the plane gets its own, tighter sigma: a 10 cm curb seen at low resolution, where one
// pixel spans more than 10 cm, is cut by it (the paper's sigma 3 mixed both sides). On a flat surface
// d . g_p is 0 up to float rounding, so the tight sigma costs no smoothing there; on a curved,
// tessellated one it stops smoothing across facets at about the angle the normal term does.
// A normal map changes the shading normal from pixel to pixel; comparing those stopped smoothing on
// bumpy floors, so the normal term compares interpolated normals.
// Glossy surfaces (perceptual roughness below grazingMinRoughness, 0.5) keep c = 1: their reflected
// light changes with the view direction from pixel to pixel along a grazing surface, and smoothing
// over more of the surface blurred it (the glossy metal floor test, roughness 0.3: mean +2.9% and
// relative L1 0.21 with c_p there, -0.1% and 0.14 without; unfiltered -1.2% and 0.11).
// The in-plane term uses c_p c_q / (footprint(p) footprint(q)), symmetric in p and q: with p's
// alone, taps on the near side of p weighed more than those on the far side on a grazing floor.
//
// Overview
// --------
//  apply()  two fragment-shader passes: the guide (glsl/passes/bilateral_guide.frag) writes each
//           pixel's normal and in-plane scale c / footprint once; the filter
//           (glsl/passes/bilateral_filter.frag) reads the unfiltered input, the G-buffer position
//           and the guide with texelFetch and writes (or adds, FullscreenDraw::Blend::Add) the
//           filtered radiance into the output target.
//
// Details
// -------
//  Window. W(p) is the 4m x 4m block of pixels with offsets -2m .. 2m-1 on both axes, m =
//  windowTiles: any 4 consecutive pixels cover the 4 residues mod 4 once, so every class appears
//  in W(p) exactly m^2 times, and with all weights 1 the result is the mean of the classes, i.e.
//  the full estimator over all VPLs (MATH.md 7). The window is half a pixel off centre (an even
//  width cannot be centred); near the image border it is shifted inwards (not clipped), so it
//  still holds every class m^2 times as long as the image is at least 4m pixels wide and high.
//  Not separable. A cross-bilateral filter's weight depends on both p and q, so two 1D passes are
//  not the same filter (the second pass would weight the first pass's results, which already mixed
//  other surfaces). The pass evaluates the full 2D window: (4m)^2 taps per pixel.
//  Rejection. q with position.w = 0 (no geometry: background) gets weight 0; q on another surface
//  far behind or in front of p's plane (a wall, a depth discontinuity) gets
//  exp(-(d . g_p)^2 / (2 (sigmaPlane footprint)^2)), which is 0 in float beyond about 13 sigmas;
//  q facing away (n_p . n_q <= 0) gets 0 when sigmaN > 0.
//  With sigmaN = 0 the normal term is 1 (x^0 = 1), also for opposite normals. Pixels without geometry
//  keep their input value. p is always in its own window with weight 1, so the sum is never 0.
//  sigmaX (sigmaPlane) >= 1e19 or infinity turns the in-plane (off-plane) term off; both off: weight 1.
//  Footprint. The in-plane distance is measured in pixels along the surface (times c_p), the
//  off-plane one in pixels across the view ray; `cosFloor` = 1 and `sigmaPlane` = sigmaX give the
//  paper's isotropic distance (docs/smcir.md, "Filter on grazing walls", measures both).
//  Disabled (enabled = false): the output is the input, bit for bit (same pass, one tap).
//  Determinism: every pixel sums its taps in a fixed order; no atomics, no shared memory.
//
// References
// ----------
//  P. Hedman, T. Karras, J. Lehtinen: Sequential Monte Carlo Instant Radiosity, TVCG 2017, sec. 4.
//  A. Keller, W. Heidrich: Interleaved Sampling, EGWR 2001.
//  E. Eisemann, F. Durand: Flash Photography Enhancement via Intrinsic Relighting, SIGGRAPH 2004, and
//  G. Petschnigg et al.: Digital Photography with Flash and No-Flash Image Pairs, SIGGRAPH 2004
//  (the cross/joint bilateral filter: weights from a second image, here the G-buffer).
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "../api/render_target.h"
#include "../api/shader_loader.h"
#include "../api/timer.h"
#include "fullscreen_pass.h"
#include "gbuffer_pass.h"

namespace vplgi {

class ParamVisitor;
struct Camera;

struct BilateralFilterParams {
    bool enabled = true; // off: the output is the input
    int windowTiles = 2; // m: the window is 4m x 4m pixels (offsets -2m .. 2m-1), each 4x4 class m^2 times
    float sigmaN = 32.0f; // exponent of cos+(n_p . n_q) [-]; 0 ignores normals
    float sigmaX = 3.0f;  // in-plane distance sigma in pixel footprints at p [pixels]; >= 1e19 ignores it
    // Not in the paper (#23 part 3; the numbers in docs/smcir.md, "Filter on grazing walls"):
    float sigmaPlane = 0.25f; // sigma of the distance off p's geometric plane [pixel footprints]; >= 1e19 ignores it
    float cosFloor = 0.2f;   // in-plane distance times max(|g_p . v_p|, cosFloor); 1: not rescaled
    float grazingMinRoughness = 0.5f; // surfaces smoother than this (perceptual) keep c_p = 1
    enum { Interpolated = 0, Shading = 1 };
    int normals = Interpolated; // which normal the normal term compares
    // Keys prefix + "enabled", prefix + "windowTiles", ... (a technique forwards e.g. "smcir.filter.").
    void visitParams(ParamVisitor& visitor, const std::string& prefix = "filter.");
};

// Where the camera is, for the pixel footprint.
struct BilateralFilterView {
    glm::vec3 eye{0.0f};      // camera position [m]
    float tanHalfFovY = 1.0f; // tan(fovY / 2)
    static BilateralFilterView fromCamera(const Camera& camera);
};

class CrossBilateralFilter {
public:
    explicit CrossBilateralFilter(const gl::ShaderLoader& shaders);
    void reloadShaders(const gl::ShaderLoader& shaders);

    // Filters `input` (RGBA, the G-buffer's size; not a texture of `output`: reading what the draw
    // writes is a feedback loop) into colour 0 of `output` (the same size) with
    // the G-buffer's position and normal. Binds the G-buffer's units and kUnitBilateralInput.
    // `blend` Add adds the result to what `output` holds. Opens a `timer` scope when one is given.
    // Throws Error naming the pass when the sizes differ or the parameters are out of range.
    void apply(const GBuffer& gbuffer, const gl::Texture& input, const gl::RenderTarget& output,
               const BilateralFilterView& view, const BilateralFilterParams& params,
               FullscreenDraw::Blend blend = FullscreenDraw::Blend::None, gl::PassTimer* timer = nullptr) const;

private:
    FullscreenPass mGuidePass; // passes/bilateral_guide.frag: per-pixel normal and in-plane scale
    FullscreenPass mPass;
    mutable gl::RenderTarget mGuide; // RGBA32F, the G-buffer's size (resized by apply)
};

} // namespace vplgi
