// Readback and bitwise comparison helpers for the compute-kernel tests.
#pragma once

#include <cstring>
#include <vector>

#include "gl/api/objects.h"

namespace vplgi::test {

// The first `count` elements of `buffer` (the writes must be visible: NextRead::BufferReadback).
template <typename T> std::vector<T> readBuffer(const gl::Buffer& buffer, std::size_t count)
{
    std::vector<T> data(count);
    glGetNamedBufferSubData(buffer.id(), 0, static_cast<GLsizeiptr>(count * sizeof(T)), data.data());
    return data;
}

// Index of the first element whose bits differ, or -1 (bitwise: -0 vs 0 and NaNs count as different);
// 0 when the sizes differ.
inline long firstBitDifference(const std::vector<float>& a, const std::vector<float>& b)
{
    if (a.size() != b.size()) return 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::memcmp(&a[i], &b[i], sizeof(float)) != 0) return static_cast<long>(i);
    return -1;
}

} // namespace vplgi::test
