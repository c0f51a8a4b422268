// Metropolis-Hastings chains over an importance map, carried from frame to frame: technique tcas's
// VPL sampler (Barak, Bittner, Havran, "Temporally Coherent Adaptive Sampling for Imperfect Shadow
// Maps", EGSR 2013, the SMCIR paper's [26]; built from the SMCIR paper's description, papers/000
// lines 220-235 and 898-902, every choice of ours labelled in passes/metropolis_chains.comp).
//
// Chain i holds one texel of the map. start() puts chain i on draw i of the importance sampler (an
// exact draw from I / total: the chains begin in their stationary distribution, so no burn-in; ours).
// step() runs `iterations` Metropolis-Hastings steps of every chain against the current map (the
// map may have changed since the last step: the chains follow it, which is the temporal coherence)
// and writes one ImportanceSample per chain, in the layout ImportanceSampler::samples() has, so the
// passes that read draws read chains unchanged. A chain on a texel of importance 0 after its steps
// (the map went dark there) writes x = -1: no VPL.
//
// Per chain, the estimator Phi_j / (N P_j) with P_j = I_j / total is unbiased once the chain is in
// its stationary distribution (its state is then distributed as I / total); after the map changes,
// until the chains have followed, it is not: the lag is the price of the coherence.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "compute_pass.h"
#include "importance_sampler.h"

namespace vplgi {

struct MetropolisProposal {
    // Not in the papers (docs/tcas.md, measured on a still cornell by tests/image/test_tcas_technique.cpp):
    // per iteration, a proposal uniform over the map with this probability (1/32: half a proposal
    // per chain per frame at 16 iterations, which lets a chain cross between RSM layers and islands),
    // else a local step. 1/8 with radius 2 moved a VPL 0.46 of an independent draw's distance per
    // frame, 1/32 with radius 1 0.16.
    float globalProbability = 0.03125f;
    int stepRadius = 1; // the local proposal's offsets, [-r, r]^2 [texels]
};

class MetropolisChains {
public:
    explicit MetropolisChains(const gl::ShaderLoader& shaders, std::string name = "Metropolis chains");

    // Chain i at draw i of `tables`' last sample() (`count` draws of `importance`).
    void start(const gl::Texture& importance, const ImportanceSampler& tables, int count, NextRead next);
    // Chain i at texel states[i] = y * W + x (shared::kNoChainState: none), for tests.
    void setStates(const std::vector<std::uint32_t>& states);
    // `iterations` steps of every chain against `importance`, whose tables `tables` last built
    // (their total normalises the probabilities), with the uniforms of `seed`; then the barrier for
    // `next`. Throws Error before start() or setStates().
    void step(const gl::Texture& importance, const ImportanceSampler& tables, int iterations, std::uint32_t seed,
              const MetropolisProposal& proposal, NextRead next, gl::PassTimer* timer = nullptr);

    int count() const { return mCount; }
    const gl::Buffer& states() const { return mStates; }   // uint[count]
    const gl::Buffer& samples() const { return mSamples; } // shared::ImportanceSample[count]
    // The chains whose texel changed in the last step (reads a counter back: a GPU sync).
    int movedInLastStep() const;

private:
    void resize(int count);

    std::string mName;
    ComputePass mPass;
    gl::Buffer mStates;
    gl::Buffer mSamples;
    gl::Buffer mCounters;
    int mCount = 0;
};

} // namespace vplgi
