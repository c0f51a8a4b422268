// The one importance sampler of vplgi: draws N texels of a W x H map with probability proportional
// to their importance, on the GPU. VSGL uses it for BRSM sampling (RSM texels as VPL candidates,
// ../shared/MATH.md 10.1), LightSkin for VAL selection (eq. 12).
//
// build() makes the tables of ../shared/MATH.md 9.7 from an R32F importance texture:
//   importance_columns.comp   column prefix sums C(u, v), "vertically": one invocation per column
//   importance_marginal.comp  prefix sums R(u) of the column totals, "horizontally": one work-group
// sample() runs importance_sample.comp: draw i hashes (seed, i) into two uniforms and binary-searches
// R, then column u of C (glsl/shared/importance.h), writing an ImportanceSample (texel and per-draw
// probability I / total) per draw.
//
// Why serial scans and not log-step ones: each table is a serial recurrence x_k = x_{k-1} + a_k.
// (1) A zero-importance texel then leaves the sum bit-identical, which is what guarantees that the
//     strict search never selects it; a tree scan adds neighbouring prefixes in different orders, so
//     R(u) can exceed R(u-1) by an ulp although T(u) = 0, and a zero column could be drawn with a
//     probability the sampler reports as 0 (an infinite VPL weight downstream).
// (2) The CPU twin (core/util/importance_table.h) is the obvious loop and agrees bit for bit.
// (3) The work is W parallel columns of H steps plus one W-step pass over shared memory: for
//     RSM-sized maps (up to 2048^2) the columns are enough parallelism on a GPU, and the accesses of
//     neighbouring invocations are contiguous.
// These are the column-CDF and marginal-CDF tables rather than a full summed-area table S(u, v):
// sampling a column from S would need differences S(u, v) - S(u-1, v), which are not exact in
// float and lose (1) again.
#pragma once

#include <cstdint>
#include <string>

#include "compute_pass.h"

namespace vplgi {

class ImportanceSampler {
public:
    explicit ImportanceSampler(const gl::ShaderLoader& shaders, std::string name = "importance sampler");

    // Builds the tables from level 0 of `importance` (GL_R32F, values finite and >= 0), then issues
    // the barrier for `next` and for sample() (NextRead::StorageBuffer). Writes to `importance`
    // before this call need the caller's barrier for image reads (NextRead::Image).
    void build(const gl::Texture& importance, NextRead next, gl::PassTimer* timer = nullptr);
    // Draws `count` texels with the uniforms of (seed, 0..count-1) into samples(), then issues the
    // barrier for `next`. `importance` is the texture of the last build(), unchanged since.
    void sample(const gl::Texture& importance, int count, std::uint32_t seed, NextRead next,
                gl::PassTimer* timer = nullptr);

    // Level l+1 of `importance` from level l, for every level of the texture: box means of 2x2 in a
    // fixed order (passes/importance_mips.comp; every level halves both sides exactly), then the
    // barrier for `next`. Writes to level 0 need the caller's barrier for image reads.
    void buildMips(const gl::Texture& importance, NextRead next, gl::PassTimer* timer = nullptr) const;

    const gl::Buffer& columns() const { return mColumns; }   // float C(u, v) at v * W + u
    const gl::Buffer& marginal() const { return mMarginal; } // float R(u); R(W-1) is the total
    const gl::Buffer& samples() const { return mSamples; }   // shared::ImportanceSample[count]

private:
    std::string mName;
    ComputePass mColumnPass;
    ComputePass mMarginalPass;
    ComputePass mSamplePass;
    ComputePass mMipsPass;
    gl::Buffer mColumns;
    gl::Buffer mMarginal;
    gl::Buffer mSamples;
    int mWidth = 0;
    int mHeight = 0;
};

} // namespace vplgi
