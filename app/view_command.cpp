// `vplgi view`: the interactive viewer. WASD/QE move, right mouse button + drag looks around,
// scroll changes speed, F12 writes a screenshot (PNG, plus linear EXR with --exr), R reloads
// shaders, Esc quits.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "cli.h"
#include "commands.h"
#include "core/error.h"
#include "core/image_io.h"
#include "gl/api/window.h"
#include "session.h"

namespace vplgi {

namespace {

// First-person camera state derived from the scene camera.
struct FlyCamera {
    float yaw = 0.0f;   // radians, around +y
    float pitch = 0.0f; // radians
    float speed = 1.0f; // [m/s]

    void fromCamera(const Camera& c)
    {
        glm::vec3 f = glm::normalize(c.target - c.position);
        pitch = std::asin(glm::clamp(f.y, -1.0f, 1.0f));
        yaw = std::atan2(f.x, -f.z);
    }
    glm::vec3 forward() const
    {
        return {std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
    }
};

std::string nextScreenshotPath(const std::string& directory, const std::string& stem, const char* extension)
{
    for (int i = 0;; ++i) {
        char name[64];
        std::snprintf(name, sizeof name, "-%04d", i);
        std::filesystem::path p = std::filesystem::path(directory) / (stem + name + extension);
        if (!std::filesystem::exists(p)) return p.string();
    }
}

} // namespace

int runView(const std::vector<std::string>& args)
{
    OptionParser parser("vplgi view", "Opens a window on a scene. Keys: WASD/QE move, right mouse drag looks,\n"
                                      "scroll sets speed, F12 screenshot, R reload shaders, Esc quit.");
    addSessionOptions(parser);
    parser.value("width", "W", "window width in pixels", "960");
    parser.value("height", "H", "window height in pixels", "540");
    parser.value("screenshot-dir", "DIR", "where F12 writes screenshots", "screenshots");
    parser.flag("exr", "F12 also writes the linear radiance as EXR");
    if (!parser.parse(args)) return 0;
    const int width = parser.getInt("width", 1, 16384);
    const int height = parser.getInt("height", 1, 16384);
    const std::string screenshotDir = parser.get("screenshot-dir");
    const bool writeExr = parser.has("exr");
    std::unique_ptr<gl::Window> windowOwner; // declared first: destroyed after the session's GL objects
    Session session(sessionOptions(parser));
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    require((display && *display) || (wayland && *wayland),
            "no display (DISPLAY is not set): use 'vplgi render' for headless rendering");
    std::printf("%s", session.configuration().c_str());

    windowOwner = std::make_unique<gl::Window>("vplgi - " + session.scene().name + " - " + session.techniqueName(),
                                               width, height);
    gl::Window& window = *windowOwner;
    std::printf("context = %s\n", window.description().c_str());
    session.createRenderer();

    FlyCamera fly;
    fly.fromCamera(session.camera());
    AABB bounds = session.scene().worldBounds();
    fly.speed = bounds.empty() ? 1.0f : 0.25f * glm::length(bounds.extent());
    bool screenshotRequested = false, reloadRequested = false;
    window.onKey = [&](int key, int action, int) {
        if (action != GLFW_PRESS) return;
        if (key == GLFW_KEY_ESCAPE) window.requestClose();
        if (key == GLFW_KEY_F12) screenshotRequested = true;
        if (key == GLFW_KEY_R) reloadRequested = true;
    };
    window.onScroll = [&](double, double dy) { fly.speed *= std::pow(1.2f, static_cast<float>(dy)); };

    gl::Framebuffer displayFramebuffer("display (blit source)");
    glm::dvec2 lastCursor = window.cursorPosition();
    auto last = std::chrono::steady_clock::now();
    const auto start = last;
    double fpsAccumulator = 0.0;
    int fpsFrames = 0;
    while (!window.shouldClose()) {
        window.pollEvents();
        auto now = std::chrono::steady_clock::now();
        float dt = std::chrono::duration<float>(now - last).count();
        last = now;
        float time = std::chrono::duration<float>(now - start).count();

        // Camera controls.
        glm::dvec2 cursor = window.cursorPosition();
        if (window.isMouseButtonDown(GLFW_MOUSE_BUTTON_RIGHT)) {
            fly.yaw += 0.005f * static_cast<float>(cursor.x - lastCursor.x);
            fly.pitch = glm::clamp(fly.pitch - 0.005f * static_cast<float>(cursor.y - lastCursor.y), -1.55f, 1.55f);
        }
        lastCursor = cursor;
        Camera& camera = session.camera();
        glm::vec3 f = fly.forward();
        glm::vec3 right = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
        glm::vec3 move(0.0f);
        if (window.isKeyDown(GLFW_KEY_W)) move += f;
        if (window.isKeyDown(GLFW_KEY_S)) move -= f;
        if (window.isKeyDown(GLFW_KEY_D)) move += right;
        if (window.isKeyDown(GLFW_KEY_A)) move -= right;
        if (window.isKeyDown(GLFW_KEY_E)) move += glm::vec3(0, 1, 0);
        if (window.isKeyDown(GLFW_KEY_Q)) move -= glm::vec3(0, 1, 0);
        camera.position += move * (fly.speed * std::min(dt, 0.25f));
        camera.target = camera.position + f;
        camera.up = glm::vec3(0, 1, 0);

        if (reloadRequested) {
            reloadRequested = false;
            try {
                session.renderer().reloadShaders();
                std::printf("shaders reloaded\n");
            } catch (const Error& e) {
                std::fprintf(stderr, "shader reload failed, keeping the old shaders: %s\n", e.what());
            }
        }
        glm::ivec2 size = window.framebufferSize();
        if (size.x <= 0 || size.y <= 0) continue; // minimised
        session.renderer().renderFrame(camera, size.x, size.y, time);

        displayFramebuffer.attach(GL_COLOR_ATTACHMENT0, session.renderer().displayTexture());
        glBlitNamedFramebuffer(displayFramebuffer.id(), 0, 0, 0, size.x, size.y, 0, 0, size.x, size.y,
                               GL_COLOR_BUFFER_BIT, GL_NEAREST);
        if (screenshotRequested) {
            screenshotRequested = false;
            std::filesystem::create_directories(screenshotDir);
            std::string stem = "vplgi-" + session.scene().name;
            std::string png = nextScreenshotPath(screenshotDir, stem, ".png");
            writeImage(png, session.renderer().readDisplay());
            std::printf("screenshot %s\n", png.c_str());
            if (writeExr) {
                std::string exr = png.substr(0, png.size() - 4) + ".exr";
                writeImage(exr, session.renderer().readRadiance());
                std::printf("screenshot %s\n", exr.c_str());
            }
            std::fflush(stdout);
        }
        window.swapBuffers();

        fpsAccumulator += dt;
        ++fpsFrames;
        if (fpsAccumulator > 1.0) {
            char title[256];
            std::snprintf(title, sizeof title, "vplgi - %s - %s - %.1f fps (%.1f ms)", session.scene().name.c_str(),
                          session.techniqueName().c_str(), fpsFrames / fpsAccumulator,
                          session.renderer().timer().total());
            glfwSetWindowTitle(window.handle(), title);
            fpsAccumulator = 0.0;
            fpsFrames = 0;
        }
    }
    return 0;
}

} // namespace vplgi
