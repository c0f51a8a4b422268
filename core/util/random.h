// Random numbers for the CPU samplers (path tracer, SMCIR): PCG32 streams keyed by hashes of
// (seed, pixel or item, sample), so results never depend on threads or scheduling. No std::
// distributions, whose outputs differ between standard libraries.
#pragma once

#include <cstdint>

namespace vplgi {

// PCG32 (O'Neill 2014, pcg32_random_r): 64-bit LCG state, xorshift-high + random-rotate output.
class Pcg32 {
public:
    Pcg32(std::uint64_t state, std::uint64_t sequence) : mIncrement((sequence << 1u) | 1u)
    {
        next();
        mState += state;
        next();
    }

    std::uint32_t next()
    {
        const std::uint64_t old = mState;
        mState = old * 6364136223846793005ull + mIncrement;
        const auto xorShifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
        const auto rotation = static_cast<std::uint32_t>(old >> 59u);
        return (xorShifted >> rotation) | (xorShifted << ((32u - rotation) & 31u));
    }

    // Uniform in [0, 1): 24 random bits, exactly representable, never 1.
    float uniform() { return static_cast<float>(next() >> 8u) * 0x1p-24f; }
    // Uniform in [0, n) for n >= 1 (multiply-shift; the bias is below 2^-32 * n).
    std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>((std::uint64_t(next()) * n) >> 32u); }

private:
    std::uint64_t mState = 0;
    std::uint64_t mIncrement;
};

// SplitMix64's finalizer: a bijective 64-bit mix.
inline std::uint64_t mix64(std::uint64_t z)
{
    z += 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30u)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27u)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31u);
}

} // namespace vplgi
