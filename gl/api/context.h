// OpenGL 4.5 core contexts behind one interface: EGL headless (surfaceless, then the device
// platform, then the default display with a pbuffer) and a GLFW window (gl/api/window.h).
#pragma once

#include <memory>
#include <string>

namespace vplgi::gl {

struct ContextOptions {
    bool debug = true;               // debug context + KHR_debug callback (synchronous)
    bool throwOnHighSeverity = false; // checkDebugMessages() throws after a high-severity message (tests)
};

class Context {
public:
    virtual ~Context() = default;
    virtual void makeCurrent() = 0;
    // "EGL surfaceless", "EGL device", "EGL pbuffer", "GLFW window" + GL_RENDERER.
    virtual std::string description() const = 0;
};

// Tries the EGL platforms in order; throws Error listing each failure when none gives 4.5 core.
std::unique_ptr<Context> createHeadlessContext(const ContextOptions& options = {});

// Called once a context is current: loads nothing (libepoxy resolves lazily), checks the version,
// installs the debug callback. Throws Error when the context is older than 4.5.
void initializeCurrentContext(const ContextOptions& options);

// GL_RENDERER string of the current context; true when it is Mesa's software rasterizer.
std::string rendererName();
bool isSoftwareRenderer();

} // namespace vplgi::gl
