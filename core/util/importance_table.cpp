#include "core/util/importance_table.h"

#include <cmath>
#include <string>

#include "core/util/error.h"

namespace vplgi {

ImportanceTable buildImportanceTable(std::vector<float> importance, int width, int height)
{
    require(width > 0 && height > 0, "importance map: size must be positive");
    require(importance.size() == static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
            "importance map: " + std::to_string(importance.size()) + " values for " + std::to_string(width) + " x " +
                std::to_string(height) + " texels");
    for (float value : importance)
        require(std::isfinite(value) && value >= 0.0f, "importance map: values must be finite and >= 0");

    ImportanceTable t;
    t.width = width;
    t.height = height;
    t.importance = std::move(importance);
    t.columns.resize(t.importance.size());
    t.marginal.resize(static_cast<std::size_t>(width));
    const auto w = static_cast<std::size_t>(width);
    // Vertical: one running sum per column, rows in order (importance_columns.comp, one invocation
    // per column).
    for (std::size_t u = 0; u < w; ++u) {
        float sum = 0.0f;
        for (std::size_t v = 0; v < static_cast<std::size_t>(height); ++v) {
            sum += t.importance[v * w + u];
            t.columns[v * w + u] = sum;
        }
    }
    // Horizontal: one running sum over the column totals (importance_marginal.comp, one invocation).
    float sum = 0.0f;
    for (std::size_t u = 0; u < w; ++u) {
        sum += t.columns[(static_cast<std::size_t>(height) - 1) * w + u];
        t.marginal[u] = sum;
    }
    return t;
}

std::vector<shared::ImportanceSample> sampleImportanceTable(const ImportanceTable& table, int count, std::uint32_t seed)
{
    std::vector<shared::ImportanceSample> samples(static_cast<std::size_t>(count));
    for (int i = 0; i < count; ++i)
        samples[static_cast<std::size_t>(i)] = shared::sampleImportance(
            table, table.width, table.height, shared::importanceUniforms(seed, static_cast<std::uint32_t>(i)));
    return samples;
}

} // namespace vplgi
