#version 450 core
// Directional shadow maps keep the rasterized depth; nothing to write but the alpha mask's discard
// (only in the masked variant: lib/alpha_mask.glsl).
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
