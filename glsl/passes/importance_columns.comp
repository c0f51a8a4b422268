#version 450 core
// Importance sampler, table 1 (gl/passes/importance_sampler.h, ../shared/MATH.md 9.7): the column
// prefix sums C(u, v) = sum_{v' <= v} I(u, v'). One invocation per column runs the serial recurrence
// over the rows: the order the CPU twin (core/util/importance_table.cpp) uses, and a zero texel leaves the
// sum bit-identical (glsl/shared/importance.h says why that matters). Neighbouring invocations read
// and write neighbouring texels of one row, so the accesses of a work-group are contiguous.
#include "shared/bindings.h"

layout(local_size_x = 64) in;
layout(binding = kImageImportance, r32f) uniform readonly image2D uImportance;
layout(std430, binding = kBindingImportanceColumns) writeonly buffer Columns { float columns[]; };

void main()
{
    ivec2 size = imageSize(uImportance);
    int u = int(gl_GlobalInvocationID.x);
    if (u >= size.x) return;
    precise float sum = 0.0f;
    for (int v = 0; v < size.y; ++v) {
        sum = sum + imageLoad(uImportance, ivec2(u, v)).r;
        columns[v * size.x + u] = sum;
    }
}
