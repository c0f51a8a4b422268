#version 450 core
// The debug view of LightSkin's selection: 1 at every RSM texel drawn this frame (the importance
// map's layout). Duplicate draws store the same value, so the order does not matter.
#include "shared/bindings.h"
#define VPLGI_IMPORTANCE_TYPES_ONLY
#include "shared/importance.h"

layout(local_size_x = 64) in;

layout(std430, binding = kBindingImportanceSamples) readonly buffer Draws { ImportanceSample draws[]; };
layout(r32f, binding = kImageSelectedVALs) writeonly uniform image2D uSelected;

uniform int uCount; // N_sVAL

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount || draws[i].x < 0) return;
    imageStore(uSelected, ivec2(draws[i].x, draws[i].y), vec4(1.0));
}
