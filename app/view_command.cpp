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
#include "core/util/error.h"
#include "core/util/image_io.h"
#include "gl/api/objects.h"
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

struct ViewOptions {
    SessionOptions session;
    ImageSize size;             // the window's at start
    std::string screenshotDir;
    bool writeExr = false;      // F12 also writes the linear radiance
};

// The viewer's parts: window and session setup (constructor), input (key callbacks, camera
// controls), the frame loop, the screenshot.
class Viewer {
public:
    explicit Viewer(const ViewOptions& options);
    void run();

private:
    void installKeyHandlers();
    void moveCamera(float dt); // right mouse drag looks, WASD/QE move
    void reloadShadersIfRequested();
    void present(glm::ivec2 size);
    void writeScreenshot();
    void updateTitle(float dt);

    ViewOptions mOptions;
    std::unique_ptr<gl::Window> mWindow; // declared first: destroyed after the session's GL objects
    Session mSession;
    std::unique_ptr<gl::Framebuffer> mDisplayFramebuffer;
    FlyCamera mFly;
    glm::dvec2 mLastCursor{0.0};
    bool mScreenshotRequested = false;
    bool mReloadRequested = false;
    double mFpsAccumulator = 0.0;
    int mFpsFrames = 0;
};

Viewer::Viewer(const ViewOptions& options) : mOptions(options), mSession(options.session)
{
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    require((display && *display) || (wayland && *wayland),
            "no display (DISPLAY is not set): use 'vplgi render' for headless rendering");
    std::printf("%s", mSession.configuration().c_str());

    mWindow = std::make_unique<gl::Window>("vplgi - " + mSession.scene().name + " - " + mSession.techniqueName(),
                                           options.size.width, options.size.height);
    std::printf("context = %s\n", mWindow->description().c_str());
    mSession.createRenderer();
    mDisplayFramebuffer = std::make_unique<gl::Framebuffer>("display (blit source)");

    mFly.fromCamera(mSession.camera());
    AABB bounds = mSession.scene().worldBounds();
    mFly.speed = bounds.empty() ? 1.0f : 0.25f * glm::length(bounds.extent());
    installKeyHandlers();
    mLastCursor = mWindow->cursorPosition();
}

void Viewer::installKeyHandlers()
{
    mWindow->onKey = [this](int key, int action, int) {
        if (action != GLFW_PRESS) return;
        if (key == GLFW_KEY_ESCAPE) mWindow->requestClose();
        if (key == GLFW_KEY_F12) mScreenshotRequested = true;
        if (key == GLFW_KEY_R) mReloadRequested = true;
    };
    mWindow->onScroll = [this](double, double dy) { mFly.speed *= std::pow(1.2f, static_cast<float>(dy)); };
}

void Viewer::run()
{
    gl::Window& window = *mWindow;
    auto last = std::chrono::steady_clock::now();
    const auto start = last;
    while (!window.shouldClose()) {
        window.pollEvents();
        auto now = std::chrono::steady_clock::now();
        float dt = std::chrono::duration<float>(now - last).count();
        last = now;
        float time = std::chrono::duration<float>(now - start).count();

        moveCamera(dt);
        reloadShadersIfRequested();
        glm::ivec2 size = window.framebufferSize();
        if (size.x <= 0 || size.y <= 0) continue; // minimised
        mSession.renderer().renderFrame(mSession.camera(), size.x, size.y, time);
        present(size);
        if (mScreenshotRequested) {
            mScreenshotRequested = false;
            writeScreenshot();
        }
        window.swapBuffers();
        updateTitle(dt);
    }
}

void Viewer::moveCamera(float dt)
{
    gl::Window& window = *mWindow;
    glm::dvec2 cursor = window.cursorPosition();
    if (window.isMouseButtonDown(GLFW_MOUSE_BUTTON_RIGHT)) {
        mFly.yaw += 0.005f * static_cast<float>(cursor.x - mLastCursor.x);
        mFly.pitch = glm::clamp(mFly.pitch - 0.005f * static_cast<float>(cursor.y - mLastCursor.y), -1.55f, 1.55f);
    }
    mLastCursor = cursor;
    Camera& camera = mSession.camera();
    glm::vec3 f = mFly.forward();
    glm::vec3 right = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
    glm::vec3 move(0.0f);
    if (window.isKeyDown(GLFW_KEY_W)) move += f;
    if (window.isKeyDown(GLFW_KEY_S)) move -= f;
    if (window.isKeyDown(GLFW_KEY_D)) move += right;
    if (window.isKeyDown(GLFW_KEY_A)) move -= right;
    if (window.isKeyDown(GLFW_KEY_E)) move += glm::vec3(0, 1, 0);
    if (window.isKeyDown(GLFW_KEY_Q)) move -= glm::vec3(0, 1, 0);
    camera.position += move * (mFly.speed * std::min(dt, 0.25f));
    camera.target = camera.position + f;
    camera.up = glm::vec3(0, 1, 0);
}

void Viewer::reloadShadersIfRequested()
{
    if (!mReloadRequested) return;
    mReloadRequested = false;
    try {
        mSession.renderer().reloadShaders();
        std::printf("shaders reloaded\n");
    } catch (const Error& e) {
        std::fprintf(stderr, "shader reload failed, keeping the old shaders: %s\n", e.what());
    }
}

void Viewer::present(glm::ivec2 size)
{
    mDisplayFramebuffer->attach(GL_COLOR_ATTACHMENT0, mSession.renderer().displayTexture());
    glBlitNamedFramebuffer(mDisplayFramebuffer->id(), 0, 0, 0, size.x, size.y, 0, 0, size.x, size.y,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

void Viewer::writeScreenshot()
{
    std::filesystem::create_directories(mOptions.screenshotDir);
    std::string stem = "vplgi-" + mSession.scene().name;
    std::string png = nextScreenshotPath(mOptions.screenshotDir, stem, ".png");
    writeImage(png, mSession.renderer().readDisplay());
    std::printf("screenshot %s\n", png.c_str());
    if (mOptions.writeExr) {
        std::string exr = png.substr(0, png.size() - 4) + ".exr";
        writeImage(exr, mSession.renderer().readRadiance());
        std::printf("screenshot %s\n", exr.c_str());
    }
    std::fflush(stdout);
}

void Viewer::updateTitle(float dt)
{
    mFpsAccumulator += dt;
    ++mFpsFrames;
    if (mFpsAccumulator <= 1.0) return;
    char title[256];
    std::snprintf(title, sizeof title, "vplgi - %s - %s - %.1f fps (%.1f ms)", mSession.scene().name.c_str(),
                  mSession.techniqueName().c_str(), mFpsFrames / mFpsAccumulator, mSession.renderer().timer().total());
    glfwSetWindowTitle(mWindow->handle(), title);
    mFpsAccumulator = 0.0;
    mFpsFrames = 0;
}

} // namespace

int runView(const std::vector<std::string>& args)
{
    OptionParser parser("vplgi view", "Opens a window on a scene. Keys: WASD/QE move, right mouse drag looks,\n"
                                      "scroll sets speed, F12 screenshot, R reload shaders, Esc quit.");
    addSessionOptions(parser);
    addSizeOptions(parser, "window", 960, 540);
    parser.value("screenshot-dir", "DIR", "where F12 writes screenshots", "screenshots");
    parser.flag("exr", "F12 also writes the linear radiance as EXR");
    if (!parser.parse(args)) return 0;
    ViewOptions options;
    options.size = imageSize(parser, 1, 16384);
    options.screenshotDir = parser.get("screenshot-dir");
    options.writeExr = parser.has("exr");
    options.session = sessionOptions(parser);
    Viewer viewer(options);
    viewer.run();
    return 0;
}

} // namespace vplgi
