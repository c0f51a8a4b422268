#include "debug.h"

#include <epoxy/gl.h>

#include <atomic>
#include <cstdio>
#include <mutex>

#include "core/util/error.h"

namespace vplgi::gl {

namespace {

std::atomic<int> gHighSeverityCount{0};
std::atomic<bool> gThrowOnHigh{false};
std::mutex gMutex;
std::string gPendingMessage;

const char* sourceName(GLenum source)
{
    switch (source) {
    case GL_DEBUG_SOURCE_API: return "api";
    case GL_DEBUG_SOURCE_SHADER_COMPILER: return "shader compiler";
    case GL_DEBUG_SOURCE_WINDOW_SYSTEM: return "window system";
    case GL_DEBUG_SOURCE_THIRD_PARTY: return "third party";
    case GL_DEBUG_SOURCE_APPLICATION: return "application";
    default: return "other";
    }
}

void GLAPIENTRY onDebugMessage(GLenum source, GLenum type, GLuint, GLenum severity, GLsizei length,
                               const GLchar* message, const void*)
{
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    if (type == GL_DEBUG_TYPE_PUSH_GROUP || type == GL_DEBUG_TYPE_POP_GROUP) return;
    std::string text(message, length >= 0 ? static_cast<std::size_t>(length) : std::char_traits<char>::length(message));
    // Shader compile errors are reported by the shader loader with file:line; do not duplicate them.
    if (source == GL_DEBUG_SOURCE_SHADER_COMPILER) return;
    const char* level = severity == GL_DEBUG_SEVERITY_HIGH ? "high" : severity == GL_DEBUG_SEVERITY_MEDIUM ? "medium" : "low";
    std::fprintf(stderr, "GL debug (%s, %s): %s\n", sourceName(source), level, text.c_str());
    if (severity == GL_DEBUG_SEVERITY_HIGH || type == GL_DEBUG_TYPE_ERROR) {
        ++gHighSeverityCount;
        std::lock_guard<std::mutex> lock(gMutex);
        if (gPendingMessage.empty()) gPendingMessage = text;
    }
}

} // namespace

void installDebugCallback(bool throwOnHighSeverity)
{
    gThrowOnHigh = throwOnHighSeverity;
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(onDebugMessage, nullptr);
    glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_TRUE);
}

void checkDebugMessages()
{
    std::string message;
    {
        std::lock_guard<std::mutex> lock(gMutex);
        message.swap(gPendingMessage);
    }
    if (gThrowOnHigh && !message.empty()) throw Error("GL error: " + message);
}

int highSeverityMessageCount()
{
    return gHighSeverityCount.load();
}

DebugGroup::DebugGroup(const std::string& name)
{
    glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, static_cast<GLsizei>(name.size()), name.c_str());
}

DebugGroup::~DebugGroup()
{
    glPopDebugGroup();
}

} // namespace vplgi::gl
