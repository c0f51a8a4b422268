#include "limits.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cstdio>
#include <mutex>
#include <set>

#include "context.h"

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

} // namespace vplgi::gl
