#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "context.h"
#include "core/util/error.h"
#include "debug.h"
#include "limits.h"

namespace vplgi::gl {

namespace {

class EGLContextImpl final : public Context {
public:
    EGLContextImpl(EGLDisplay display, EGLContext context, EGLSurface surface, std::string kind)
        : mDisplay(display), mContext(context), mSurface(surface), mKind(std::move(kind))
    {
    }
    ~EGLContextImpl() override
    {
        eglMakeCurrent(mDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (mSurface != EGL_NO_SURFACE) eglDestroySurface(mDisplay, mSurface);
        eglDestroyContext(mDisplay, mContext);
        eglTerminate(mDisplay);
    }
    void makeCurrent() override
    {
        require(eglMakeCurrent(mDisplay, mSurface, mSurface, mContext) == EGL_TRUE, "EGL: eglMakeCurrent failed");
    }
    std::string description() const override { return mKind + ", " + rendererName(); }

private:
    EGLDisplay mDisplay;
    EGLContext mContext;
    EGLSurface mSurface;
    std::string mKind;
};

std::string eglErrorText()
{
    return "EGL error 0x" + [] {
        char buffer[16];
        std::snprintf(buffer, sizeof buffer, "%04x", eglGetError());
        return std::string(buffer);
    }();
}

// Creates a 4.5 core context on `display`; with `pbuffer` also a 16x16 pbuffer surface.
std::unique_ptr<Context> tryDisplay(EGLDisplay display, bool pbuffer, const std::string& kind,
                                    const ContextOptions& options, std::string& failure)
{
    if (display == EGL_NO_DISPLAY) {
        failure = kind + ": no display";
        return nullptr;
    }
    EGLint major = 0, minor = 0;
    if (eglInitialize(display, &major, &minor) != EGL_TRUE) {
        failure = kind + ": eglInitialize failed (" + eglErrorText() + ")";
        return nullptr;
    }
    const EGLint configAttributes[] = {EGL_SURFACE_TYPE, pbuffer ? EGL_PBUFFER_BIT : 0, EGL_RENDERABLE_TYPE,
                                       EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    bool haveConfig = eglChooseConfig(display, configAttributes, &config, 1, &count) == EGL_TRUE && count > 0;
    if (!haveConfig && pbuffer) {
        failure = kind + ": no pbuffer config";
        eglTerminate(display);
        return nullptr;
    }
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
        failure = kind + ": eglBindAPI(OpenGL) failed";
        eglTerminate(display);
        return nullptr;
    }
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                        EGL_CONTEXT_OPENGL_DEBUG, options.debug ? EGL_TRUE : EGL_FALSE, EGL_NONE};
    EGLContext context = eglCreateContext(display, haveConfig ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT,
                                          contextAttributes);
    if (context == EGL_NO_CONTEXT) {
        failure = kind + ": no OpenGL 4.5 core context (" + eglErrorText() + ")";
        eglTerminate(display);
        return nullptr;
    }
    EGLSurface surface = EGL_NO_SURFACE;
    if (pbuffer) {
        const EGLint surfaceAttributes[] = {EGL_WIDTH, 16, EGL_HEIGHT, 16, EGL_NONE};
        surface = eglCreatePbufferSurface(display, config, surfaceAttributes);
        if (surface == EGL_NO_SURFACE) {
            failure = kind + ": eglCreatePbufferSurface failed (" + eglErrorText() + ")";
            eglDestroyContext(display, context);
            eglTerminate(display);
            return nullptr;
        }
    }
    auto result = std::make_unique<EGLContextImpl>(display, context, surface, kind);
    if (eglMakeCurrent(display, surface, surface, context) != EGL_TRUE) {
        failure = kind + ": eglMakeCurrent failed (" + eglErrorText() + ")";
        return nullptr;
    }
    return result;
}

bool hasClientExtension(const char* name)
{
    const char* extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    return extensions != nullptr && std::string(" ") .append(extensions).append(" ").find(std::string(" ") + name + " ") !=
                                        std::string::npos;
}

#if defined(__SANITIZE_ADDRESS__)
// ASan builds only: Mesa's EGL and its llvmpipe driver keep a few allocations they never free, and
// unload the driver at eglTerminate, after which LeakSanitizer cannot name the module those leaks
// came from (the stack ends inside it) and no suppression can match them. Loading both first with
// RTLD_NODELETE keeps them mapped until exit, so tests/sanitizers/lsan.supp can name them.
void keepMesaLoadedForLeakChecks()
{
    static const bool loaded = [] {
        dlopen("libEGL_mesa.so.0", RTLD_NOW | RTLD_NODELETE);
        dlopen(VPLGI_MESA_DRI_DIR "/swrast_dri.so", RTLD_NOW | RTLD_NODELETE);
        return true;
    }();
    (void)loaded;
}
#else
void keepMesaLoadedForLeakChecks() {}
#endif

} // namespace

std::unique_ptr<Context> createHeadlessContext(const ContextOptions& options)
{
    keepMesaLoadedForLeakChecks();
    std::vector<std::string> failures;
    std::string failure;
    std::unique_ptr<Context> context;
    // VPLGI_EGL_PLATFORM=surfaceless|device|pbuffer restricts the search to one platform (tests use
    // it to exercise the fallbacks).
    const char* forced = std::getenv("VPLGI_EGL_PLATFORM");
    const std::string only = forced ? forced : "";
    require(only.empty() || only == "surfaceless" || only == "device" || only == "pbuffer",
            "VPLGI_EGL_PLATFORM must be surfaceless, device or pbuffer");
    auto allowed = [&](const char* name) { return only.empty() || only == name; };
    // eglGetPlatformDisplayEXT, not the EGL 1.5 entry point: libepoxy aborts on the latter before a
    // display exists (../shared/ENVIRONMENT.md).
    if (allowed("surfaceless") && hasClientExtension("EGL_MESA_platform_surfaceless")) {
        EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        context = tryDisplay(display, false, "EGL surfaceless", options, failure);
        if (!context) failures.push_back(failure);
    }
    if (!context && allowed("device") && hasClientExtension("EGL_EXT_platform_device")) {
        EGLDeviceEXT devices[8];
        EGLint count = 0;
        if (eglQueryDevicesEXT(8, devices, &count) == EGL_TRUE) {
            for (EGLint i = 0; i < count && !context; ++i) {
                EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
                context = tryDisplay(display, false, "EGL device", options, failure);
                if (!context) failures.push_back(failure);
            }
        }
    }
    if (!context && allowed("pbuffer")) {
        context = tryDisplay(eglGetDisplay(EGL_DEFAULT_DISPLAY), true, "EGL pbuffer", options, failure);
        if (!context) failures.push_back(failure);
    }
    if (!context) {
        std::string message = "no headless OpenGL 4.5 core context:";
        for (const std::string& f : failures) message += " [" + f + "]";
        throw Error(message + " (is Mesa installed? run ./scripts/deps)");
    }
    initializeCurrentContext(options);
    return context;
}

void initializeCurrentContext(const ContextOptions& options)
{
    int version = epoxy_gl_version();
    require(version >= 45, "OpenGL 4.5 core required, the context has " + std::to_string(version / 10) + "." +
                               std::to_string(version % 10) + " (" + rendererName() + ")");
    requireResourceLimits();
    if (options.debug) installDebugCallback(options.throwOnHighSeverity);
}

std::string rendererName()
{
    const GLubyte* name = glGetString(GL_RENDERER);
    return name ? reinterpret_cast<const char*>(name) : "unknown";
}

bool isSoftwareRenderer()
{
    std::string name = rendererName();
    return name.find("llvmpipe") != std::string::npos || name.find("softpipe") != std::string::npos ||
           name.find("lavapipe") != std::string::npos;
}

} // namespace vplgi::gl
