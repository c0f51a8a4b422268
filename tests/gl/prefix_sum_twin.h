// CPU twin of PrefixSumPass (gl/passes/prefix_sum_pass.h): the same blocks, the same Hillis-Steele
// steps, the same recursion and the same adds, in the same operand order, so the GPU result must
// match it bit for bit (float addition is commutative in IEEE arithmetic, so only which values are
// added together matters, and that is fixed here).
#pragma once

#include <cstddef>
#include <vector>

namespace vplgi::test {

inline void prefixSumTwin(std::vector<float>& values, int blockSize)
{
    const std::size_t n = values.size();
    const auto block = static_cast<std::size_t>(blockSize);
    const std::size_t blocks = (n + block - 1) / block;
    std::vector<float> sums(blocks);
    std::vector<float> partial(block), next(block);
    for (std::size_t b = 0; b < blocks; ++b) {
        // prefix_sum_blocks.comp: values past the end count as 0.
        for (std::size_t k = 0; k < block; ++k)
            partial[k] = b * block + k < n ? values[b * block + k] : 0.0f;
        for (std::size_t offset = 1; offset < block; offset *= 2) {
            for (std::size_t k = 0; k < block; ++k)
                next[k] = k >= offset ? partial[k - offset] + partial[k] : partial[k];
            partial.swap(next);
        }
        for (std::size_t k = 0; k < block && b * block + k < n; ++k)
            values[b * block + k] = partial[k];
        sums[b] = partial[block - 1];
    }
    if (blocks <= 1) return;
    prefixSumTwin(sums, blockSize);
    // prefix_sum_add.comp
    for (std::size_t i = block; i < n; ++i)
        values[i] = sums[i / block - 1] + values[i];
}

} // namespace vplgi::test
