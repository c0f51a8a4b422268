// Bit-identical results across runs and llvmpipe thread counts: a hash of the bytes, and a record of
// it for tests/gl/threads_identical.sh, which runs a test once with LP_NUM_THREADS=1 and once with 2
// and compares what each run recorded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace vplgi::test {

// FNV-1a over `size` bytes, continuing from `hash`.
inline std::uint64_t hashBytes(const void* data, std::size_t size, std::uint64_t hash = 1469598103934665603ull)
{
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i)
        hash = (hash ^ bytes[i]) * 1099511628211ull;
    return hash;
}

// Appends "label hash" to the file named by $VPLGI_HASH_FILE (set by tests/gl/threads_identical.sh);
// nothing when it is unset. Returns false when the file cannot be written.
inline bool recordHash(const std::string& label, std::uint64_t hash)
{
    const char* file = std::getenv("VPLGI_HASH_FILE");
    if (!file) return true;
    std::FILE* out = std::fopen(file, "a");
    if (!out) return false;
    std::fprintf(out, "%s %016llx\n", label.c_str(), static_cast<unsigned long long>(hash));
    return std::fclose(out) == 0;
}

} // namespace vplgi::test
