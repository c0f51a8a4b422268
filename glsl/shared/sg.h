// Spherical Gaussians (SG), anisotropic SGs (ASG) and the radiance of one virtual SG light (VSGL),
// defined once for the GPU (GLSL) and the CPU (C++: tests/cpu/test_sg.cpp checks every formula
// against quadrature, tests/gl/test_sg_gpu.cpp checks that GLSL and C++ agree).
//
// Tokuyoshi, "Virtual Spherical Gaussian Lights for Real-Time Glossy Indirect Illumination", 2015
// (papers/002), sections 2, 3.1-3.3; the formulas are those of MATH.md 4 and 5, tagged below.
//
// Overview
// --------
//  SGLobe, sgEvaluate, sgIntegral       a G(w; xi, eta) = a exp(eta (w.xi - 1))        MATH 4.1, 4.2
//  sgProduct, sgInnerProduct            product (an SG again) and its integral          MATH 4.3, 4.4
//  ASGLobe, asgEvaluate                 c max(w.z, 0) exp(-l (w.x)^2 - m (w.y)^2)        MATH 4.9
//  asgSGProductIntegral                 int ASG x SG (large-sharpness closed form)       MATH 4.9
//  cone*                                the visibility cone of a VSL as 2 G(w; w_i, 4pi/Omega)   MATH 4.5
//  ggxNDFSharpness                      GGX NDF D(h) ~= 1/(pi a^2) G(h; n, eta_ndf(a))  MATH 4.6 (docs/vsgl.md)
//  ggxWarpedSGLobe / ggxReflectionLobe  the NDF SG warped to the reflection lobe (SG)    MATH 4.7
//  ggxWarpedASGLobe                     the same as an ASG (Xu et al. 2013)              MATH 4.7
//  toksvigEncode / toksvigDecode        lobes as mip-mappable vectors                    MATH 4.8
//  vsglMipLevel                         filtered importance sampling's level             MATH 5.2
//  vsglRadiance                         eq. (2) + (3) with K = 2, and section 3.3        MATH 4.10, 5.1, 5.4
//  vplRadiance                          eq. (1) with exact BRDFs at both ends            MATH 1.1
//
// Details
// -------
//  Numerics (everything runs as float32 GLSL). SG integrals use 2 pi (1 - e^{-2 eta}) / eta and a
//  series below eta = 0.05, never sinh (MATH 4.4: it overflows). The amplitude of a product,
//  e^{|v| - eta_1 - eta_2}, is computed as e^{-eta_1 eta_2 |xi_1 - xi_2|^2 / (|v| + eta_1 + eta_2)},
//  which is the same number without the cancellation of |v| - eta_1 - eta_2 when one sharpness is
//  huge (the cone SG of a small VSL). The cone enters normalised: 2 G_V = 2 S(eta_V) Gn_V with
//  S = sgIntegral and Gn_V = G_V / S(eta_V), and
//      2 S(eta_V) / (pi r^2) = Omega/(pi r^2) (1 - e^{-2 eta_V}) = 2 (1 - e^{-2 eta_V}) / (s (s + d))
//  with s = sqrt(d^2 + r^2) (MATH 4.5's cancellation-free forms). As r -> 0, Gn_V tends to a delta
//  at w_i and 2/(s(s+d)) to 1/d^2, so every term stays finite and the sum tends to the SG lobes
//  evaluated at w_i over d^2 (eq. 1 with the fitted lobes). eta_V is capped at kConeMaxSharpness
//  (r/d ~ 2e-6), beyond which nothing visible changes.
//
//  The lobes of eq. (3), K = 2 at both ends (VSGL 3.1):
//    shading point  f(x_s, w_s, w) ~= rho_s/pi + F(F0_s, n.v) ASG(w)    ASG: GGX NDF SG warped (Xu)
//    light          Phi f(x_i, -w, w'_i) cos ~= Phi rho_d/pi cos+(-w.n_i) + Phi F(F0_i, n_i.xi) s' Gn(w; -xi, eta)
//  with s' = s (n_i.xi) (the light's exit cosine at its lobe's axis, folded in by ggxReflectionLobe).
//  The light's lobe leaves the light along xi; as a function of w (from x_s towards the light) its
//  axis is -xi (MATH 4.10 "Axis sign"). With T_jl the integrals of the products with Gn_V:
//    T_00 = 1,  T_01 = int Gn_l Gn_V (sgInnerProduct),  T_10 = int ASG Gn_V (asgSGProductIntegral),
//    T_11 = int ASG (Gn_l Gn_V) (sgProduct, then asgSGProductIntegral)          MATH 4.10
//    L = cos+(w_i.n_s) 2 (1 - e^{-2 eta_V}) / (s (s + d)) sum_jl c'_j c_l T_jl,  c_0 with cos+(-w_i.n_i)
//  A diffuse light on a diffuse receiver is therefore exactly
//    rho_s/pi Phi rho_d/pi cos cos Omega/(pi r^2) (1 - e^{-8 pi/Omega})   (MATH 4.10 "both diffuse").
//
//  Consistent bias reduction (VSGL 3.3, MATH 5.4). eta_rho is the largest sharpness of the
//  product of the lobes, in SG units; the reading used here (MATH 5.4's, not in the paper):
//    eta_rho = [receiver specular] 2 max(lambda, mu) + [light specular] eta_l
//  (an ASG of bandwidths lambda, mu is an SG of sharpness 2 lambda, 2 mu along its axes, MATH 4.9;
//  sharpnesses add where aligned lobes multiply; a term counts only where its coefficient is not
//  zero, so two diffuse ends give eta_rho = 0 and always cancel when biasAlpha > 0). If
//  eta_rho < biasAlpha 4pi/Omega, the integral is replaced by rho_i(w_i) Omega/(pi r^2) with the
//  exact glTF BRDFs at both ends (the light's lit from the primary light's direction, toPrimary)
//  and both cosines at w_i: eq. (1) over the cone's solid angle.
//
//  Degenerate inputs give finite results: an invalid light (normalValid.w = 0), zero normals, zero
//  flux and r = 0 give 0 or the limits above; d = 0 with r > 0 takes w_i = n_s (the direction to a
//  light at the shading point is undefined; a light on the same plane, n_i = n_s, then gives 0);
//  d = 0 and r = 0 gives 0.
#ifndef VPLGI_SHARED_SG_H
#define VPLGI_SHARED_SG_H
#include "brdf.h"
#include "compat.h"
#include "vpl.h"

VPLGI_SHARED_BEGIN

// --- Spherical Gaussians (MATH 4.1-4.4) ----------------------------------------------------------

// a G(w; axis, sharpness) = a exp(sharpness (w.axis - 1)); axis unit, sharpness >= 0.
struct SGLobe {
    vec3 axis;
    float sharpness;
    float amplitude;
};

VPLGI_FUNC float sgEvaluate(SGLobe g, vec3 w)
{
    return g.amplitude * exp(g.sharpness * (dot(w, g.axis) - 1.0f)); // MATH 4.1
}

// int_{S^2} G(w; xi, eta) dw = 2 pi (1 - e^{-2 eta}) / eta (MATH 4.2), 4 pi at eta = 0. Below
// eta = 0.05 the series of (1 - e^{-x})/x, x = 2 eta, replaces the subtraction (truncation 1.4e-8;
// the subtraction's float error is 6e-8 / (2 eta), 6e-7 at the switch).
VPLGI_FUNC float sgIntegral(float sharpness)
{
    if (sharpness < 0.05f) {
        float x = 2.0f * sharpness;
        return 4.0f * kPi * (1.0f - x * (0.5f - x * (1.0f / 6.0f - x * (1.0f / 24.0f - x * (1.0f / 120.0f)))));
    }
    return 2.0f * kPi * (1.0f - exp(-2.0f * sharpness)) / sharpness;
}

// The SG of unit integral (von Mises-Fisher density, MATH 4.1).
VPLGI_FUNC SGLobe sgNormalised(vec3 axis, float sharpness)
{
    SGLobe g;
    g.axis = axis;
    g.sharpness = sharpness;
    g.amplitude = 1.0f / sgIntegral(sharpness);
    return g;
}

// G_a G_b = G(w; v/|v|, |v|) a_a a_b e^{|v| - eta_a - eta_b}, v = eta_a xi_a + eta_b xi_b (MATH 4.3).
// |v| - eta_a - eta_b = (|v|^2 - (eta_a + eta_b)^2) / (|v| + eta_a + eta_b)
//                     = -eta_a eta_b |xi_a - xi_b|^2 / (|v| + eta_a + eta_b)     (unit axes)
// keeps every digit when one sharpness dwarfs the other. Opposite axes of equal sharpness give a
// constant (sharpness 0); its axis is then a's.
VPLGI_FUNC SGLobe sgProduct(SGLobe a, SGLobe b)
{
    vec3 v = a.sharpness * a.axis + b.sharpness * b.axis;
    float sharpness = length(v);
    vec3 axisDifference = a.axis - b.axis;
    float denominator = sharpness + a.sharpness + b.sharpness;
    float logScale =
        denominator > 0.0f ? -a.sharpness * b.sharpness * dot(axisDifference, axisDifference) / denominator : 0.0f;
    SGLobe g;
    g.axis = sharpness > 0.0f ? v / sharpness : a.axis;
    g.sharpness = sharpness;
    g.amplitude = a.amplitude * b.amplitude * exp(logScale);
    return g;
}

// int G_a G_b dw = a_a a_b 2 pi (e^{d - eta_a - eta_b} - e^{-d - eta_a - eta_b}) / d, d = |v| (MATH 4.4),
// written as the product's amplitude times sgIntegral(d): no sinh, no overflow.
VPLGI_FUNC float sgInnerProduct(SGLobe a, SGLobe b)
{
    SGLobe p = sgProduct(a, b);
    return p.amplitude * sgIntegral(p.sharpness);
}

// --- Anisotropic SGs (MATH 4.9) -------------------------------------------------------------------

// c max(w.z, 0) exp(-sharpnessX (w.x)^2 - sharpnessY (w.y)^2), {x, y, z} orthonormal; the
// bandwidths are in ASG units (an SG of sharpness eta is near its axis the ASG of eta/2, eta/2).
struct ASGLobe {
    vec3 x;
    vec3 y;
    vec3 z;
    float sharpnessX;
    float sharpnessY;
    float amplitude;
};

VPLGI_FUNC float asgEvaluate(ASGLobe g, vec3 w)
{
    float u = dot(w, g.x);
    float v = dot(w, g.y);
    return g.amplitude * max(dot(w, g.z), 0.0f) * exp(-g.sharpnessX * u * u - g.sharpnessY * v * v);
}

// int ASG(w) G(w) dw for an SG a G(w; p, nu) (Xu et al. 2013 section 4.3, MATH 4.9): with nu' = nu/2,
//   c a pi / sqrt((lambda + nu')(mu + nu')) max(p.z, 0) exp(-lambda' (p.x)^2 - mu' (p.y)^2),
//   lambda' = lambda nu' / (lambda + nu'),  mu' = mu nu' / (mu + nu').
// It is a large-sharpness form: for (lambda + nu')(mu + nu') below 1 it exceeds the exact value,
// whose limit at zero sharpness is pi (the integral of the clamped cosine), so the factor
// pi / sqrt(...) is capped at pi there (finite for every input; the lobes of vsglRadiance are far
// sharper wherever they matter: the cone alone has nu >= 2).
VPLGI_FUNC float asgSGProductIntegral(ASGLobe a, SGLobe g)
{
    float halfSharpness = 0.5f * g.sharpness;
    float sumX = a.sharpnessX + halfSharpness;
    float sumY = a.sharpnessY + halfSharpness;
    float reducedX = sumX > 0.0f ? a.sharpnessX * halfSharpness / sumX : 0.0f;
    float reducedY = sumY > 0.0f ? a.sharpnessY * halfSharpness / sumY : 0.0f;
    float u = dot(g.axis, a.x);
    float v = dot(g.axis, a.y);
    return a.amplitude * g.amplitude * kPi * inversesqrt(max(sumX * sumY, 1.0f)) * max(dot(g.axis, a.z), 0.0f) *
           exp(-reducedX * u * u - reducedY * v * v);
}

// --- The visibility cone of a VSL (VSGL 3.1, MATH 4.5) --------------------------------------------
// A disk of radius r facing x_s at distance d subtends a cone of half-angle theta, cos theta = d/s,
// s = sqrt(d^2 + r^2), and solid angle Omega = 2 pi (1 - cos theta) = 2 pi r^2 / (s (s + d)).

VPLGI_CONST float kConeMaxSharpness = 1.0e12f;

// Omega / (pi r^2) = 2 / (s (s + d)); 1/d^2 at r = 0. d = r = 0 is the caller's to avoid.
VPLGI_FUNC float coneSolidAngleOverArea(float lightDistance, float radius2)
{
    float s = sqrt(lightDistance * lightDistance + radius2);
    return 2.0f / (s * (s + lightDistance));
}

VPLGI_FUNC float coneSolidAngle(float lightDistance, float radius2)
{
    return kPi * radius2 * coneSolidAngleOverArea(lightDistance, radius2);
}

// eta_V = 4 pi / Omega = 2 s (s + d) / r^2 (>= 2), capped at kConeMaxSharpness (also for r = 0).
VPLGI_FUNC float coneSharpness(float lightDistance, float radius2)
{
    float s = sqrt(lightDistance * lightDistance + radius2);
    float numerator = 2.0f * s * (s + lightDistance);
    return radius2 * kConeMaxSharpness > numerator ? numerator / radius2 : kConeMaxSharpness;
}

// --- GGX as SGs (MATH 4.6, 4.7) -------------------------------------------------------------------

// The sharpness of the SG fit of the GGX NDF, D(h) ~= 1/(pi alpha^2) G(h; n, eta). Chosen by
// measured error between the two mappings in use (MATH 4.6): 2/alpha^2 - 2 (exact at alpha = 1,
// where GGX is the constant 1/pi) against 2/alpha^2; docs/vsgl.md has the table and the test that
// prints it (tests/cpu/test_sg.cpp, "GGX to SG fit").
VPLGI_FUNC float ggxNDFSharpness(float alpha)
{
    return max(2.0f / (alpha * alpha) - 2.0f, 0.0f);
}

// The cosine below which the warp's 1/cos factors are held (grazing incidence): keeps the
// sharpness finite; the fit is poor there anyway (the SG warp's L2 shape error is 76% at 80 deg,
// eta_d = 200: ../shared/MATH.md section 4.7, "Accuracy"; docs/vsgl.md's table stops at 60 deg).
VPLGI_CONST float kWarpMinCosine = 1.0e-3f;

// The specular lobe leaving a surface lit from `incoming` (or seen from it), as an SG:
// f_spec(w) ~= F(F0, cos) * integral * Gn(w; axis, sharpness) with Gn of unit integral.
struct SpecularLobe {
    vec3 axis;       // unit reflection of `incoming` about n
    float sharpness; // eta_w
    float integral;  // s = V_smith(axis) a_d sgIntegral(eta_w), a_d = 1/(pi alpha^2)
};

// Wang et al. 2009 spherical warp of the NDF SG a_d G(h; n, eta_ndf) about n (MATH 4.7):
// axis = 2 (incoming.n) n - incoming, eta_w = eta_ndf / (4 |incoming.n|), the other BRDF factors at
// the axis (where h = n and n.l = n.v = incoming.n). A surface lit from below (incoming.n <= 0, or
// a zero normal) reflects nothing: integral 0.
VPLGI_FUNC SpecularLobe ggxWarpedSGLobe(vec3 n, vec3 incoming, float alpha, float ndfSharpness)
{
    float cosine = dot(n, incoming);
    SpecularLobe lobe;
    lobe.axis = incoming;
    lobe.sharpness = 0.0f;
    lobe.integral = 0.0f;
    if (!(cosine > 0.0f)) return lobe;
    lobe.axis = normalize(2.0f * cosine * n - incoming);
    lobe.sharpness = ndfSharpness / (4.0f * max(cosine, kWarpMinCosine));
    lobe.integral = visibilitySmithGGX(cosine, cosine, alpha) / (kPi * alpha * alpha) * sgIntegral(lobe.sharpness);
    return lobe;
}

// The light-side lobe of a surface of perceptual roughness `roughness` (glTF alpha = roughness^2,
// at least kMinAlpha, as in brdf.h) lit from `incoming`: what the RSM pass stores per texel. The
// light's exit cosine cos(n, w) is folded into the integral factor at the axis, where it is
// cos(n, incoming): s' = s (n . incoming), so that f_spec(w) cos(n, w) ~= F s' Gn(w; axis, eta).
// A footprint's mip mean of s' is then the mean of each texel's own cosine, which the cosine of
// the mean normal is not (VSGL section 3.1 leaves the cosine outside the lobes; issue "VSGL made
// exact", part 2: with it outside, a filtered glossy light took its spread normal's cosine).
VPLGI_FUNC SpecularLobe ggxReflectionLobe(vec3 n, vec3 incoming, float roughness)
{
    float alpha = max(roughness * roughness, kMinAlpha);
    SpecularLobe lobe = ggxWarpedSGLobe(n, incoming, alpha, ggxNDFSharpness(alpha));
    lobe.integral *= max(dot(n, incoming), 0.0f);
    return lobe;
}

// The warp as an ASG (Xu et al. 2013, MATH 4.7): z = the reflected view, x perpendicular to the
// plane of incidence (normalize(view x n)), y = z x x, bandwidths eta_ndf/(8 cos^2) along x and
// eta_ndf/8 along y (ASG units), amplitude V_smith(axis) a_d, so that f_spec(w) ~= F(F0, n.v) ASG(w).
// At normal view the plane of incidence is undefined and both bandwidths are equal: any tangent
// frame of z does. A view from below (or a zero normal) gives amplitude 0.
VPLGI_FUNC ASGLobe ggxWarpedASGLobe(vec3 n, vec3 view, float alpha, float ndfSharpness)
{
    float cosine = dot(n, view);
    ASGLobe lobe;
    mat3 frame = lightViewBasis(n);
    lobe.x = frame[0];
    lobe.y = frame[1];
    lobe.z = frame[2];
    lobe.sharpnessX = 0.0f;
    lobe.sharpnessY = 0.0f;
    lobe.amplitude = 0.0f;
    if (!(cosine > 0.0f)) return lobe;
    float c = max(cosine, kWarpMinCosine);
    vec3 z = normalize(2.0f * cosine * n - view);
    vec3 across = cross(view, n);
    float acrossLength = length(across);
    if (acrossLength > 1.0e-6f) {
        lobe.x = across / acrossLength;
        lobe.y = cross(z, lobe.x);
    } else {
        frame = lightViewBasis(z);
        lobe.x = frame[0];
        lobe.y = frame[1];
    }
    lobe.z = z;
    lobe.sharpnessX = ndfSharpness / (8.0f * c * c);
    lobe.sharpnessY = ndfSharpness / 8.0f;
    lobe.amplitude = visibilitySmithGGX(cosine, cosine, alpha) / (kPi * alpha * alpha);
    return lobe;
}

// --- Filtering lobes (MATH 4.8, VSGL 3.2) ---------------------------------------------------------

// Toksvig's linear encoding: r = eta / (1 + eta), stored as r xi so that mip-mapping averages it.
VPLGI_FUNC vec3 toksvigEncode(vec3 axis, float sharpness)
{
    float s = max(sharpness, 0.0f);
    return (s / (1.0f + s)) * axis;
}

// Inverse of toksvigEncode for an averaged vector: r = |v|, axis = v / r, eta = r / (1 - r) with r
// held below 1 - 1e-6 (eta <= ~1e6). A zero vector is the constant lobe (eta 0, axis +z).
VPLGI_FUNC void toksvigDecode(vec3 v, VPLGI_OUT(vec3) axis, VPLGI_OUT(float) sharpness)
{
    float r = length(v);
    axis = r > 0.0f ? v / r : vec3(0.0f, 0.0f, 1.0f);
    r = min(r, 1.0f - 1.0e-6f);
    sharpness = r / (1.0f - r);
}

// The RSM mip level of a VSGL drawn with per-texel probability `probability` (MATH 5.2):
// h = h_max - 1/2 log2((N/k) P_j W H) = 1/2 log2(k / (N P_j)) on a square 2^h_max RSM, clamped to
// [0, levels - 1]. N = count, k = smoothness. N P_j <= 0 gives the top level, k <= 0 level 0.
VPLGI_FUNC float vsglMipLevel(float count, float probability, float smoothness, int levels)
{
    float top = float(max(levels - 1, 0));
    if (!(smoothness > 0.0f)) return 0.0f;
    float expected = count * probability;
    if (!(expected > 0.0f)) return top;
    return clamp(0.5f * log2(smoothness / expected), 0.0f, top);
}

// --- One VSGL (VSGL eq. 1-3, section 3.3) ---------------------------------------------------------

struct VSGLight {         // std430, 7 x vec4 = 112 bytes
    vec4 positionRadius2; // xyz filtered position E[x] [m], w r_i^2 = 2 sigma^2 [m^2] (MATH 5.3), >= 0
    vec4 normalValid;     // xyz unit (renormalised) normal n_i, w 1 valid / 0 empty
    vec4 flux;            // rgb incident flux of the light Phi_i = Phi_bar_h / (N P_j) [W], w the RSM layer it came from
    vec4 diffuse;         // rgb diffuse reflectance rho_d (BRDF = rho_d/pi) times |n_mean| (VSGLs; 1 for VPLs), w perceptual roughness
    vec4 specular;        // rgb F0, w = s': the specular lobe's integral factor with the exit cosine (ggxReflectionLobe)
    vec4 lobe;            // xyz unit lobe axis xi (direction the reflected light leaves in), w SG sharpness eta
    vec4 geometric;       // xyz the geometric normal n_g of a VPL's surface (the RSM texel's triangle; VSGLs: n_i), w 0
};

struct VSGLShadingPoint {
    vec3 position;
    vec3 normal;
    vec3 view;    // unit, from the point towards the eye
    vec3 diffuse; // rho_d
    vec3 f0;
    float roughness; // perceptual
};

// What vsglRadiance needs of a shading point, computed once per pixel (vsglReceiver) and reused
// for every light (vsglRadianceReceiver): the ASG of its specular lobe and the lobe coefficients.
struct VSGLReceiver {
    VSGLShadingPoint point;
    ASGLobe lobe;      // f_spec(w) ~= specular * asgEvaluate(lobe, w)
    vec3 diffuse;      // c'_0 = rho_d / pi (0 when the view is below the horizon)
    vec3 specular;     // F(F0, n.v) (0 when the view is below the horizon or F0 = 0)
    float sharpnessSG; // 2 max(lambda, mu): the lobe's largest sharpness in SG units (MATH 5.4)
};

VPLGI_FUNC VSGLReceiver vsglReceiver(VSGLShadingPoint s)
{
    VSGLReceiver r;
    r.point = s;
    float alpha = max(s.roughness * s.roughness, kMinAlpha);
    r.lobe = ggxWarpedASGLobe(s.normal, s.view, alpha, ggxNDFSharpness(alpha));
    float cosine = dot(s.normal, s.view);
    bool visible = cosine > 0.0f;
    bool glossy = visible && s.f0.x + s.f0.y + s.f0.z > 0.0f; // brdf.h: F0 = 0 is exactly Lambertian
    r.diffuse = visible ? s.diffuse * kInvPi : vec3(0.0f);
    r.specular = glossy ? fresnelSchlick(s.f0, clamp(cosine, 0.0f, 1.0f)) : vec3(0.0f);
    r.sharpnessSG = glossy ? 2.0f * max(r.lobe.sharpnessX, r.lobe.sharpnessY) : 0.0f;
    return r;
}

// vsglRadiance with the shading point's part precomputed (the loop over N lights calls this).
VPLGI_FUNC vec3 vsglRadianceReceiver(VSGLReceiver r, VSGLight l, vec3 toPrimary, float biasAlpha,
                                     VPLGI_OUT(float) cancelled)
{
    cancelled = 0.0f;
    if (!(l.normalValid.w > 0.0f)) return vec3(0.0f);
    vec3 toLight = vec3(l.positionRadius2) - r.point.position;
    float lightDistance = length(toLight);
    float radius2 = max(l.positionRadius2.w, 0.0f);
    if (!(lightDistance > 0.0f) && !(radius2 > 0.0f)) return vec3(0.0f);
    vec3 w = lightDistance > 0.0f ? toLight / lightDistance : r.point.normal;
    vec3 lightNormal = vec3(l.normalValid);
    // q_jl's cosines, pulled out of the integral (eq. 3): the receiver's on every term, the light's
    // on its diffuse lobe (its specular lobe carries its own: ggxReflectionLobe). Nothing leaves a
    // light below its surface.
    float cosReceiver = max(dot(w, r.point.normal), 0.0f);
    float cosLight = max(-dot(w, lightNormal), 0.0f);
    if (!(cosReceiver > 0.0f) || !(cosLight > 0.0f)) return vec3(0.0f);

    // The light's lobes (MATH 4.10): c_0 = Phi rho_d / pi, c_1 Gn_1 = Phi F s' Gn(w; -xi, eta).
    vec3 lobeAxis = vec3(l.lobe);
    float lobeSharpness = max(l.lobe.w, 0.0f);
    vec3 lightDiffuse = vec3(l.flux) * vec3(l.diffuse) * kInvPi;
    // F0 = 0 is exactly Lambertian (brdf.h), although Schlick's F(0, cos) is not 0 at grazing angles.
    vec3 lightF0 = vec3(l.specular);
    vec3 lightSpecular =
        lightF0.x + lightF0.y + lightF0.z > 0.0f
            ? vec3(l.flux) * fresnelSchlick(lightF0, clamp(dot(lightNormal, lobeAxis), 0.0f, 1.0f)) * l.specular.w
            : vec3(0.0f);
    bool lightGlossy = lightSpecular.x + lightSpecular.y + lightSpecular.z > 0.0f;
    bool receiverGlossy = r.specular.x + r.specular.y + r.specular.z > 0.0f;
    SGLobe lightLobe = sgNormalised(-lobeAxis, lobeSharpness);
    float coneEta = coneSharpness(lightDistance, radius2);
    float omegaOverArea = coneSolidAngleOverArea(lightDistance, radius2);

    // Section 3.3: pull rho out of the integral when it is smooth next to the cone (MATH 5.4), with
    // the exact glTF BRDF at both ends (the paper's rho is the true BRDF; the light's is lit from
    // toPrimary, so that the cancelled light tends to eq. (1) as r -> 0 anywhere in its lobe, not
    // only at the SG fit's peak: issue "VSGL made exact", part 3).
    float sharpnessRho = (receiverGlossy ? r.sharpnessSG : 0.0f) + (lightGlossy ? lobeSharpness : 0.0f);
    if (biasAlpha > 0.0f && sharpnessRho < biasAlpha * coneEta) {
        cancelled = 1.0f;
        VSGLShadingPoint s = r.point;
        vec3 receiverBRDF = evaluateBRDFCoefficients(s.diffuse, s.f0, s.roughness, s.normal, s.view, w);
        // The diffuse lobe needs no direction (the RSM's flux already took the incidence); the GGX
        // lobe is 0 where toPrimary is below n_i, as eq. (1)'s.
        vec3 lightBRDF = vec3(l.diffuse) * kInvPi;
        if (lightGlossy) lightBRDF += evaluateBRDFCoefficients(vec3(0.0f), lightF0, l.diffuse.w, lightNormal, -w, toPrimary);
        return vec3(l.flux) * receiverBRDF * lightBRDF * (cosReceiver * cosLight * omegaOverArea);
    }

    // Eq. (3) with the normalised cone: sum_jl c'_j c_l T_jl, T_00 = 1 (see the file head).
    SGLobe cone = sgNormalised(w, coneEta);
    vec3 sum = r.diffuse * lightDiffuse * cosLight;
    if (lightGlossy) sum += r.diffuse * lightSpecular * sgInnerProduct(lightLobe, cone);
    if (receiverGlossy) {
        sum += r.specular * lightDiffuse * (cosLight * asgSGProductIntegral(r.lobe, cone));
        if (lightGlossy) sum += r.specular * lightSpecular * asgSGProductIntegral(r.lobe, sgProduct(lightLobe, cone));
    }
    // 2 S(eta_V) / (pi r^2) = Omega/(pi r^2) (1 - e^{-2 eta_V}); eta_V >= 2, so no cancellation.
    return sum * (cosReceiver * omegaOverArea * (1.0f - exp(-2.0f * coneEta)));
}

// Reflected radiance at s towards s.view from one VSGL, without visibility [W/(m^2 sr)]: eq. (2)
// with eq. (3), K = 2, and the bias reduction of section 3.3 when biasAlpha > 0 (cancelled = 1 when
// it applied). Finite for r^2 -> 0 (tends to eq. 1 with the fitted lobes) and d -> 0. toPrimary
// (unit, from the light towards the primary light) is read only by the bias reduction.
VPLGI_FUNC vec3 vsglRadiance(VSGLShadingPoint s, VSGLight l, vec3 toPrimary, float biasAlpha,
                             VPLGI_OUT(float) cancelled)
{
    return vsglRadianceReceiver(vsglReceiver(s), l, toPrimary, biasAlpha, cancelled);
}

// Eq. (1): the light as a point light with exact glTF BRDFs at both ends: at s its own, at the
// light diffuse = l.diffuse.rgb, F0 = l.specular.rgb, roughness = l.diffuse.w, shading normal n_i,
// seen towards s and lit from `toLight` (unit, from the light sample towards the primary light).
// clampGeometry > 0 caps cos cos / d^2 at clampGeometry (MATH 1.2 (a)).
// The cosines at the light's end as the one-bounce path tracer has them (not in the paper; issue
// "Every light type in the RSM techniques", part 2): the RSM texel's flux I dw is what crosses its
// triangle, so the irradiance of a point of it is Phi cos_s(in) / (cos_g(in) dA), n_g the geometric
// normal; the path tracer reaches the texel's area dA from s by a direction, which brings the
// geometric cosine of exit cos_g(out) / d^2. So L = Phi (cos_s(in) / cos_g(in)) f_x f_s cos_s(s)
// cos_g(out) / d^2, where an RSM without normal maps has n_s = n_g and the usual Phi f f cos cos / d^2.
VPLGI_FUNC vec3 vplRadiance(VSGLShadingPoint s, VSGLight l, vec3 toLight, float clampGeometry)
{
    if (!(l.normalValid.w > 0.0f)) return vec3(0.0f);
    vec3 lightNormal = vec3(l.normalValid);
    vec3 lightGeometric = vec3(l.geometric);
    float cosGeometricIn = dot(lightGeometric, toLight);
    if (!(cosGeometricIn > 1e-3f)) return vec3(0.0f);
    float incidence = max(dot(lightNormal, toLight), 0.0f) / cosGeometricIn;
    vec3 toVPL = vec3(l.positionRadius2) - s.position;
    float geometry = vplGeometryTerm(s.normal, lightGeometric, toVPL, clampGeometry);
    if (!(geometry > 0.0f) || !(incidence > 0.0f)) return vec3(0.0f);
    vec3 w = normalize(toVPL);
    vec3 receiverBRDF = evaluateBRDFCoefficients(s.diffuse, s.f0, s.roughness, s.normal, s.view, w);
    vec3 lightBRDF = evaluateBRDFCoefficients(vec3(l.diffuse), vec3(l.specular), l.diffuse.w, lightNormal, -w, toLight);
    return vec3(l.flux) * receiverBRDF * lightBRDF * (geometry * incidence);
}

VPLGI_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(vplgi::shared::VSGLight) == 112, "VSGLight must match std430 (7 x vec4)");
#endif

#endif // VPLGI_SHARED_SG_H
