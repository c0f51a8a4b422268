#version 450 core
// Metropolis-Hastings chains over an importance map (gl/passes/metropolis_chains.h; technique tcas,
// after Barak et al. 2013 as the SMCIR paper describes it, papers/000 lines 233-235 and 898-902).
// One invocation per chain. uMode 0 starts chain i at draw i of the importance sampler (the draws
// sit in the Samples buffer); uMode 1 runs uIterations steps from each chain's state and writes the
// chain's draw record (texel, probability I / total) into the Samples buffer for the VPL generation.
//
// One step (ours; the SMCIR paper gives only "Metropolis-Hastings", "16 iterations per frame"):
//   propose y: with probability uGlobalProbability a texel uniform over the whole map (the
//              original's quasi-random proposals, here hashed), otherwise x + an offset uniform in
//              [-r, r]^2 without (0, 0) (a texel outside the map has importance 0); both proposals are
//              symmetric, q(x -> y) = q(y -> x), so
//   accept with probability min(1, I(y) / I(x))       (Metropolis; I(x) = 0: always accepted)
// which keeps the distribution I / total stationary (each proposal kind is a kernel in detailed
// balance; a mixture of such kernels is too). tests/gl/test_metropolis_chains.cpp checks it with a
// chi-square test from a start far from the target.
#include "shared/bindings.h"
#define VPLGI_IMPORTANCE_TYPES_ONLY // the draw record and the hashed uniforms; no table search
#include "shared/importance.h"

layout(local_size_x = 64) in;
layout(binding = kImageImportance, r32f) uniform readonly image2D uImportance;
// The importance tables' marginal sums: its last entry is the map's total.
layout(std430, binding = kBindingImportanceMarginal) readonly buffer Marginal { float marginal[]; };

layout(std430, binding = kBindingImportanceSamples) buffer Samples { ImportanceSample samples[]; };
layout(std430, binding = kBindingChainStates) buffer States { uint states[]; };
layout(std430, binding = kBindingChainCounters) buffer Counters { uint moved; };

uniform int uMode;               // 0: start from the draws; 1: step
uniform int uCount;              // chains
uniform uint uSeed;              // this step's uniforms (the caller changes it every frame)
uniform int uIterations;         // Metropolis-Hastings iterations
uniform float uGlobalProbability; // probability of a proposal uniform over the map
uniform int uStepRadius;         // r of the local proposal [texels], >= 1

float importanceAt(uint state, ivec2 size)
{
    if (state == kNoChainState) return 0.0;
    return imageLoad(uImportance, ivec2(int(state % uint(size.x)), int(state / uint(size.x)))).r;
}

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount) return;
    ivec2 size = imageSize(uImportance);
    if (uMode == 0) {
        ImportanceSample s = samples[i];
        states[i] = s.x < 0 ? kNoChainState : uint(s.y * size.x + s.x);
        return;
    }
    uint state = states[i];
    if (state != kNoChainState && state >= uint(size.x * size.y)) state = kNoChainState; // the map shrank
    uint start = state;
    float current = importanceAt(state, size);
    for (int k = 0; k < uIterations; ++k) {
        // Four uniforms per iteration: the proposal kind, its two coordinates, the acceptance.
        uint index = (uint(i) * uint(uIterations) + uint(k)) * 2u;
        vec2 a = importanceUniforms(uSeed, index);
        vec2 b = importanceUniforms(uSeed, index + 1u);
        ivec2 proposal;
        if (a.x < uGlobalProbability || state == kNoChainState) {
            proposal = min(ivec2(a.y * float(size.x), b.x * float(size.y)), size - 1);
        } else {
            // Offset j of the (2r + 1)^2 - 1 non-zero offsets.
            int side = 2 * uStepRadius + 1;
            int j = min(int(a.y * float(side * side - 1)), side * side - 2);
            j += j >= (side * side - 1) / 2 ? 1 : 0; // skip the centre
            ivec2 x = ivec2(int(state % uint(size.x)), int(state / uint(size.x)));
            proposal = x + ivec2(j % side, j / side) - ivec2(uStepRadius);
            // Outside the map: importance 0, rejected while the chain stands on importance > 0.
            if (any(lessThan(proposal, ivec2(0))) || any(greaterThanEqual(proposal, size))) {
                if (current > 0.0) continue;
                proposal = clamp(proposal, ivec2(0), size - 1);
            }
        }
        float candidate = imageLoad(uImportance, proposal).r;
        // min(1, I(y) / I(x)) without the division: u I(x) < I(y); I(x) = 0 accepts every proposal.
        if (current == 0.0 || b.y * current < candidate) {
            state = uint(proposal.y * size.x + proposal.x);
            current = candidate;
        }
    }
    states[i] = state;
    if (state != start) atomicAdd(moved, 1u);
    float total = marginal[size.x - 1];
    ImportanceSample s;
    s.x = -1;
    s.y = -1;
    s.probability = 0.0;
    s.importance = 0.0;
    if (current > 0.0 && total > 0.0) {
        s.x = int(state % uint(size.x));
        s.y = int(state / uint(size.x));
        s.probability = current / total;
        s.importance = current;
    }
    samples[i] = s;
}
