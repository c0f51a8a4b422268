// Inclusive prefix sums of a float buffer on the GPU, in place, deterministic: two kernels and a
// recursion, with no atomics and an order of adds fixed by the block size alone.
//   1. prefix_sum_blocks.comp: each block of B values is scanned in shared memory (Hillis-Steele,
//      log2 B steps); its total goes to a per-level block-sum buffer.
//   2. the block sums are scanned by the same two steps (recursively, until one block is left).
//   3. prefix_sum_add.comp: block b > 0 adds the scanned total of blocks 0..b-1.
// Hillis-Steele does O(B log B) adds per block rather than the work-efficient O(B); at B = 256 and
// the sizes used here (up to a few million values) that is a few microseconds on a GPU, and it keeps
// the kernel and its CPU twin (tests/gl/prefix_sum_twin.h, bit-identical) short.
#pragma once

#include <string>
#include <vector>

#include "compute_pass.h"

namespace vplgi {

class PrefixSumPass {
public:
    // `blockSize`: values per work-group (a power of two, at most the driver's work-group size limit).
    PrefixSumPass(const gl::ShaderLoader& shaders, std::string name, int blockSize = 256);

    // Replaces values[0..count) with their inclusive prefix sums, then issues the barrier for `next`.
    // Uses the storage-buffer slots kBindingScanValues and kBindingScanBlockSums.
    void run(const gl::Buffer& values, int count, NextRead next, gl::PassTimer* timer = nullptr);

    int blockSize() const { return mBlockSize; }

private:
    void scanLevel(const gl::Buffer& values, int count, std::size_t level, gl::PassTimer* timer);

    std::string mName;
    int mBlockSize;
    ComputePass mBlocks;
    ComputePass mAdd;
    std::vector<gl::Buffer> mBlockSums; // one per recursion level, grown on demand
};

} // namespace vplgi
