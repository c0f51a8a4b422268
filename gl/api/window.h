// A GLFW window with an OpenGL 4.5 core context (the interactive viewer). Never used headless:
// glfwInit fails without a display, so headless code paths must not construct a Window.
#pragma once

#include <functional>
#include <string>

#include <glm/glm.hpp>

#include "context.h"

struct GLFWwindow;

namespace vplgi::gl {

class Window final : public Context {
public:
    Window(const std::string& title, int width, int height, const ContextOptions& options = {});
    ~Window() override;
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    void makeCurrent() override;
    std::string description() const override;

    bool shouldClose() const;
    void requestClose();
    void swapBuffers();
    void pollEvents();
    glm::ivec2 framebufferSize() const;
    glm::dvec2 cursorPosition() const;
    bool isKeyDown(int glfwKey) const;
    bool isMouseButtonDown(int glfwButton) const;
    GLFWwindow* handle() const { return mWindow; }

    std::function<void(int key, int action, int mods)> onKey;
    std::function<void(double dx, double dy)> onScroll;

private:
    GLFWwindow* mWindow = nullptr;
};

} // namespace vplgi::gl
