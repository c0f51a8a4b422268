#version 450 core
// Direct light: every point emitter (point, spot, emissive-surface sample) with its cube shadow,
// every directional emitter with its shadow map, plus the surface's own emission. The same sums as
// core/scene/surface.cpp evaluateDirectLight, with shadow maps in place of Embree visibility.
#include "../lib/frame.glsl"
#include "../lib/shadows.glsl"
#include "../shared/brdf.h"

layout(binding = kUnitGBufferPosition) uniform sampler2D uPosition;
layout(binding = kUnitGBufferNormal) uniform sampler2D uNormal;
layout(binding = kUnitGBufferBaseColor) uniform sampler2D uBaseColor;
layout(binding = kUnitGBufferEmission) uniform sampler2D uEmission;

layout(std430, binding = kBindingPointEmitters) readonly buffer PointEmitters {
    PointEmitter pointEmitters[];
};
layout(std430, binding = kBindingDirectionalEmitters) readonly buffer DirectionalEmitters {
    DirectionalEmitter directionalEmitters[];
};

layout(location = 0) out vec4 outRadiance;

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 position = texelFetch(uPosition, pixel, 0);
    if (position.w == 0.0) {
        outRadiance = vec4(0.0);
        return;
    }
    vec4 normalRoughness = texelFetch(uNormal, pixel, 0);
    vec4 baseMetallic = texelFetch(uBaseColor, pixel, 0);
    vec4 emissionSpecular = texelFetch(uEmission, pixel, 0);
    vec3 p = position.xyz;
    vec3 n = normalize(normalRoughness.xyz);
    vec3 wo = normalize(frame.cameraPosition.xyz - p);
    SurfaceMaterial m = SurfaceMaterial(baseMetallic.rgb, baseMetallic.a, normalRoughness.w, emissionSpecular.a);

    vec3 radiance = emissionSpecular.rgb;
    for (int i = 0; i < frame.counts.x; ++i) {
        PointEmitter e = pointEmitters[i];
        vec3 toLight = e.positionProfile.xyz - p;
        float distance2 = dot(toLight, toLight);
        vec3 wi = toLight * inversesqrt(distance2);
        float cosine = dot(n, wi);
        if (cosine <= 0.0) continue;
        float profile = emitterProfile(e, -wi);
        if (profile <= 0.0) continue;
        float lit = e.intensity.w >= 0.0 ? pointShadow(int(e.intensity.w), e.positionProfile.xyz, p, n) : 1.0;
        if (lit == 0.0) continue;
        radiance += evaluateBRDF(m, n, wo, wi) * e.intensity.rgb * (profile * cosine * lit / distance2);
    }
    for (int i = 0; i < frame.counts.y; ++i) {
        DirectionalEmitter d = directionalEmitters[i];
        vec3 wi = -d.direction.xyz;
        float cosine = dot(n, wi);
        if (cosine <= 0.0) continue;
        float lit = d.direction.w >= 0.0 ? directionalShadow(int(d.direction.w), p, n) : 1.0;
        radiance += evaluateBRDF(m, n, wo, wi) * d.irradiance.rgb * (cosine * lit);
    }
    outRadiance = vec4(radiance, 1.0);
}
