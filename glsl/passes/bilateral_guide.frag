#version 450 core
// The cross-bilateral filter's per-pixel guide (gl/passes/bilateral_filter.h), made once per frame so
// that each of the filter's (4m)^2 taps reads one texel instead of decoding normals:
//   xyz  the normal the normal term compares: the interpolated normal without the normal map
//        (uNormalSource 0) or the shading normal (1);
//   w    the in-plane scale c / footprint [1/m]: c = max(|g . v|, uCosFloor) on surfaces at least
//        uGrazingMinRoughness rough (perceptual), c = 1 on smoother, glossier ones, whose reflection
//        changes with the view direction along a grazing surface; g the geometric normal, v the
//        direction to the eye, footprint = |x - eye| uFootprintScale.
// Pixels without geometry get 0 (the filter never reads them: position.w = 0 rejects them first).
#include "../shared/bindings.h"
#include "../shared/normals.h"

layout(binding = kUnitGBufferPosition) uniform sampler2D uPosition; // xyz world [m], w = 1 where hit
layout(binding = kUnitGBufferNormal) uniform sampler2D uNormal;     // xyz shading normal, w perceptual roughness
layout(binding = kUnitGBufferSurfaceNormals) uniform sampler2D uSurfaceNormals; // oct geometric (xy), interpolated (zw)

uniform int uNormalSource;          // 0: interpolated normal without the normal map, 1: shading normal
uniform float uCosFloor;            // c = max(|g . v|, uCosFloor); 1: in-plane distance not rescaled
uniform float uGrazingMinRoughness; // c = 1 on surfaces smoother than this
uniform vec3 uEye;                  // camera position [m]
uniform float uFootprintScale;      // 2 tan(fovY/2) / height

layout(location = 0) out vec4 outGuide;

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec4 position = texelFetch(uPosition, p, 0);
    if (position.w == 0.0) {
        outGuide = vec4(0.0);
        return;
    }
    vec4 shading = texelFetch(uNormal, p, 0);
    vec4 surface = texelFetch(uSurfaceNormals, p, 0);
    vec3 normal = uNormalSource == 1 ? shading.xyz : octDecode(surface.zw);
    vec3 toEye = uEye - position.xyz;
    float distanceToEye = length(toEye);
    // (The floor keeps a pixel at the eye finite; no real G-buffer has one.)
    float footprint = max(distanceToEye * uFootprintScale, 1e-15);
    float c = 1.0;
    if (shading.w >= uGrazingMinRoughness)
        c = max(abs(dot(octDecode(surface.xy), toEye)) / max(distanceToEye, 1e-30), uCosFloor);
    outGuide = vec4(normal, c / footprint);
}
