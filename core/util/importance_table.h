// CPU twin of the GPU importance sampler (gl/passes/importance_sampler.h): the same tables, summed in
// the same order, and the same search (glsl/shared/importance.h), so CPU and GPU agree bit for bit.
// Also usable on its own by CPU code that draws texels in proportion to a map.
#pragma once

#include <cstdint>
#include <vector>

#include "glsl/shared/importance.h"

namespace vplgi {

// ../shared/MATH.md 9.7 tables of a width x height map, rows bottom to top as GL stores them.
struct ImportanceTable {
    int width = 0;
    int height = 0;
    std::vector<float> importance; // I(u, v) at v * width + u
    std::vector<float> columns;    // C(u, v) = sum_{v' <= v} I(u, v'), at v * width + u
    std::vector<float> marginal;   // R(u) = sum_{u' <= u} C(u', height - 1)

    float total() const { return marginal.empty() ? 0.0f : marginal.back(); }
};

// Builds the tables with serial sums in index order (the GPU kernels' order). Throws Error when the
// size does not match or a value is negative or not finite.
ImportanceTable buildImportanceTable(std::vector<float> importance, int width, int height);

// Readers for glsl/shared/importance.h (found by argument-dependent lookup).
inline float importanceMarginal(const ImportanceTable& t, int u)
{
    return t.marginal[static_cast<std::size_t>(u)];
}
inline float importanceColumn(const ImportanceTable& t, int u, int v)
{
    return t.columns[static_cast<std::size_t>(v) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(u)];
}
inline float importanceValue(const ImportanceTable& t, int u, int v)
{
    return t.importance[static_cast<std::size_t>(v) * static_cast<std::size_t>(t.width) + static_cast<std::size_t>(u)];
}

// Draw i = 0..count-1 uses shared::importanceUniforms(seed, i), as the GPU kernel does.
std::vector<shared::ImportanceSample> sampleImportanceTable(const ImportanceTable& table, int count,
                                                            std::uint32_t seed);

} // namespace vplgi
