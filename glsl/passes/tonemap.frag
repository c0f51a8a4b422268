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
layout(binding = kUnitDisplayView) uniform sampler2DArray uView; // a texture view (kDisplayTextureView)
layout(location = kLocationDisplayView) uniform int uDisplay;
layout(location = kLocationDisplayViewInfo) uniform ivec4 uViewInfo;  // x kDebugView* kind, y layers (0: none)
layout(location = kLocationDisplayViewRect) uniform ivec4 uViewRect;  // texels shown: x, y, width, height
layout(location = kLocationDisplayViewRange) uniform vec2 uViewRange; // scalar: black, white; count: y max

layout(location = 0) out vec4 outDisplay;  // RGBA8, sRGB-encoded by hand
layout(location = 1) out vec4 outRadiance; // RGBA32F linear

// The texture view at output pixel `pixel` (GL rows, bottom up): uViewInfo.y layers in a grid of
// ceil(sqrt(n)) columns, layer 0 at the top left, each cell showing uViewRect scaled by nearest
// texel. Integer arithmetic, in half pixels so that the pixel centre is exact, so that the CPU twin
// (tests/image/test_display_views.cpp) matches texel for texel: with c cells across W pixels,
// centre 2i + 1 (half pixels) times c is in cell ((2i + 1) c) / (2W), at texel
// (((2i + 1) c) mod 2W) w / (2W) of a rectangle w texels wide.
vec3 textureViewValue(ivec2 pixel, out bool encoded)
{
    encoded = true;
    int layers = uViewInfo.y;
    if (layers <= 0) return vec3(0.0);
    int columns = int(ceil(sqrt(float(layers))));
    while (columns * columns < layers) ++columns; // guard the float square root
    while ((columns - 1) * (columns - 1) >= layers) --columns;
    int rows = (layers + columns - 1) / columns;
    ivec2 size2 = 2 * ivec2(frame.viewport.xy);
    int x = (2 * pixel.x + 1) * columns;
    int yFromTop = (2 * (int(frame.viewport.y) - 1 - pixel.y) + 1) * rows;
    int layer = (yFromTop / size2.y) * columns + x / size2.x;
    if (layer >= layers) return vec3(0.0);
    int texelX = ((x % size2.x) * uViewRect.z) / size2.x;
    int texelFromTop = ((yFromTop % size2.y) * uViewRect.w) / size2.y;
    ivec2 texel = uViewRect.xy + ivec2(texelX, uViewRect.w - 1 - texelFromTop);
    vec4 v = texelFetch(uView, ivec3(texel, layer), 0);
    int kind = uViewInfo.x;
    if (kind == kDebugViewScalar) return vec3(clamp((v.r - uViewRange.x) / (uViewRange.y - uViewRange.x), 0.0, 1.0));
    if (kind == kDebugViewNormal) return clamp(v.xyz * 0.5 + 0.5, 0.0, 1.0);
    if (kind == kDebugViewCount) return vec3(clamp(log2(1.0 + max(v.r, 0.0)) / log2(1.0 + uViewRange.y), 0.0, 1.0));
    encoded = false;
    return toneMapReinhard(v.rgb, frame.toneMap.x);
}

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
    } else if (uDisplay == kDisplayTextureView) shown = textureViewValue(pixel, encoded);
    else shown = toneMapReinhard(radiance, frame.toneMap.x);
    outDisplay = encoded ? vec4(shown, 1.0) : vec4(encodeSRGB(shown.r), encodeSRGB(shown.g), encodeSRGB(shown.b), 1.0);
    outRadiance = vec4(radiance, 1.0);
}
