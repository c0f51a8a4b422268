#include "window.h"

#include <epoxy/gl.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "core/util/error.h"

namespace vplgi::gl {

namespace {

std::string gLastGlfwError;

void onGlfwError(int, const char* description)
{
    gLastGlfwError = description ? description : "unknown GLFW error";
}

} // namespace

Window::Window(const std::string& title, int width, int height, const ContextOptions& options)
{
    glfwSetErrorCallback(onGlfwError);
    require(glfwInit() == GLFW_TRUE, "GLFW: cannot initialise (" + gLastGlfwError + "); use --headless without a display");
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, options.debug ? GLFW_TRUE : GLFW_FALSE);
    mWindow = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!mWindow) {
        glfwTerminate();
        throw Error("GLFW: cannot create an OpenGL 4.5 core window (" + gLastGlfwError + ")");
    }
    glfwSetWindowUserPointer(mWindow, this);
    glfwSetKeyCallback(mWindow, [](GLFWwindow* w, int key, int, int action, int mods) {
        auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
        if (self->onKey) self->onKey(key, action, mods);
    });
    glfwSetScrollCallback(mWindow, [](GLFWwindow* w, double dx, double dy) {
        auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
        if (self->onScroll) self->onScroll(dx, dy);
    });
    makeCurrent();
    glfwSwapInterval(1);
    initializeCurrentContext(options);
}

Window::~Window()
{
    if (mWindow) glfwDestroyWindow(mWindow);
    glfwTerminate();
}

void Window::makeCurrent()
{
    glfwMakeContextCurrent(mWindow);
}

std::string Window::description() const
{
    return "GLFW window, " + rendererName();
}

bool Window::shouldClose() const
{
    return glfwWindowShouldClose(mWindow) == GLFW_TRUE;
}

void Window::requestClose()
{
    glfwSetWindowShouldClose(mWindow, GLFW_TRUE);
}

void Window::swapBuffers()
{
    glfwSwapBuffers(mWindow);
}

void Window::pollEvents()
{
    glfwPollEvents();
}

glm::ivec2 Window::framebufferSize() const
{
    int w = 0, h = 0;
    glfwGetFramebufferSize(mWindow, &w, &h);
    return {w, h};
}

glm::dvec2 Window::cursorPosition() const
{
    double x = 0.0, y = 0.0;
    glfwGetCursorPos(mWindow, &x, &y);
    return {x, y};
}

bool Window::isKeyDown(int glfwKey) const
{
    return glfwGetKey(mWindow, glfwKey) == GLFW_PRESS;
}

bool Window::isMouseButtonDown(int glfwButton) const
{
    return glfwGetMouseButton(mWindow, glfwButton) == GLFW_PRESS;
}

} // namespace vplgi::gl
