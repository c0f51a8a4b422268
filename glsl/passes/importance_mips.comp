#version 450 core
// Box mips of an importance map (gl/passes/importance_sampler.h, buildMips): level l+1 texel (x, y)
// = ((I(2x, 2y) + I(2x+1, 2y)) + (I(2x, 2y+1) + I(2x+1, 2y+1))) / 4 of level l, in this fixed order,
// so that 4^l times a level-l texel is its cell's total importance up to float rounding, on every
// driver (glGenerateTextureMipmap's filter is the driver's choice, and a width of 6 x 2^n, the cube
// faces side by side, is not a power of two). VSGL's cell footprints read these cells' probabilities
// (passes/vsgl_generate.comp). Power-of-two layers side by side: no cell straddles two layers.
#include "shared/bindings.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = kImageImportance, r32f) uniform readonly image2D uFine;
layout(binding = kImageImportanceCoarser, r32f) uniform writeonly image2D uCoarse;

void main()
{
    ivec2 at = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(at, imageSize(uCoarse)))) return;
    ivec2 child = 2 * at;
    precise float top = imageLoad(uFine, child).r + imageLoad(uFine, child + ivec2(1, 0)).r;
    precise float bottom = imageLoad(uFine, child + ivec2(0, 1)).r + imageLoad(uFine, child + ivec2(1, 1)).r;
    precise float mean = (top + bottom) * 0.25;
    imageStore(uCoarse, at, vec4(mean, 0.0, 0.0, 0.0));
}
