#include "limits.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <set>

#include "context.h"
#include "core/util/error.h"

namespace vplgi::gl {

namespace {

std::mutex gMutex;
std::vector<std::string> gWarnings;
std::set<std::string> gWarned; // what = value pairs already reported

int clampTo(int value, long long limit, const std::string& what, const std::string& why)
{
    if (limit <= 0 || value <= limit) return value;
    const int clamped = static_cast<int>(limit);
    const std::string key = what + "=" + std::to_string(value) + "->" + std::to_string(clamped);
    std::lock_guard<std::mutex> lock(gMutex);
    if (gWarned.insert(key).second) {
        const std::string message = what + " = " + std::to_string(value) + " exceeds " + why + "; clamped to " +
                                    std::to_string(clamped);
        std::fprintf(stderr, "vplgi: warning: %s\n", message.c_str());
        gWarnings.push_back(message);
    }
    return clamped;
}

} // namespace

Limits queryLimits()
{
    Limits limits;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &limits.maxTextureSize);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &limits.maxArrayTextureLayers);
    GLint64 block = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
    limits.maxStorageBlockSize = static_cast<long long>(block);
    limits.maxShaderLoopIterations = rendererName().find("llvmpipe") != std::string::npos ? kLlvmpipeLoopIterations : 0;
    return limits;
}

int clampToLimit(int value, long long limit, const std::string& what, const std::string& why)
{
    return clampTo(value, limit, what, why);
}

int clampStorageCount(int value, std::size_t elementBytes, const std::string& what)
{
    const long long block = queryLimits().maxStorageBlockSize;
    if (block <= 0 || elementBytes == 0) return value;
    return clampTo(value, block / static_cast<long long>(elementBytes), what, "GL_MAX_SHADER_STORAGE_BLOCK_SIZE");
}

int clampShaderLoopCount(int value, const std::string& what, int iterationsPerUnit)
{
    const int budget = queryLimits().maxShaderLoopIterations;
    if (budget <= 0) return value;
    return clampTo(value, budget / std::max(iterationsPerUnit, 1), what,
                   "llvmpipe's loop budget per shader invocation (65535 iterations)");
}

const std::vector<std::string>& limitWarnings()
{
    return gWarnings;
}

namespace {

// Each limit once: its GL name, its enum and where it lives in ResourceCounts.
struct LimitRow {
    const char* name;
    GLenum pname;
    int ResourceCounts::*total;
    StageResources ResourceCounts::*stage;
    int StageResources::*count;
};

const LimitRow kLimitRows[] = {
    {"GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS", GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &ResourceCounts::storageBufferBindings, nullptr, nullptr},
    {"GL_MAX_UNIFORM_BUFFER_BINDINGS", GL_MAX_UNIFORM_BUFFER_BINDINGS, &ResourceCounts::uniformBufferBindings, nullptr, nullptr},
    {"GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS", GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &ResourceCounts::textureUnits, nullptr, nullptr},
    {"GL_MAX_IMAGE_UNITS", GL_MAX_IMAGE_UNITS, &ResourceCounts::imageUnits, nullptr, nullptr},
    {"GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS", GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, nullptr, &ResourceCounts::vertex, &StageResources::storageBlocks},
    {"GL_MAX_VERTEX_UNIFORM_BLOCKS", GL_MAX_VERTEX_UNIFORM_BLOCKS, nullptr, &ResourceCounts::vertex, &StageResources::uniformBlocks},
    {"GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS", GL_MAX_VERTEX_TEXTURE_IMAGE_UNITS, nullptr, &ResourceCounts::vertex, &StageResources::samplers},
    {"GL_MAX_VERTEX_IMAGE_UNIFORMS", GL_MAX_VERTEX_IMAGE_UNIFORMS, nullptr, &ResourceCounts::vertex, &StageResources::images},
    {"GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS", GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS, nullptr, &ResourceCounts::fragment, &StageResources::storageBlocks},
    {"GL_MAX_FRAGMENT_UNIFORM_BLOCKS", GL_MAX_FRAGMENT_UNIFORM_BLOCKS, nullptr, &ResourceCounts::fragment, &StageResources::uniformBlocks},
    {"GL_MAX_TEXTURE_IMAGE_UNITS", GL_MAX_TEXTURE_IMAGE_UNITS, nullptr, &ResourceCounts::fragment, &StageResources::samplers},
    {"GL_MAX_FRAGMENT_IMAGE_UNIFORMS", GL_MAX_FRAGMENT_IMAGE_UNIFORMS, nullptr, &ResourceCounts::fragment, &StageResources::images},
    {"GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS", GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, nullptr, &ResourceCounts::compute, &StageResources::storageBlocks},
    {"GL_MAX_COMPUTE_UNIFORM_BLOCKS", GL_MAX_COMPUTE_UNIFORM_BLOCKS, nullptr, &ResourceCounts::compute, &StageResources::uniformBlocks},
    {"GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS", GL_MAX_COMPUTE_TEXTURE_IMAGE_UNITS, nullptr, &ResourceCounts::compute, &StageResources::samplers},
    {"GL_MAX_COMPUTE_IMAGE_UNIFORMS", GL_MAX_COMPUTE_IMAGE_UNIFORMS, nullptr, &ResourceCounts::compute, &StageResources::images},
};

// The row's number in `counts` (a reference: const or not, as `counts`).
template <typename Counts>
auto& field(Counts& counts, const LimitRow& row)
{
    return row.total ? counts.*row.total : (counts.*row.stage).*row.count;
}

} // namespace

ResourceCounts queryResourceLimits()
{
    ResourceCounts limits;
    for (const LimitRow& row : kLimitRows) {
        GLint value = 0;
        glGetIntegerv(row.pname, &value);
        field(limits, row) = value;
    }
    return limits;
}

std::vector<std::string> resourceShortfalls(const ResourceCounts& offered, const ResourceCounts& needed)
{
    std::vector<std::string> shortfalls;
    for (const LimitRow& row : kLimitRows) {
        if (field(offered, row) < field(needed, row)) {
            shortfalls.push_back(std::string(row.name) + " is " + std::to_string(field(offered, row)) +
                                 ", vplgi needs " + std::to_string(field(needed, row)));
        }
    }
    return shortfalls;
}

void requireResourceLimits()
{
    const std::vector<std::string> shortfalls = resourceShortfalls(queryResourceLimits(), kResourceNeeds);
    if (shortfalls.empty()) return;
    std::string message = "this OpenGL implementation (" + rendererName() + ") offers too little for vplgi's shaders:";
    for (std::size_t i = 0; i < shortfalls.size(); ++i)
        message += (i ? "; " : " ") + shortfalls[i];
    throw Error(message + " (gl/api/limits.h, kResourceNeeds)");
}

} // namespace vplgi::gl
