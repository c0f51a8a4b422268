// Powers of two: the edges of textures with full mip chains (RSMs, the shadow atlas, paraboloid
// maps, VSGL's G-buffer grid).
#pragma once

namespace vplgi {

inline bool isPowerOfTwo(int n)
{
    return n > 0 && (n & (n - 1)) == 0;
}

// The smallest l with 2^l >= n (log2 n exactly for a power of two); 0 for n <= 1.
inline int ceilLog2(int n)
{
    int l = 0;
    while ((1 << l) < n)
        ++l;
    return l;
}

// Levels of a full mip chain over an edge of `size` texels (a power of two): 1 + log2(size).
inline int mipLevelCount(int size)
{
    return 1 + ceilLog2(size);
}

} // namespace vplgi
