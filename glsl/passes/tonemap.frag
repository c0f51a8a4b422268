#version 450 core
// Display transform: the view chosen by renderer.display (kDisplay*; default: (direct + indirect) *
// exposure -> Reinhard on luminance) -> sRGB bytes. Writes the combined linear radiance too (for EXR
// output and metrics), whatever the view.
#include "../lib/frame.glsl"
#include "../shared/tonemap.h"

layout(binding = kUnitDirect) uniform sampler2D uDirect;
layout(binding = kUnitIndirect) uniform sampler2D uIndirect;
layout(binding = kUnitGBufferPosition) uniform sampler2D uPosition;
layout(binding = kUnitGBufferNormal) uniform sampler2D uNormal;
layout(binding = kUnitGBufferBaseColor) uniform sampler2D uBaseColor;
layout(location = kLocationDisplayView) uniform int uDisplay;

layout(location = 0) out vec4 outDisplay;  // RGBA8, sRGB-encoded by hand
layout(location = 1) out vec4 outRadiance; // RGBA32F linear

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec3 direct = texelFetch(uDirect, pixel, 0).rgb;
    vec3 indirect = texelFetch(uIndirect, pixel, 0).rgb;
    vec3 radiance = direct + indirect;
    vec3 shown; // linear in [0, 1], sRGB-encoded below
    bool encoded = false; // normal and depth views are display values already
    if (uDisplay == kDisplayDirect) shown = toneMapReinhard(direct, frame.toneMap.x);
    else if (uDisplay == kDisplayIndirect) shown = toneMapReinhard(indirect, frame.toneMap.x);
    else if (uDisplay == kDisplayAlbedo) shown = clamp(texelFetch(uBaseColor, pixel, 0).rgb, 0.0, 1.0);
    else if (uDisplay == kDisplayNormal || uDisplay == kDisplayDepth) {
        vec4 p = texelFetch(uPosition, pixel, 0);
        float d = length(p.xyz - frame.cameraPosition.xyz);
        shown = p.w <= 0.0 ? vec3(0.0) : uDisplay == kDisplayNormal ? texelFetch(uNormal, pixel, 0).xyz * 0.5 + 0.5
                                                                    : vec3(d / (1.0 + d));
        encoded = true;
    } else shown = toneMapReinhard(radiance, frame.toneMap.x);
    outDisplay = encoded ? vec4(shown, 1.0) : vec4(encodeSRGB(shown.r), encodeSRGB(shown.g), encodeSRGB(shown.b), 1.0);
    outRadiance = vec4(radiance, 1.0);
}
