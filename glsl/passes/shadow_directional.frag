#version 450 core
// Directional shadow maps keep the rasterized depth; nothing to write but the alpha mask's discard
// (only in the masked variant: lib/alpha_mask.glsl).
#include "../shared/bindings.h"
#include "../lib/alpha_mask.glsl"

layout(location = 2) in vec2 vTexcoord;

layout(binding = kUnitBaseColor) uniform sampler2D uBaseColorTexture;

void main()
{
    discardMasked(uBaseColorTexture, vTexcoord);
}
