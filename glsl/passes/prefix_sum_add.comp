#version 450 core
// Prefix sums, step 3 (gl/passes/prefix_sum_pass.h): adds to every value of block b > 0 the scanned
// total of the blocks before it (blockSums, already scanned inclusively by the recursion).
#include "shared/bindings.h"

#ifndef BLOCK_SIZE
#define BLOCK_SIZE 256
#endif

layout(local_size_x = BLOCK_SIZE) in;
layout(std430, binding = kBindingScanValues) buffer Values { float values[]; };
layout(std430, binding = kBindingScanBlockSums) readonly buffer BlockSums { float blockSums[]; };

uniform int uCount;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(uCount) || gl_WorkGroupID.x == 0u) return;
    precise float sum = blockSums[gl_WorkGroupID.x - 1u] + values[i];
    values[i] = sum;
}
