#version 450 core
// LightSkin + BRSM eq. (10)'s view samples: the camera's G-buffer at N_VS Halton-distributed pixels
// (section 4, Fig. 2: 512), sample i at (phi_2(i) W, phi_3(i) H) for i = 1..N_VS (MATH.md 9.8;
// i = 0 would be the corner pixel). Pixels without a surface give invalid samples, which the
// importance pass skips.
#include "shared/bindings.h"
#include "shared/lightskin.h"
#include "shared/lightskin_gpu.h"

layout(local_size_x = 64) in;

layout(binding = kUnitGBufferPosition) uniform sampler2D uPosition;
layout(binding = kUnitGBufferNormal) uniform sampler2D uNormal;
layout(std430, binding = kBindingViewSamples) writeonly buffer Samples { ViewSample samples[]; };

uniform int uCount; // N_VS

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount) return;
    ivec2 size = textureSize(uPosition, 0);
    uint index = uint(i + 1);
    vec2 uv = vec2(halton(index, 2u), halton(index, 3u));
    ivec2 pixel = min(ivec2(uv * vec2(size)), size - 1);
    vec4 position = texelFetch(uPosition, pixel, 0);
    vec3 normal = texelFetch(uNormal, pixel, 0).xyz;
    samples[i].positionValid = vec4(position.xyz, position.w != 0.0 ? 1.0 : 0.0);
    samples[i].normal = vec4(position.w != 0.0 ? normalize(normal) : vec3(0.0), 0.0);
}
