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

// Resources the shaders bind: binding points (one name per buffer and texture in
// glsl/shared/bindings.h) and, per stage, what the busiest entry point's live code uses.
struct StageResources {
    int storageBlocks = 0; // GL_MAX_<STAGE>_SHADER_STORAGE_BLOCKS
    int uniformBlocks = 0; // GL_MAX_<STAGE>_UNIFORM_BLOCKS
    int samplers = 0;      // GL_MAX_<STAGE>_TEXTURE_IMAGE_UNITS (fragment: GL_MAX_TEXTURE_IMAGE_UNITS)
    int images = 0;        // GL_MAX_<STAGE>_IMAGE_UNIFORMS
};
struct ResourceCounts {
    int storageBufferBindings = 0; // GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS
    int uniformBufferBindings = 0; // GL_MAX_UNIFORM_BUFFER_BINDINGS
    int textureUnits = 0;          // GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS
    int imageUnits = 0;            // GL_MAX_IMAGE_UNITS
    StageResources vertex, fragment, compute;
};

// What vplgi needs (issue 29 part 2). Every stage's count is within GL 4.5's guaranteed minimum but
// the vertex stage's storage blocks (GL 4.5 guarantees none; every desktop driver offers them); the
// storage buffer binding points, numbered up to 31 in bindings.h, exceed the guaranteed 8 (llvmpipe
// offers 80). Kept exact by tests/shaders/validate_shaders.cpp, which counts the binding points in
// bindings.h and each stage from glslangValidator's reflection of every entry point, and fails when a
// number here differs from what it counts.
constexpr ResourceCounts kResourceNeeds{32, 1, 28, 8, {2, 1, 0, 0}, {5, 1, 7, 0}, {7, 1, 7, 6}};

// The current context's values of the limits above.
ResourceCounts queryResourceLimits();
// One phrase per limit that `offered` has below `needed`: "GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS is 16,
// vplgi needs 32"; empty when everything fits.
std::vector<std::string> resourceShortfalls(const ResourceCounts& offered, const ResourceCounts& needed);
// Throws Error with one line naming every shortfall of the current context (called when a context
// is made: a driver that offers less stops there, not at a link error or a silently unbound buffer).
void requireResourceLimits();

} // namespace vplgi::gl
