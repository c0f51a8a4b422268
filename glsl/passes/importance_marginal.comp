#version 450 core
// Importance sampler, table 2 (gl/passes/importance_sampler.h, ../shared/MATH.md 9.7): the prefix
// sums R(u) of the column totals T(u) = C(u, H-1), as one serial recurrence in column order (the CPU
// twin's order; a zero column leaves R unchanged, bit for bit). One work-group: all invocations load
// a chunk of totals into shared memory, then invocation 0 adds them up in order, so the serial part
// runs from shared memory rather than waiting on one buffer load per step.
#include "shared/bindings.h"

#define CHUNK 256

layout(local_size_x = CHUNK) in;
layout(std430, binding = kBindingImportanceColumns) readonly buffer Columns { float columns[]; };
layout(std430, binding = kBindingImportanceMarginal) writeonly buffer Marginal { float marginal[]; };

uniform int uWidth;
uniform int uHeight;

shared float sChunk[CHUNK];

void main()
{
    uint local = gl_LocalInvocationID.x;
    int lastRow = (uHeight - 1) * uWidth;
    precise float sum = 0.0f; // meaningful in invocation 0 only
    for (int start = 0; start < uWidth; start += CHUNK) {
        int u = start + int(local);
        sChunk[local] = u < uWidth ? columns[lastRow + u] : 0.0f;
        barrier();
        if (local == 0u) {
            int end = min(CHUNK, uWidth - start);
            for (int k = 0; k < end; ++k) {
                sum = sum + sChunk[k];
                marginal[start + k] = sum;
            }
        }
        barrier(); // invocation 0 is done with the chunk before it is overwritten
    }
}
