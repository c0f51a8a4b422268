#version 450 core
// Cross-bilateral filter over the 4x4-interleaved indirect radiance (gl/passes/bilateral_filter.h
// has the prose): a 4m x 4m window, offsets -2m .. 2m-1 (shifted inwards at the image border) so
// every interleaving class is in it m^2 times, weights
//   w(p,q) = [q is geometry] min(cos+(n_p . n_q), 1)^sigmaN
//            exp(-c_p c_q |d_t|^2 / (2 sigmaX^2 f_p f_q) - (d . g_p)^2 / (2 sigmaPlane^2 f_p^2)), f = footprint,
//   d = x_q - x_p, g_p the geometric normal, d_t = d - (d . g_p) g_p, c_p = max(|g_p . v_p|, cosFloor)
//   (1 on surfaces smoother than grazingMinRoughness).
// n and c / f per pixel come from the guide pass (passes/bilateral_guide.frag): n is the interpolated
// normal without the normal map (or the shading normal).
// Taps are summed in a fixed order (rows, then columns): deterministic.
#include "../shared/bindings.h"
#include "../shared/normals.h"

layout(binding = kUnitBilateralInput) uniform sampler2D uInput;
layout(binding = kUnitGBufferPosition) uniform sampler2D uPosition; // xyz world [m], w = 1 where hit
layout(binding = kUnitGBufferSurfaceNormals) uniform sampler2D uSurfaceNormals; // oct geometric (xy), interpolated (zw)
layout(binding = kUnitBilateralGuide) uniform sampler2D uGuide; // xyz the normal term's normal, w c / footprint [1/m]

uniform ivec2 uSize;            // input, G-buffer and output size [pixels]
uniform int uEnabled;           // 0: copy the input
uniform int uWindowTiles;       // m
uniform float uSigmaN;          // normal exponent; 0: no normal term
uniform float uInvTwoSigmaX2;   // 1 / (2 sigmaX^2) [1/pixels^2]; 0: no distance term
uniform float uInvTwoSigmaPlane2; // 1 / (2 sigmaPlane^2) [1/pixels^2]; 0: no plane-distance term
uniform vec3 uEye;              // camera position [m]
uniform float uFootprintScale;  // 2 tan(fovY/2) / height: footprint(p) = |x_p - eye| uFootprintScale

layout(location = 0) out vec4 outRadiance;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 centre = texelFetch(uInput, p, 0);
    vec4 positionP = texelFetch(uPosition, p, 0);
    if (uEnabled == 0 || positionP.w == 0.0) {
        outRadiance = centre;
        return;
    }
    vec4 guideP = texelFetch(uGuide, p, 0);
    vec3 toEye = uEye - positionP.xyz;
    float footprint = length(toEye) * uFootprintScale;
    // (The floor keeps a pixel at the eye finite; no real G-buffer has one.)
    float invFootprint2 = 1.0 / max(footprint * footprint, 1e-30);
    // Not in the paper (#23 part 3): distances split along p's geometric plane. The in-plane part is
    // scaled by c_p, so a wall seen at a grazing angle is smoothed over as many pixels as one seen
    // face on; the part off the plane (a step, a curb, another surface) has its own, tighter sigma.
    vec3 geometricP = octDecode(texelFetch(uSurfaceNormals, p, 0).xy);
    float kOffPlane = uInvTwoSigmaPlane2 * invFootprint2;

    int width = 4 * uWindowTiles;
    // Shift the window inwards at the border rather than clip it: 4m consecutive pixels hold every
    // residue mod 4 exactly m times.
    ivec2 start = max(min(p - 2 * uWindowTiles, uSize - width), ivec2(0));
    ivec2 end = min(start + width, uSize);

    vec4 sum = vec4(0.0);
    float weightSum = 0.0;
    for (int y = start.y; y < end.y; ++y) {
        for (int x = start.x; x < end.x; ++x) {
            ivec2 q = ivec2(x, y);
            vec4 positionQ = texelFetch(uPosition, q, 0);
            if (positionQ.w == 0.0) continue; // background: no surface to share light with
            vec4 guideQ = texelFetch(uGuide, q, 0);
            float w = 1.0;
            if (uSigmaN > 0.0) {
                // Half-float normals can give a dot product slightly above 1: clamp.
                float cosPQ = clamp(dot(guideP.xyz, guideQ.xyz), 0.0, 1.0);
                w = cosPQ > 0.0 ? pow(cosPQ, uSigmaN) : 0.0;
            }
            vec3 d = positionQ.xyz - positionP.xyz;
            float offPlane = dot(d, geometricP);
            // The geometric mean of p's and q's scales: symmetric in p and q (with p's alone, taps
            // on the near side of p on a grazing floor weighed more than those on the far side: the
            // glossy metal floor's mean came out +5.1%, +2.9% with both, before the glossy exception).
            float kInPlane = uInvTwoSigmaX2 * guideP.w * guideQ.w;
            float exponent = kInPlane * max(dot(d, d) - offPlane * offPlane, 0.0) + kOffPlane * offPlane * offPlane;
            if (exponent > 0.0) w *= exp(-exponent);
            // Numeric guard: a NaN or infinite tap (a defect upstream) would poison every pixel
            // whose window holds it (w * NaN, inf - inf); it gets weight 0 instead.
            vec4 value = texelFetch(uInput, q, 0);
            if (any(isnan(value)) || any(isinf(value))) continue;
            sum += w * value;
            weightSum += w;
        }
    }
    // p is in its own window with a weight near 1 (its normal with itself), so weightSum > 0 unless
    // p and every other tap were non-finite (then black).
    outRadiance = weightSum > 0.0 ? sum / weightSum : vec4(0.0);
}
