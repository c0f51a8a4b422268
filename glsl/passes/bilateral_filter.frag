#version 450 core
// Cross-bilateral filter over the 4x4-interleaved indirect radiance (gl/passes/bilateral_filter.h
// has the prose): a 4m x 4m window, offsets -2m .. 2m-1 (shifted inwards at the image border) so
// every interleaving class is in it m^2 times, weights
//   w(p,q) = [q is geometry] min(cos+(n_p . n_q), 1)^sigmaN exp(-|x_p - x_q|^2 k_p),
//   k_p = 1 / (2 (sigmaX footprint(p))^2).
// Taps are summed in a fixed order (rows, then columns): deterministic.
#include "../shared/bindings.h"

layout(binding = kUnitBilateralInput) uniform sampler2D uInput;
layout(binding = kUnitGBufferPosition) uniform sampler2D uPosition; // xyz world [m], w = 1 where hit
layout(binding = kUnitGBufferNormal) uniform sampler2D uNormal;     // xyz shading normal

uniform ivec2 uSize;            // input, G-buffer and output size [pixels]
uniform int uEnabled;           // 0: copy the input
uniform int uWindowTiles;       // m
uniform float uSigmaN;          // normal exponent; 0: no normal term
uniform float uInvTwoSigmaX2;   // 1 / (2 sigmaX^2) [1/pixels^2]; 0: no distance term
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
    vec3 normalP = texelFetch(uNormal, p, 0).xyz;
    float footprint = length(positionP.xyz - uEye) * uFootprintScale;
    // (The floor keeps a pixel at the eye finite; no real G-buffer has one.)
    float kp = uInvTwoSigmaX2 > 0.0 ? uInvTwoSigmaX2 / max(footprint * footprint, 1e-30) : 0.0;

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
            float w = 1.0;
            if (uSigmaN > 0.0) {
                // Half-float normals can give a dot product slightly above 1: clamp.
                float c = clamp(dot(normalP, texelFetch(uNormal, q, 0).xyz), 0.0, 1.0);
                w = c > 0.0 ? pow(c, uSigmaN) : 0.0;
            }
            if (kp > 0.0) {
                vec3 d = positionQ.xyz - positionP.xyz;
                w *= exp(-dot(d, d) * kp);
            }
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
