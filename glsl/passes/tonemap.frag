#version 450 core
// Display transform: (direct + indirect) * exposure -> Reinhard on luminance -> sRGB bytes.
// Writes the combined linear radiance too (for EXR output and metrics).
#include "../lib/frame.glsl"
#include "../shared/tonemap.h"

layout(binding = kUnitDirect) uniform sampler2D uDirect;
layout(binding = kUnitIndirect) uniform sampler2D uIndirect;

layout(location = 0) out vec4 outDisplay;  // RGBA8, sRGB-encoded by hand
layout(location = 1) out vec4 outRadiance; // RGBA32F linear

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec3 radiance = texelFetch(uDirect, pixel, 0).rgb + texelFetch(uIndirect, pixel, 0).rgb;
    vec3 mapped = toneMapReinhard(radiance, frame.toneMap.x);
    outDisplay = vec4(encodeSRGB(mapped.r), encodeSRGB(mapped.g), encodeSRGB(mapped.b), 1.0);
    outRadiance = vec4(radiance, 1.0);
}
