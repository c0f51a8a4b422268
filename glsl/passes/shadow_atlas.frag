#version 450 core
// The shadow atlas keeps the rasterized depth (DEPTH32F, the same window-space depth as the view
// rendered alone); nothing to write, so the rasterizer can test and write depth early. The masked
// variant (lib/alpha_mask.glsl) discards what the alpha mask cuts.
#include "../shared/bindings.h"
#include "../lib/alpha_mask.glsl"

layout(location = 2) in vec2 vTexcoord;
layout(location = 3) in vec2 vTexcoord1;
layout(location = 4) in float vAlpha;

layout(binding = kUnitBaseColor) uniform sampler2D uBaseColorTexture;

void main()
{
    discardMasked(uBaseColorTexture, vTexcoord, vTexcoord1, vAlpha);
}
