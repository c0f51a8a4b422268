// The GL implementation's limits, and clamps of budgets and sizes to them with a one-line warning
// (issue 13 part 6): a parameter that asks for more than the driver gives is reduced to what it
// gives, once per value, rather than failing with a GL error or, worse, silently dropping work.
//
// llvmpipe's loop budget: Mesa's llvmpipe stops a shader invocation's loops after 65535 iterations
// in total (LP_MAX_TGSI_LOOP_ITERATIONS, summed over every loop the invocation runs), without an
// error: a per-pixel loop over 65536 lights silently drops the last one. clampShaderLoopCount()
// caps such counts on llvmpipe only.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace vplgi::gl {

struct Limits {
    int maxTextureSize = 0;             // GL_MAX_TEXTURE_SIZE [texels]
    int maxArrayTextureLayers = 0;      // GL_MAX_ARRAY_TEXTURE_LAYERS
    long long maxStorageBlockSize = 0;  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE [bytes]
    int maxShaderLoopIterations = 0;    // per invocation, over all its loops; 0: no known limit
};

// The current context's limits (queried every call: cheap, and right after a context change).
Limits queryLimits();

// llvmpipe's per-invocation loop budget (LP_MAX_TGSI_LOOP_ITERATIONS).
constexpr int kLlvmpipeLoopIterations = 65535;

// Each returns `value` when the implementation allows it, else the largest value it allows, and
// then prints one line "vplgi: warning: <what> = <value> ... clamped to <n>" (once per what/value).
// `what` names the parameter ("vsgl.count", "rsm.size").
// `limit` is derived by the caller; `why` names it ("GL_MAX_TEXTURE_SIZE / layers").
int clampToLimit(int value, long long limit, const std::string& what, const std::string& why);
// A count of elements of `elementBytes` each in one shader storage block.
int clampStorageCount(int value, std::size_t elementBytes, const std::string& what);
// A count a shader iterates over per invocation (`iterationsPerUnit` loop iterations each).
int clampShaderLoopCount(int value, const std::string& what, int iterationsPerUnit = 1);

// Every warning printed so far in this process (tests check them).
const std::vector<std::string>& limitWarnings();

} // namespace vplgi::gl
