#include "prefix_sum_pass.h"

#include <optional>

#include "core/util/error.h"
#include "glsl/shared/bindings.h"

namespace vplgi {

PrefixSumPass::PrefixSumPass(const gl::ShaderLoader& shaders, std::string name, int blockSize)
    : mName(std::move(name)), mBlockSize(blockSize)
{
    require(blockSize >= 2 && (blockSize & (blockSize - 1)) == 0,
            mName + ": block size " + std::to_string(blockSize) + " is not a power of two >= 2");
    const std::vector<std::string> defines = {"BLOCK_SIZE=" + std::to_string(blockSize)};
    mBlocks = ComputePass(shaders, mName + ": blocks", "passes/prefix_sum_blocks.comp", defines);
    mAdd = ComputePass(shaders, mName + ": add block offsets", "passes/prefix_sum_add.comp", defines);
}

void PrefixSumPass::run(const gl::Buffer& values, int count, NextRead next, gl::PassTimer* timer)
{
    require(count >= 0 && static_cast<GLsizeiptr>(count) * static_cast<GLsizeiptr>(sizeof(float)) <= values.size(),
            mName + ": " + std::to_string(count) + " values do not fit the buffer");
    // All levels' block-sum buffers exist before the recursion holds references into mBlockSums.
    std::size_t level = 0;
    for (int n = count; n > 0; n = n > mBlockSize ? (n + mBlockSize - 1) / mBlockSize : 0, ++level) {
        const GLsizeiptr size = static_cast<GLsizeiptr>((n + mBlockSize - 1) / mBlockSize) * sizeof(float);
        if (mBlockSums.size() <= level) mBlockSums.resize(level + 1);
        if (mBlockSums[level].size() < size)
            mBlockSums[level] = gl::Buffer(mName + " block sums " + std::to_string(level), size);
    }
    std::optional<gl::PassTimer::Scope> scope;
    if (timer) scope.emplace(*timer, mName);
    if (count > 0) scanLevel(values, count, 0, timer);
    memoryBarrier(next);
}

void PrefixSumPass::scanLevel(const gl::Buffer& values, int count, std::size_t level, gl::PassTimer* timer)
{
    const int blocks = (count + mBlockSize - 1) / mBlockSize;
    const gl::Buffer& sums = mBlockSums[level]; // sized by run()

    bindStorageBuffer(shared::kBindingScanValues, values);
    bindStorageBuffer(shared::kBindingScanBlockSums, sums);
    mBlocks.program().set("uCount", count);
    mBlocks.dispatch(count, 1, NextRead::StorageBuffer, timer);
    if (blocks == 1) return;

    scanLevel(sums, blocks, level + 1, timer); // rebinds the two slots to the next level's buffers
    bindStorageBuffer(shared::kBindingScanValues, values);
    bindStorageBuffer(shared::kBindingScanBlockSums, sums);
    mAdd.program().set("uCount", count);
    mAdd.dispatch(count, 1, NextRead::StorageBuffer, timer);
}

} // namespace vplgi
