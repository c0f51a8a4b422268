#version 450 core
// Radiance estimation (VSGL Table 1's last row): every pixel sums all N lights (no interleaving in
// the paper), each as a VSGL (eq. 2-3 with section 3.3's cancellation; glsl/shared/sg.h) or, for the
// baseline vpl-brsm, as a VPL (eq. 1), times its visibility (imperfect shadow maps, or none).
// Outputs: the indirect radiance, and the fraction of lights whose SG approximation was cancelled
// (VSGL Fig. 6 bottom).
#include "../lib/frame.glsl"
#include "../lib/ism.glsl"
#include "../shared/rsm.h"
#include "../shared/sg.h"
#include "../shared/normals.h"

layout(binding = kUnitGBufferPosition) uniform sampler2D uPosition;
layout(binding = kUnitGBufferNormal) uniform sampler2D uNormal;
layout(binding = kUnitGBufferSurfaceNormals) uniform sampler2D uSurfaceNormals;
layout(binding = kUnitGBufferBaseColor) uniform sampler2D uBaseColor;
layout(binding = kUnitGBufferEmission) uniform sampler2D uEmission;

layout(std430, binding = kBindingVSGLights) readonly buffer Lights { VSGLight lights[]; };
layout(std430, binding = kBindingRSMLayers) readonly buffer Layers { RSMLayerLight layers[]; };

uniform int uCount;          // N
uniform int uPointLights;    // 1: eq. (1) (vpl-brsm), 0: VSGLs
uniform float uBiasAlpha;    // alpha of section 3.3 (0: never cancel)
uniform float uClampGeometry; // vpl-brsm: cap on cos cos / d^2 [1/m^2]; 0 = none
uniform int uVisibility;     // 0 none, 1 imperfect shadow maps

layout(location = 0) out vec4 outRadiance;
layout(location = 1) out vec4 outCancelled;


void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 position = texelFetch(uPosition, pixel, 0);
    outCancelled = vec4(0.0);
    if (position.w == 0.0) {
        outRadiance = vec4(0.0);
        return;
    }
    vec4 normalRoughness = texelFetch(uNormal, pixel, 0);
    vec4 baseMetallic = texelFetch(uBaseColor, pixel, 0);
    float specularFactor = texelFetch(uEmission, pixel, 0).a;
    VSGLShadingPoint s;
    s.position = position.xyz;
    s.normal = normalize(normalRoughness.xyz);
    s.view = normalize(frame.cameraPosition.xyz - position.xyz);
    s.diffuse = (1.0 - baseMetallic.a) * baseMetallic.rgb;
    s.f0 = mix(vec3(0.04 * specularFactor), baseMetallic.rgb, baseMetallic.a);
    s.roughness = normalRoughness.w;

    // n_g, the G-buffer's geometric normal: a light below the triangle's plane (n_g . w <= 0) adds
    // nothing (for an SG light: its centre), as the path tracer drops a direction below the geometric surface (issue "Every light
    // type in the RSM techniques", part 2; the shading normal alone let a normal map tilt light in).
    vec3 ng = octDecode(texelFetch(uSurfaceNormals, pixel, 0).xy);

    VSGLReceiver receiver = vsglReceiver(s);
    vec3 sum = vec3(0.0);
    float cancelled = 0.0;
    float valid = 0.0;
    for (int i = 0; i < uCount; ++i) {
        VSGLight l = lights[i];
        if (l.normalValid.w == 0.0) continue;
        valid += 1.0;
        if (dot(ng, l.positionRadius2.xyz - s.position) <= 0.0) continue;
        float v = uVisibility != 0 ? ismVisibility(i, l.positionRadius2.xyz, l.normalValid.xyz, s.position, s.normal, ng) : 1.0;
        if (v == 0.0) continue;
        vec3 toLight = rsmDirectionToLight(layers[int(l.flux.w)], l.positionRadius2.xyz);
        if (uPointLights != 0) {
            sum += v * vplRadiance(s, l, toLight, uClampGeometry);
        } else {
            float lightCancelled;
            sum += v * vsglRadianceReceiver(receiver, l, toLight, uBiasAlpha, lightCancelled);
            cancelled += lightCancelled;
        }
    }
    outRadiance = vec4(sum, 1.0);
    outCancelled = vec4(valid > 0.0 ? cancelled / valid : 0.0, 0.0, 0.0, 1.0);
}
