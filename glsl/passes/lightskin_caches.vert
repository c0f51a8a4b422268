#version 450 core
// LightSkin's cache view: one point per cache (pulled from the cache SSBO by gl_VertexID), coloured
// by the radiance its diffuse proxy gives a white Lambertian surface at the cache:
// (1/pi) Phi_p V cos+ / (4 pi d^2).
#include "../lib/frame.glsl"
#include "../shared/brdf.h"
#include "../shared/lightskin_gpu.h"

layout(std430, binding = kBindingLightCaches) readonly buffer Caches { GpuLightCache caches[]; };
layout(std430, binding = kBindingProxyLights) readonly buffer Proxies { ProxyLight proxies[]; };

out vec3 vWorld;
flat out vec3 vColor;

void main()
{
    GpuLightCache c = caches[gl_VertexID];
    ProxyLight p = proxies[gl_VertexID];
    vec3 toProxy = p.diffusePositionRadius.xyz - c.positionArea.xyz;
    float d2 = max(dot(toProxy, toProxy), 1e-8);
    float cosine = max(dot(c.normalRoughness.xyz, toProxy * inversesqrt(d2)), 0.0);
    vColor = p.diffuseFlux.rgb * p.diffuseFlux.w * cosine / (4.0 * kPi * kPi * d2);
    vWorld = c.positionArea.xyz;
    gl_Position = frame.clipFromWorld * vec4(vWorld, 1.0);
    gl_PointSize = 3.0;
}
