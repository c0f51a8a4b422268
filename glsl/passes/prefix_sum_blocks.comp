#version 450 core
// Prefix sums, step 1 (gl/passes/prefix_sum_pass.h): the inclusive scan of each block of BLOCK_SIZE
// values, in place, by log2(BLOCK_SIZE) Hillis-Steele steps in shared memory (step k adds the value
// 2^k places back), and the block's total into blockSums. The order of the adds is fixed by the block
// size alone, never by scheduling, so the result is deterministic and the CPU twin
// (tests/gl/prefix_sum_twin.h) repeats it exactly. Values past uCount count as 0 (x + 0 = x).
#include "shared/bindings.h"

#ifndef BLOCK_SIZE
#define BLOCK_SIZE 256
#endif

layout(local_size_x = BLOCK_SIZE) in;
layout(std430, binding = kBindingScanValues) buffer Values { float values[]; };
layout(std430, binding = kBindingScanBlockSums) writeonly buffer BlockSums { float blockSums[]; };

uniform int uCount;

shared float sPartial[BLOCK_SIZE];

void main()
{
    uint i = gl_GlobalInvocationID.x;
    uint local = gl_LocalInvocationID.x;
    bool inside = i < uint(uCount);
    sPartial[local] = inside ? values[i] : 0.0f;
    barrier();
    for (uint offset = 1u; offset < uint(BLOCK_SIZE); offset *= 2u) {
        // `precise`: one IEEE add, no reassociation by the compiler.
        precise float sum = sPartial[local];
        if (local >= offset) sum = sPartial[local - offset] + sum;
        barrier(); // everyone has read step k-1 before anyone writes step k
        sPartial[local] = sum;
        barrier();
    }
    if (inside) values[i] = sPartial[local];
    if (local == uint(BLOCK_SIZE) - 1u) blockSums[gl_WorkGroupID.x] = sPartial[local];
}
