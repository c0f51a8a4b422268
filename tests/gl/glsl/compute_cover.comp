#version 450 core
// ComputePass test probe: every invocation inside uSize counts itself at its texel, so a dispatch
// that rounds down leaves zeros and one that runs a texel twice leaves a 2.
#ifndef GROUP_X
#define GROUP_X 8
#endif
layout(local_size_x = GROUP_X, local_size_y = 8) in;
layout(std430, binding = 0) buffer Counts { uint counts[]; };

uniform ivec2 uSize;

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(p, uSize))) return;
    atomicAdd(counts[p.y * uSize.x + p.x], 1u);
}
