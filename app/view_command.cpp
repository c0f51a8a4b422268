// `vplgi view`: the interactive viewer. A Dear ImGui panel over the one parameter list
// (Renderer::visitParams: renderer, passes, technique), live technique switching, per-pass timings
// with a frame-time graph, debug views with a picture-in-picture, camera path recording and scene
// animation playback at a fixed frame step, light dragging and the sun's angles, screenshots (PNG of
// what is shown + the linear frame as EXR), hot shader reload, and a frame-timed --script for tests.
// F1 lists the keys (kKeys below: the help overlay, --help and the README say the same).
#include <epoxy/gl.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "camera_path.h"
#include "cli.h"
#include "commands.h"
#include "core/util/error.h"
#include "core/util/image_io.h"
#include "gl/api/context.h"
#include "gl/api/objects.h"
#include "gl/api/window.h"
#include "param_panel.h"
#include "render_scale.h"
#include "report.h"
#include "session.h"
#include "video_writer.h"
#include "view_script.h"

namespace vplgi {

namespace {

constexpr const char* kKeys[][2] = {
    {"W A S D / Q E", "move / down, up"},
    {"right mouse drag", "look around"},
    {"scroll", "movement speed"},
    {"middle mouse drag", "move the selected light in the view plane"},
    {"0 .. 9", "display view: 0 final, 1.. the views of renderer.display in order"},
    {"F1", "this help"},
    {"F2", "show / hide the panel"},
    {"F12", "screenshot: PNG of what is shown (+ EXR of the linear frame)"},
    {"R", "reload shaders (the old ones stay when compiling fails)"},
    {"P", "play / pause the scene's animations (fixed step 1/fps per frame)"},
    {"C", "start / stop recording the camera path (saved as a scene file)"},
    {"M", "start / stop recording a video of what is shown, without the panel (.mp4 in the screenshot directory)"},
    {"V", "vsync on / off"},
    {"Esc", "quit"},
};

constexpr int kHistory = 300; // frames in the frame-time graph

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

// The newest modification time of the files under `directory` (hot reload's file watch).
std::filesystem::file_time_type newestFileTime(const std::string& directory)
{
    std::filesystem::file_time_type newest{};
    std::error_code ec;
    for (auto it = std::filesystem::recursive_directory_iterator(directory, ec);
         !ec && it != std::filesystem::recursive_directory_iterator(); it.increment(ec)) {
        if (it->is_regular_file(ec)) newest = std::max(newest, it->last_write_time(ec));
    }
    return newest;
}

struct ViewOptions {
    SessionOptions session;
    ImageSize size; // the window's at start
    std::string screenshotDir;
    std::string recordPath;      // where C writes the recorded camera path
    std::string scriptPath;      // --script
    std::string dumpPanelParams; // --dump-panel-params FILE: the panel's keys after the first frame, then quit
    std::string statsPath;       // --stats FILE: frame, ms, internal size per frame, written at the end
    RenderScale renderScale;     // the --set viewer.* keys
    float fps = 30.0f;           // animation playback and recording: 1/fps per frame
    bool play = false;           // start with the animations playing
    bool panel = true;
    bool watchShaders = false;
};

// The viewer's parts: window, ImGui and session setup (constructor), input (keys, camera, light
// drag), the script, the frame loop, the panel, screenshots.
class Viewer {
public:
    explicit Viewer(const ViewOptions& options);
    ~Viewer();
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;
    void run();

private:
    // Input.
    void installKeyHandlers();
    void handleKey(int key);
    void moveCamera(float dt); // right mouse drag looks, WASD/QE move
    void dragLight();          // middle mouse drag moves the selected light in the view plane
    // State changes between frames.
    void runScript();
    void runScriptCommand(const ScriptCommand& command);
    void switchTechnique(const std::string& name);
    void applySettings(const Settings& settings);
    void applySoftwareDefaults(); // after each createRenderer on a software rasterizer
    void selectView(int index);
    void reloadShaders();
    void watchShaders();
    void toggleRecording(const std::string& path);
    void togglePlayback();
    void toggleVideo(const std::string& path); // path "": the next free name in the screenshot directory
    void recordVideoFrame(glm::ivec2 size);
    // The frame.
    void renderScene(glm::ivec2 size);
    void present(glm::ivec2 size);
    void drawUi(glm::ivec2 size);
    void renderImGui(glm::ivec2 size); // the ImGui draw data into the window's back buffer
    void drawPanel(glm::ivec2 size);
    void drawTimings();
    void drawRenderScale(glm::ivec2 size);
    void drawLights();
    void drawCameraSection();
    void drawHelp();
    void drawProgress(const std::string& task, int done, int total); // a whole frame (ProgressSink)
    void writeScreenshot(const std::string& path);
    ImageRGBA8 readWindow(glm::ivec2 size) const;
    void dumpPanelParams(const std::string& path) const;
    Settings defaultSettings();
    std::string setArguments();

    ViewOptions mOptions;
    RenderScale mScale;
    Settings mSoftwareDefaults;         // the lighter defaults in use (shown in the panel)
    std::set<std::string> mUserKeys;    // keys the user set (--set, panel, script): defaults leave them
    std::ostringstream mStats;          // --stats rows
    std::unique_ptr<gl::Window> mWindow; // declared first: destroyed after the session's GL objects
    std::unique_ptr<Session> mSession;
    std::unique_ptr<gl::Framebuffer> mBlitSource;
    std::optional<ViewScript> mScript;
    FlyCamera mFly;
    glm::dvec2 mLastCursor{0.0};
    glm::dvec2 mLastDragCursor{0.0};
    ParamPanel mPanel;
    CameraPathRecorder mRecorder;
    std::unique_ptr<VideoWriter> mVideo; // while M records
    std::chrono::steady_clock::time_point mStart;

    // UI state.
    bool mShowPanel = true;
    bool mShowHelp = false;
    bool mScreenshotWithPanel = true;
    bool mScreenshotExr = true;
    bool mVsync = true;
    bool mWatchShaders = false;
    bool mPlaying = false;
    std::string mInsetView; // picture-in-picture view; empty: none
    std::string mMessage;   // last error or notice, shown in the panel
    bool mMessageIsError = false;
    std::string mShaderError; // the failed reload's message until a reload succeeds
    std::string mPendingTechnique;
    std::string mPendingScreenshot; // path; "" none
    bool mScreenshotRequested = false;
    bool mReloadRequested = false;
    int mSelectedLight = 0;
    float mUiScale = 1.0f;

    // Clocks and history.
    int mFrame = 0;              // frames rendered (the script's clock)
    float mAnimationTime = 0.0f; // advances 1/fps per frame while playing
    float mRecordTime = 0.0f;    // the recorder's clock: wall clock, or 1/fps per frame with a script
    std::vector<float> mFrameMs; // wall-clock frame times, ring of kHistory
    std::vector<float> mGpuMs;   // PassTimer totals, ring of kHistory
    int mHistoryNext = 0;
    double mLastShaderCheck = 0.0;
    std::filesystem::file_time_type mShaderTime{};
    bool mInProgressFrame = false;
};

Viewer::Viewer(const ViewOptions& options)
    : mOptions(options), mScale(options.renderScale), mShowPanel(options.panel || !options.dumpPanelParams.empty()),
      mWatchShaders(options.watchShaders), mPlaying(options.play), mFrameMs(kHistory, 0.0f), mGpuMs(kHistory, 0.0f)
{
    // Everything about the input is checked before a window opens.
    if (!options.scriptPath.empty()) mScript = ViewScript::load(options.scriptPath);
    mSession = std::make_unique<Session>(options.session);
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    require((display && *display) || (wayland && *wayland),
            "no display (DISPLAY is not set): use 'vplgi render' for headless rendering");
    std::printf("%s", mSession->configuration().c_str());

    mWindow = std::make_unique<gl::Window>("vplgi - " + mSession->scene().name + " - " + mSession->techniqueName(),
                                           options.size.width, options.size.height);
    std::printf("context = %s\n", mWindow->description().c_str());
    mScale.setSoftware(gl::isSoftwareRenderer());
    for (const auto& setting : options.session.settings)
        mUserKeys.insert(setting.first);

    // Dear ImGui after the window's own callbacks: its GLFW backend chains to them.
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini beside wherever the viewer was started
    float xscale = 1.0f, yscale = 1.0f;
    glfwGetWindowContentScale(mWindow->handle(), &xscale, &yscale);
    mUiScale = std::clamp(std::max(xscale, yscale), 1.0f, 4.0f); // HiDPI: fonts and sizes scale together
    ImFontConfig font;
    font.SizePixels = std::round(13.0f * mUiScale);
    io.Fonts->AddFontDefault(&font);
    ImGui::StyleColorsDark();
    ImGui::GetStyle().ScaleAllSizes(mUiScale);
    ImGui::GetStyle().Colors[ImGuiCol_WindowBg].w = 0.85f;
    require(ImGui_ImplGlfw_InitForOpenGL(mWindow->handle(), true), "Dear ImGui: cannot initialise its GLFW backend");
    require(ImGui_ImplOpenGL3_Init("#version 450"), "Dear ImGui: cannot initialise its OpenGL 3 backend");

    mSession->createRenderer([this](const std::string& task, int done, int total) { drawProgress(task, done, total); });
    applySoftwareDefaults();
    mBlitSource = std::make_unique<gl::Framebuffer>("display (blit source)");

    mFly.fromCamera(mSession->camera());
    AABB bounds = mSession->scene().worldBounds();
    mFly.speed = bounds.empty() ? 1.0f : 0.25f * glm::length(bounds.extent());
    installKeyHandlers();
    mLastCursor = mWindow->cursorPosition();
    mShaderTime = newestFileTime(gl::ShaderLoader::defaultDirectory());
}

Viewer::~Viewer()
{
    mVideo.reset();   // only after an error: run() finishes a video still recording when the window closes
    mSession.reset(); // GL objects before the ImGui backend and the window
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

void Viewer::installKeyHandlers()
{
    mWindow->onKey = [this](int key, int action, int) {
        if (action != GLFW_PRESS) return;
        if (ImGui::GetIO().WantCaptureKeyboard) return; // typing into a field
        try {                                           // never through GLFW's C callback
            handleKey(key);
        } catch (const std::exception& e) {
            mMessage = e.what();
            mMessageIsError = true;
        }
    };
    mWindow->onScroll = [this](double, double dy) {
        if (ImGui::GetIO().WantCaptureMouse) return;
        mFly.speed *= std::pow(1.2f, static_cast<float>(dy));
    };
}

void Viewer::handleKey(int key)
{
    if (key == GLFW_KEY_ESCAPE)
        mWindow->requestClose();
    else if (key == GLFW_KEY_F1)
        mShowHelp = !mShowHelp;
    else if (key == GLFW_KEY_F2)
        mShowPanel = !mShowPanel;
    else if (key == GLFW_KEY_F12)
        mScreenshotRequested = true;
    else if (key == GLFW_KEY_R)
        mReloadRequested = true;
    else if (key == GLFW_KEY_P)
        togglePlayback();
    else if (key == GLFW_KEY_C)
        toggleRecording(mOptions.recordPath);
    else if (key == GLFW_KEY_M)
        toggleVideo("");
    else if (key == GLFW_KEY_V) {
        mVsync = !mVsync;
        glfwSwapInterval(mVsync ? 1 : 0);
    } else if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9)
        selectView(key - GLFW_KEY_0);
}

void Viewer::selectView(int index)
{
    const std::vector<std::string> names = displayViewNames(mSession->renderer().technique().debugViews());
    if (index < 0 || index >= static_cast<int>(names.size())) return;
    applySettings({{"renderer.display", names[static_cast<std::size_t>(index)]}});
}

void Viewer::togglePlayback()
{
    mPlaying = !mPlaying;
    if (mPlaying && mSession->scene().animations.empty()) {
        mMessage = "the scene has no animations to play";
        mMessageIsError = false;
        mPlaying = false;
    }
}

void Viewer::toggleRecording(const std::string& path)
{
    if (!mRecorder.recording()) {
        mRecorder.start();
        mMessage = "recording the camera path (C stops and writes " + path + ")";
        mMessageIsError = false;
        return;
    }
    mRecorder.stop();
    mRecorder.write(path, mOptions.session.sceneSpec, mSession->cameraName());
    mMessage = "camera path: " + std::to_string(mRecorder.keyCount()) + " keys written to " + path +
               " (replay: vplgi view --scene " + path + " --play)";
    mMessageIsError = false;
    std::printf("%s\n", mMessage.c_str());
    std::fflush(stdout);
}

void Viewer::toggleVideo(const std::string& path)
{
    if (!mVideo) {
        std::string file = path;
        if (file.empty()) {
            std::filesystem::create_directories(mOptions.screenshotDir);
            file = nextScreenshotPath(mOptions.screenshotDir, "vplgi-" + mSession->scene().name, ".mp4");
        }
        const glm::ivec2 size = mWindow->framebufferSize();
        mVideo = std::make_unique<VideoWriter>(file, size.x, size.y, mOptions.fps);
        mMessage = "recording a video to " + file + " (M stops)";
        mMessageIsError = false;
        return;
    }
    const std::unique_ptr<VideoWriter> video = std::move(mVideo);
    video->finish();
    char message[512];
    std::snprintf(message, sizeof message, "video: %d frames at %g fps written to %s", video->frames(),
                  static_cast<double>(mOptions.fps), video->path().c_str());
    mMessage = message;
    mMessageIsError = false;
    std::printf("%s\n", message);
    std::fflush(stdout);
}

// One video frame per frame shown (the real-time frames are not resampled: a video at --fps plays
// them at that rate), read from the window before the panel is drawn.
void Viewer::recordVideoFrame(glm::ivec2 size)
{
    if (!mVideo) return;
    if (size.x != mVideo->width() || size.y != mVideo->height()) {
        toggleVideo(""); // a video has one size: a resized window ends it
        mMessage += " (the window was resized)";
        return;
    }
    mVideo->add(readWindow(size));
}

void Viewer::applySettings(const Settings& settings)
{
    // Unknown keys and bad values throw: a script stops with the error, the panel shows it. The
    // viewer's own keys (viewer.*) go to the render scale.
    Settings rest = settings;
    mScale.take(rest);
    for (const auto& setting : settings)
        mUserKeys.insert(setting.first);
    if (rest.empty()) return;
    mSession->renderer().applySettings(rest);
}

// The viewer's lighter defaults on a software rasterizer (issue 28 part 5), for the keys this
// technique has and the user did not set; measured with scripts/viewer-frame-times (README "The
// viewer without a GPU"). Not in the papers: their budgets stay the defaults everywhere else.
void Viewer::applySoftwareDefaults()
{
    mSoftwareDefaults.clear();
    if (!gl::isSoftwareRenderer()) return;
    struct Lighter {
        const char* technique;
        const char* key;
        const char* value;
    };
    // On cornell at 320 x 180 (2 cores, `render` per-pass times): vsgl 2.0 s -> 0.34 s a frame, of it
    // the BRSM PDF 0.72 s -> 0.05 s (RSM texels x view lights) and the radiance estimation 1.01 s ->
    // 0.23 s (pixels x lights); vpl-brsm 1.9 s -> 0.32 s. lightskin on canyon 0.80 s -> 0.44 s
    // (`bench`: importance 69 -> 18 ms with rsm 128, proxy lights 142 -> 107 ms and occlusion 82 -> 52 ms
    // with 1797 caches instead of 2410; its interpolation, about 0.24 s, does not shrink with the budget).
    static const Lighter kLighter[] = {
        {"smcir", "smcir.mapsPerFrame", "64"}, // the shadow maps' first build spread over frames
        {"ir", "ir.mapsPerFrame", "64"},
        {"mir", "mir.mapsPerFrame", "64"},
        {"mir", "mir.resamplingRate", "64"}, // 128 k light-path candidates instead of 512 k (the paper: 256:1)
        {"lightskin", "rsm.size", "128"}, // LightSkin's 1024^2 RSM (its VALs): 64x fewer texels
        {"lightskin", "lightskin.valCount", "512"}, // proxy lights: 4x fewer VALs per cache (the paper: 2048)
        {"lightskin", "lightskin.cacheTarget", "768"}, // canyon: 1797 caches instead of 4050
        {"lightskin-full", "rsm.size", "64"}, // every VAL lights every cache: 4096 of them
        {"vsgl", "rsm.size", "128"},      // the BRSM's texels, 4x fewer
        {"vsgl", "vsgl.count", "256"},    // lights per pixel, 4x fewer (the paper: 1024)
        {"vsgl", "vsgl.viewLevel", "3"},  // the PDF's view lights, 8 x 8 instead of 16 x 16
        {"vpl-brsm", "rsm.size", "128"},
        {"vpl-brsm", "vpl-brsm.count", "256"},
        {"vpl-brsm", "vpl-brsm.viewLevel", "3"},
        {"tcas", "rsm.size", "128"}, // tcas: vpl-brsm's passes with chains instead of draws
        {"tcas", "tcas.count", "256"},
        {"tcas", "tcas.viewLevel", "3"},
    };
    ParamDumper current;
    mSession->renderer().visitParams(current);
    const std::string technique = mSession->techniqueName();
    for (const Lighter& l : kLighter)
        if (technique == l.technique && current.values().count(l.key) && !mUserKeys.count(l.key))
            mSoftwareDefaults.emplace_back(l.key, l.value);
    if (mSoftwareDefaults.empty()) return;
    mSession->renderer().applySettings(mSoftwareDefaults);
    std::printf("software rasterizer: lighter defaults:");
    for (const auto& [key, value] : mSoftwareDefaults)
        std::printf(" %s=%s", key.c_str(), value.c_str());
    std::printf(" (--set KEY=VALUE overrides)\n");
    std::fflush(stdout);
}

void Viewer::switchTechnique(const std::string& name)
{
    // The renderer's own fields carry over (exposure, shadow.*, lights.*), and any other key both
    // techniques have (rsm.*); a debug view only the old technique has falls back to final.
    Renderer& old = mSession->renderer();
    ParamDumper current;
    old.visitParams(current);
    const std::vector<std::string> views = displayViewNames(createTechnique(name)->debugViews());
    SessionOptions options = mOptions.session;
    options.technique = name;
    options.rejectUnknownSettings = false;
    options.settings.clear();
    for (const auto& [key, value] : current.values()) {
        if (key == "renderer.display" && std::find(views.begin(), views.end(), value) == views.end()) continue;
        options.settings.emplace_back(key, value);
    }
    auto next = std::make_unique<Session>(options);  // CPU only: a bad scene throws before anything changes
    next->scene().lights = mSession->scene().lights; // moved lights stay where they are
    next->camera() = mSession->camera();
    mSession.reset();
    mSession = std::move(next);
    mSession->createRenderer([this](const std::string& task, int done, int total) { drawProgress(task, done, total); });
    applySoftwareDefaults();
    glfwSetWindowTitle(mWindow->handle(),
                       ("vplgi - " + mSession->scene().name + " - " + mSession->techniqueName()).c_str());
    std::printf("technique = %s\n", name.c_str());
    std::fflush(stdout);
}

void Viewer::runScript()
{
    if (!mScript) return;
    for (const ScriptCommand& command : mScript->due(mFrame)) {
        try {
            runScriptCommand(command);
        } catch (const std::exception& e) {
            throw Error(mScript->where(command) + ": " + command.name + ": " + e.what());
        }
    }
}

void Viewer::runScriptCommand(const ScriptCommand& c)
{
    const std::vector<std::string>& a = c.args;
    if (c.name == "set") {
        Settings settings;
        for (const std::string& s : a)
            settings.push_back(parseSetting(s));
        applySettings(settings);
    } else if (c.name == "technique") {
        switchTechnique(a[0]);
    } else if (c.name == "display") {
        applySettings({{"renderer.display", a[0]}});
    } else if (c.name == "pip") {
        if (a[0] == "off")
            mInsetView.clear();
        else {
            const std::vector<std::string> names = displayViewNames(mSession->renderer().technique().debugViews());
            require(std::find(names.begin(), names.end(), a[0]) != names.end(), "no display view \"" + a[0] + "\"");
            mInsetView = a[0];
        }
    } else if (c.name == "panel") {
        mShowPanel = a[0] == "on";
    } else if (c.name == "screenshot-panel") {
        mScreenshotWithPanel = a[0] == "on";
    } else if (c.name == "screenshot") {
        mScreenshotRequested = true;
        mPendingScreenshot = a.empty() ? "" : a[0];
    } else if (c.name == "key") {
        handleKey(scriptKeyCode(a[0]));
    } else if (c.name == "dump-params") {
        require(mShowPanel && mFrame > 0, "the panel has not been drawn yet (panel on, and at a frame after 0)");
        dumpPanelParams(a[0]);
    } else if (c.name == "camera") {
        Camera& camera = mSession->camera();
        camera.position = glm::vec3(std::stof(a[0]), std::stof(a[1]), std::stof(a[2]));
        camera.target = glm::vec3(std::stof(a[3]), std::stof(a[4]), std::stof(a[5]));
        require(glm::length(camera.target - camera.position) > 0.0f, "the eye and the target must differ");
        mFly.fromCamera(camera);
    } else if (c.name == "record") {
        if (a[0] == "start" && !mRecorder.recording())
            toggleRecording("");
        else if (a[0] == "stop") {
            require(mRecorder.recording(), "record stop: not recording");
            toggleRecording(a[1]);
        }
    } else if (c.name == "video") {
        require((a[0] == "start") != static_cast<bool>(mVideo),
                a[0] == "start" ? "video start: already recording" : "video stop: not recording");
        toggleVideo(a.size() > 1 ? a[1] : "");
    } else if (c.name == "play") {
        if ((a[0] == "on") != mPlaying) togglePlayback();
        require(mPlaying == (a[0] == "on"), "play on: the scene has no animations");
    } else if (c.name == "reload") {
        mReloadRequested = true;
    } else if (c.name == "wait-file") {
        const auto start = std::chrono::steady_clock::now();
        while (!std::filesystem::exists(a[0])) {
            require(std::chrono::steady_clock::now() - start < std::chrono::seconds(120),
                    a[0] + " did not appear within 120 s");
            glfwWaitEventsTimeout(0.05);
        }
    } else if (c.name == "vsync") {
        mVsync = a[0] == "on";
        glfwSwapInterval(mVsync ? 1 : 0);
    } else if (c.name == "resize") {
        glfwSetWindowSize(mWindow->handle(), std::atoi(a[0].c_str()), std::atoi(a[1].c_str()));
    } else if (c.name == "quit") {
        mWindow->requestClose();
    }
}

void Viewer::dumpPanelParams(const std::string& path) const
{
    std::string text;
    for (const std::string& key : mPanel.keys())
        text += key + "\n";
    writeTextFile(path, text); // a temporary renamed into place: never half a list
}

void Viewer::run()
{
    gl::Window& window = *mWindow;
    mStart = std::chrono::steady_clock::now();
    auto last = mStart;
    const bool scripted = mScript.has_value();
    while (!window.shouldClose()) {
        window.pollEvents();
        runScript(); // a script's quit still renders this frame (its screenshots), then ends
        if (!mPendingTechnique.empty()) {
            const std::string name = mPendingTechnique;
            mPendingTechnique.clear();
            try {
                switchTechnique(name);
            } catch (const Error& e) {
                mMessage = e.what();
                mMessageIsError = true;
            }
        }
        auto now = std::chrono::steady_clock::now();
        const float dt = std::chrono::duration<float>(now - last).count();
        last = now;
        const double seconds = std::chrono::duration<double>(now - mStart).count();

        if (mPlaying) {
            // Fixed step per frame, as `vplgi render` and `vplgi compare` advance animations (--fps).
            mSession->applyAnimations(mAnimationTime);
            mAnimationTime += 1.0f / mOptions.fps;
            mFly.fromCamera(mSession->camera());
        } else {
            moveCamera(dt);
        }
        dragLight();
        reloadShaders();
        if (mWatchShaders && seconds - mLastShaderCheck > 0.5) {
            mLastShaderCheck = seconds;
            watchShaders();
        }
        glm::ivec2 size = window.framebufferSize();
        if (size.x <= 0 || size.y <= 0) { // minimised
            glfwWaitEventsTimeout(0.1);
            continue;
        }
        const auto frameStart = std::chrono::steady_clock::now();
        const glm::ivec2 internal = mScale.internalSize(size);
        renderScene(size);
        present(size);
        recordVideoFrame(size);
        const bool screenshot = mScreenshotRequested;
        mScreenshotRequested = false;
        if (screenshot && !mScreenshotWithPanel) writeScreenshot(mPendingScreenshot);
        drawUi(size);
        if (screenshot && mScreenshotWithPanel) writeScreenshot(mPendingScreenshot);
        if (screenshot) mPendingScreenshot.clear();
        window.swapBuffers();
        if (mScale.adapting() || !mOptions.statsPath.empty()) glFinish(); // the frame's whole cost
        const double frameMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frameStart).count();
        if (!mOptions.statsPath.empty()) mStats << mFrame << ',' << frameMs << ',' << internal.x << ',' << internal.y << '\n';
        mScale.adapt(frameMs, size);

        if (!mOptions.dumpPanelParams.empty()) { // the panel's keys of the first frame, then quit
            dumpPanelParams(mOptions.dumpPanelParams);
            window.requestClose();
        }
        mRecordTime = scripted ? static_cast<float>(mFrame + 1) / mOptions.fps : static_cast<float>(seconds);
        mRecorder.add(mRecordTime, mSession->camera(), 1.0f / mOptions.fps);
        mFrameMs[static_cast<std::size_t>(mHistoryNext)] = 1000.0f * dt;
        mGpuMs[static_cast<std::size_t>(mHistoryNext)] = static_cast<float>(mSession->renderer().timer().total());
        mHistoryNext = (mHistoryNext + 1) % kHistory;
        ++mFrame;
    }
    if (mVideo) toggleVideo(""); // Esc or a script's quit while recording: the video is kept
    if (!mOptions.statsPath.empty()) writeTextFile(mOptions.statsPath, "frame,ms,internal_width,internal_height\n" + mStats.str());
}

void Viewer::renderScene(glm::ivec2 size)
{
    const float time = mPlaying ? mAnimationTime : 0.0f;
    const glm::ivec2 internal = mScale.internalSize(size);
    try {
        mSession->renderer().renderFrame(mSession->camera(), internal.x, internal.y, time);
    } catch (const Error& e) {
        // A view that cannot be shown (renderer.displayLayer past its layers): back to the final
        // image with the message in the panel, instead of an error every frame.
        if (mScript) throw;
        mMessage = e.what();
        mMessageIsError = true;
        mSession->renderer().applySettings({{"renderer.display", "final"}, {"renderer.displayLayer", "-1"}});
        mSession->renderer().renderFrame(mSession->camera(), internal.x, internal.y, time);
    }
}

void Viewer::present(glm::ivec2 size)
{
    // The internal size upscaled to the window (bilinear; 1:1 at scale 1).
    const glm::ivec2 internal = mScale.internalSize(size);
    mBlitSource->attach(GL_COLOR_ATTACHMENT0, mSession->renderer().displayTexture());
    glBlitNamedFramebuffer(mBlitSource->id(), 0, 0, 0, internal.x, internal.y, 0, 0, size.x, size.y,
                           GL_COLOR_BUFFER_BIT, internal == size ? GL_NEAREST : GL_LINEAR);
    if (mInsetView.empty()) return;
    // Picture-in-picture: a quarter-size copy of the chosen view in the bottom right corner.
    const gl::Texture& inset = mSession->renderer().renderInset(mInsetView);
    mBlitSource->attach(GL_COLOR_ATTACHMENT0, inset);
    const int w = size.x / 4, h = size.y / 4, margin = static_cast<int>(8 * mUiScale);
    glBlitNamedFramebuffer(mBlitSource->id(), 0, 0, 0, internal.x, internal.y, size.x - w - margin, margin, size.x - margin,
                           margin + h, GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

void Viewer::moveCamera(float dt)
{
    gl::Window& window = *mWindow;
    glm::dvec2 cursor = window.cursorPosition();
    const ImGuiIO& io = ImGui::GetIO();
    if (window.isMouseButtonDown(GLFW_MOUSE_BUTTON_RIGHT) && !io.WantCaptureMouse) {
        mFly.yaw += 0.005f * static_cast<float>(cursor.x - mLastCursor.x);
        mFly.pitch = glm::clamp(mFly.pitch - 0.005f * static_cast<float>(cursor.y - mLastCursor.y), -1.55f, 1.55f);
    }
    mLastCursor = cursor;
    Camera& camera = mSession->camera();
    glm::vec3 f = mFly.forward();
    glm::vec3 right = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
    glm::vec3 move(0.0f);
    if (!io.WantCaptureKeyboard) {
        if (window.isKeyDown(GLFW_KEY_W)) move += f;
        if (window.isKeyDown(GLFW_KEY_S)) move -= f;
        if (window.isKeyDown(GLFW_KEY_D)) move += right;
        if (window.isKeyDown(GLFW_KEY_A)) move -= right;
        if (window.isKeyDown(GLFW_KEY_E)) move += glm::vec3(0, 1, 0);
        if (window.isKeyDown(GLFW_KEY_Q)) move -= glm::vec3(0, 1, 0);
    }
    camera.position += move * (mFly.speed * std::min(dt, 0.25f));
    camera.target = camera.position + f;
    camera.up = glm::vec3(0, 1, 0);
}

void Viewer::dragLight()
{
    const glm::dvec2 cursor = mWindow->cursorPosition();
    const glm::dvec2 delta = cursor - mLastDragCursor;
    mLastDragCursor = cursor;
    std::vector<Light>& lights = mSession->scene().lights;
    if (!mWindow->isMouseButtonDown(GLFW_MOUSE_BUTTON_MIDDLE) || ImGui::GetIO().WantCaptureMouse) return;
    if (mSelectedLight < 0 || mSelectedLight >= static_cast<int>(lights.size())) return;
    Light& light = lights[static_cast<std::size_t>(mSelectedLight)];
    if (light.type == LightType::Directional || (delta.x == 0.0 && delta.y == 0.0)) return;
    // One pixel of cursor motion moves the light by one pixel's footprint at the light's depth, so it
    // follows the cursor in the view plane.
    const Camera& camera = mSession->camera();
    const glm::vec3 forward = glm::normalize(camera.target - camera.position);
    const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
    const glm::vec3 up = glm::cross(right, forward);
    const float depth = std::max(glm::dot(light.position - camera.position, forward), camera.zNear);
    const float pixel = 2.0f * depth * std::tan(0.5f * camera.fovY) / static_cast<float>(mWindow->framebufferSize().y);
    light.position += pixel * (static_cast<float>(delta.x) * right - static_cast<float>(delta.y) * up);
    mSession->renderer().markLightsChanged();
}

void Viewer::reloadShaders()
{
    if (!mReloadRequested) return;
    mReloadRequested = false;
    try {
        mSession->renderer().reloadShaders();
        mShaderError.clear();
        std::printf("shaders reloaded\n");
    } catch (const Error& e) {
        mShaderError = e.what(); // shown in the window until a reload succeeds
        std::fprintf(stderr, "shader reload failed, keeping the old shaders: %s\n", e.what());
    }
    std::fflush(stdout);
}

void Viewer::watchShaders()
{
    const auto newest = newestFileTime(gl::ShaderLoader::defaultDirectory());
    if (newest == mShaderTime) return;
    mShaderTime = newest;
    mReloadRequested = true;
}

Settings Viewer::defaultSettings()
{
    // The structs' defaults: a fresh technique and RendererParams visited with the live view list.
    RendererParams defaults;
    std::unique_ptr<Technique> technique = createTechnique(mSession->techniqueName());
    ParamDumper dumper;
    defaults.visitParams(dumper, displayViewNames(technique->debugViews()));
    technique->visitParams(dumper);
    return Settings(dumper.values().begin(), dumper.values().end());
}

std::string Viewer::setArguments()
{
    ParamDumper current;
    mSession->renderer().visitParams(current);
    std::string text = "--technique " + mSession->techniqueName();
    for (const auto& [key, value] : defaultSettings()) {
        auto it = current.values().find(key);
        if (it != current.values().end() && it->second != value) text += " --set " + key + "=" + it->second;
    }
    return text;
}

void Viewer::drawUi(glm::ivec2 size)
{
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (mShowPanel) drawPanel(size);
    if (mShowHelp) drawHelp();
    if (!mShaderError.empty()) {
        ImGui::SetNextWindowPos(ImVec2(0.5f * size.x, 0.0f), ImGuiCond_Always, ImVec2(0.5f, 0.0f));
        // A fixed width (wrapped text cannot size an auto-resizing window) and a fitted height (0).
        ImGui::SetNextWindowSize(ImVec2(std::min(0.7f * size.x, 640.0f * mUiScale), 0.0f), ImGuiCond_Always);
        ImGui::Begin("shader error", nullptr, ImGuiWindowFlags_NoCollapse);
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.4f, 1.0f));
        ImGui::TextWrapped("shader reload failed, the old shaders stay (R retries):");
        ImGui::PopStyleColor();
        ImGui::TextWrapped("%s", mShaderError.c_str());
        ImGui::End();
    }
    ImGui::Render();
    renderImGui(size);

    // Edits apply between frames, through the same path as --set (structural ones rebuild).
    Settings edits = mPanel.takeEdits();
    try {
        applySettings(edits);
    } catch (const Error& e) {
        mMessage = e.what();
        mMessageIsError = true;
    }
}

void Viewer::renderImGui(glm::ivec2 size)
{
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, size.x, size.y);
    // The 1.86 backend samples its font atlas on unit 0 without unbinding a sampler object; the
    // renderer's passes leave theirs bound (a depth-comparison sampler reads the atlas as zero).
    glBindSampler(0, 0);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void Viewer::drawPanel(glm::ivec2 size)
{
    const float width = std::min(360.0f * mUiScale, 0.5f * size.x);
    ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(width, static_cast<float>(size.y)), ImGuiCond_Always);
    ImGui::Begin("vplgi", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(-0.45f * width);
    ImGui::Text("%s   %d x %d   F1 help", mSession->scene().name.c_str(), size.x, size.y);
    drawRenderScale(size);

    // Technique selector.
    const std::vector<std::string> techniques = techniqueNames();
    if (ImGui::BeginCombo("technique", mSession->techniqueName().c_str())) {
        for (const std::string& t : techniques)
            if (ImGui::Selectable(t.c_str(), t == mSession->techniqueName()) && t != mSession->techniqueName())
                mPendingTechnique = t; // switched between frames
        ImGui::EndCombo();
    }
    if (!mMessage.empty()) {
        ImGui::PushTextWrapPos(0.0f);
        if (mMessageIsError)
            ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.45f, 1.0f), "%s", mMessage.c_str());
        else
            ImGui::TextColored(ImVec4(0.6f, 0.9f, 0.6f, 1.0f), "%s", mMessage.c_str());
        ImGui::PopTextWrapPos();
    }

    drawTimings();

    // Debug views: renderer.display is among the parameters below; the picture-in-picture here.
    if (ImGui::CollapsingHeader("views", ImGuiTreeNodeFlags_DefaultOpen)) {
        const std::vector<std::string> names = displayViewNames(mSession->renderer().technique().debugViews());
        if (ImGui::BeginCombo("picture in picture", mInsetView.empty() ? "off" : mInsetView.c_str())) {
            if (ImGui::Selectable("off", mInsetView.empty())) mInsetView.clear();
            for (const std::string& n : names)
                if (ImGui::Selectable(n.c_str(), n == mInsetView)) mInsetView = n;
            ImGui::EndCombo();
        }
        for (const DebugView& view : mSession->renderer().debugViews())
            if (view.name == mSession->renderer().params().display) ImGui::TextWrapped("%s", view.description.c_str());
    }

    // Every parameter, from the one field list.
    ImGui::Separator();
    if (ImGui::Button("reset to defaults")) {
        try {
            applySettings(defaultSettings());
        } catch (const Error& e) {
            mMessage = e.what();
            mMessageIsError = true;
        }
    }
    ImGui::SameLine();
    if (ImGui::Button("copy as --set")) {
        const std::string text = setArguments();
        ImGui::SetClipboardText(text.c_str());
        std::printf("%s\n", text.c_str());
        std::fflush(stdout);
        mMessage = "copied: " + text;
        mMessageIsError = false;
    }
    mPanel.begin();
    mSession->renderer().visitParams(mPanel);
    mPanel.end();

    drawLights();
    drawCameraSection();

    if (ImGui::CollapsingHeader("window and screenshots")) {
        ImGui::Checkbox("screenshots include the panel", &mScreenshotWithPanel);
        ImGui::Checkbox("screenshots also write EXR", &mScreenshotExr);
        if (ImGui::Checkbox("vsync", &mVsync)) glfwSwapInterval(mVsync ? 1 : 0);
        ImGui::Checkbox("reload shaders when glsl/ changes", &mWatchShaders);
        if (ImGui::Button("reload shaders (R)")) mReloadRequested = true;
        ImGui::SameLine();
        if (ImGui::Button("screenshot (F12)")) mScreenshotRequested = true;
    }
    ImGui::PopItemWidth();
    ImGui::End();
}

// The internal size, its control and the software rasterizer's lighter defaults.
void Viewer::drawRenderScale(glm::ivec2 size)
{
    ImGui::Text("internal %s", mScale.describe(size).c_str());
    bool automatic = mScale.automatic();
    float scale = mScale.internalSize(size).x / static_cast<float>(std::max(size.x, 1));
    if (ImGui::Checkbox("auto scale", &automatic)) mScale.set("viewer.renderScale", automatic ? "auto" : "1");
    if (!automatic) {
        ImGui::SameLine();
        if (ImGui::SliderFloat("##renderScale", &scale, 0.05f, 1.0f, "%.2f"))
            mScale.set("viewer.renderScale", std::to_string(scale));
    } else if (mScale.adapting()) {
        float target = mScale.targetMs();
        ImGui::SameLine();
        if (ImGui::SliderFloat("target ms", &target, 16.0f, 2000.0f, "%.0f", ImGuiSliderFlags_Logarithmic))
            mScale.set("viewer.targetMs", std::to_string(target));
    }
    if (!mSoftwareDefaults.empty()) {
        std::string text = "software rasterizer, lighter defaults:";
        for (const auto& [key, value] : mSoftwareDefaults)
            text += " " + key + "=" + value;
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextDisabled("%s", text.c_str());
        ImGui::PopTextWrapPos();
    }
}

void Viewer::drawTimings()
{
    if (!ImGui::CollapsingHeader("timings", ImGuiTreeNodeFlags_DefaultOpen)) return;
    const gl::PassTimer& timer = mSession->renderer().timer();
    const bool queries = timer.mode() == gl::PassTimer::Mode::TimestampQueries;
    ImGui::TextDisabled("%s", queries ? "GPU timestamp queries (read a few frames late)"
                                      : "glFinish + wall clock (software rasterizer)");
    if (ImGui::BeginTable("passes", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
        for (const gl::PassTime& t : timer.times()) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::Indent(static_cast<float>(t.depth) * 10.0f * mUiScale + 1.0f);
            ImGui::TextUnformatted(t.name.c_str());
            ImGui::Unindent(static_cast<float>(t.depth) * 10.0f * mUiScale + 1.0f);
            ImGui::TableNextColumn();
            ImGui::Text("%8.2f ms", t.milliseconds);
        }
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted("total");
        ImGui::TableNextColumn();
        ImGui::Text("%8.2f ms", timer.total());
        ImGui::EndTable();
    }
    // The frame-time graph: wall clock per frame and the passes' total, oldest on the left.
    const float latest = mFrameMs[static_cast<std::size_t>((mHistoryNext + kHistory - 1) % kHistory)];
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "frame %.1f ms (%.1f fps)", latest, latest > 0 ? 1000.0f / latest : 0.0f);
    // (1.86's PlotLines takes a negative width literally, not as "up to the right edge".)
    const float plotWidth = ImGui::GetContentRegionAvail().x;
    ImGui::PlotLines("##frame", mFrameMs.data(), kHistory, mHistoryNext, overlay, 0.0f, FLT_MAX,
                     ImVec2(plotWidth, 50.0f * mUiScale));
    ImGui::PlotLines("##passes", mGpuMs.data(), kHistory, mHistoryNext, "passes total [ms]", 0.0f, FLT_MAX,
                     ImVec2(plotWidth, 35.0f * mUiScale));
    // The technique's own counts and CPU stages (Technique::frameStats: VPLs, rays, maps re-rendered, ...).
    const auto stats = mSession->renderer().technique().frameStats();
    if (!stats.empty() && ImGui::BeginTable("stats", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
        for (const auto& [name, value] : stats) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(name.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%.6g", value);
        }
        ImGui::EndTable();
    }
    ImGui::Text("shadow cubes re-rendered: %d", mSession->renderer().lastRenderedShadowCubes());
}

void Viewer::drawLights()
{
    if (!ImGui::CollapsingHeader("lights")) return;
    std::vector<Light>& lights = mSession->scene().lights;
    if (lights.empty()) {
        ImGui::TextDisabled("no analytic lights");
        return;
    }
    mSelectedLight = std::clamp(mSelectedLight, 0, static_cast<int>(lights.size()) - 1);
    Light& light = lights[static_cast<std::size_t>(mSelectedLight)];
    if (ImGui::BeginCombo("light", light.name.c_str())) {
        for (std::size_t i = 0; i < lights.size(); ++i)
            if (ImGui::Selectable((lights[i].name + "##" + std::to_string(i)).c_str(),
                                  static_cast<int>(i) == mSelectedLight))
                mSelectedLight = static_cast<int>(i);
        ImGui::EndCombo();
    }
    bool changed = false;
    if (light.type == LightType::Directional) {
        // The sun: elevation above the horizon and azimuth from +x towards +z of where it shines from.
        const glm::vec3 toSun = -glm::normalize(light.direction);
        float elevation = glm::degrees(std::asin(glm::clamp(toSun.y, -1.0f, 1.0f)));
        float azimuth = glm::degrees(std::atan2(toSun.z, toSun.x));
        bool moved = ImGui::SliderFloat("elevation", &elevation, -10.0f, 90.0f, "%.1f deg");
        moved |= ImGui::SliderFloat("azimuth", &azimuth, -180.0f, 180.0f, "%.1f deg");
        if (moved) {
            const float e = glm::radians(elevation), a = glm::radians(azimuth);
            light.direction = -glm::vec3(std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a));
            changed = true;
        }
    } else {
        changed |= ImGui::DragFloat3("position [m]", &light.position.x, 0.01f * mFly.speed);
        ImGui::TextDisabled("middle mouse drag moves it in the view plane");
    }
    changed |= ImGui::DragFloat("intensity", &light.intensity, 0.01f * std::max(light.intensity, 0.1f), 0.0f, 1e9f);
    changed |= ImGui::ColorEdit3("color", &light.color.x);
    if (changed) mSession->renderer().markLightsChanged();
}

void Viewer::drawCameraSection()
{
    if (!ImGui::CollapsingHeader("camera and animation")) return;
    const Camera& camera = mSession->camera();
    ImGui::Text("position %.2f %.2f %.2f", camera.position.x, camera.position.y, camera.position.z);
    ImGui::SliderFloat("speed [m/s]", &mFly.speed, 0.01f, 1000.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    if (ImGui::Button(mRecorder.recording() ? "stop recording (C)" : "record camera path (C)")) {
        try {
            toggleRecording(mOptions.recordPath);
        } catch (const Error& e) {
            mMessage = e.what();
            mMessageIsError = true;
        }
    }
    if (mRecorder.recording()) {
        ImGui::SameLine();
        ImGui::Text("%zu keys", mRecorder.keyCount());
    }
    ImGui::TextDisabled("writes %s", mOptions.recordPath.c_str());
    if (ImGui::Checkbox("play animations (P)", &mPlaying) && mPlaying && mSession->scene().animations.empty())
        mPlaying = false;
    ImGui::SameLine();
    if (ImGui::Button("rewind")) mAnimationTime = 0.0f;
    ImGui::Text("t = %.2f s at 1/%.0f s per frame", mAnimationTime, mOptions.fps);
}

void Viewer::drawHelp()
{
    ImGuiIO& io = ImGui::GetIO();
    ImGui::SetNextWindowPos(ImVec2(0.5f * io.DisplaySize.x, 0.5f * io.DisplaySize.y), ImGuiCond_Always,
                            ImVec2(0.5f, 0.5f));
    ImGui::Begin("keys (F1 closes)", &mShowHelp, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
    if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg)) {
        for (const auto& key : kKeys) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(key[0]);
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(key[1]);
        }
        ImGui::EndTable();
    }
    ImGui::End();
}

void Viewer::drawProgress(const std::string& task, int done, int total)
{
    // Called between steps of a long precomputation (inside renderFrame or a technique switch): one
    // whole frame with the progress bar, so the window keeps drawing instead of freezing. The
    // renderer may have a framebuffer of its own bound; that binding is restored.
    if (mInProgressFrame || !mWindow) return;
    mInProgressFrame = true;
    GLint drawFramebuffer = 0, readFramebuffer = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFramebuffer);
    glfwPollEvents();
    const glm::ivec2 size = mWindow->framebufferSize();
    if (size.x > 0 && size.y > 0) {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, size.x, size.y);
        glClearColor(0.08f, 0.08f, 0.1f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        ImGui::SetNextWindowPos(ImVec2(0.5f * size.x, 0.5f * size.y), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
        ImGui::SetNextWindowSize(ImVec2(std::min(400.0f * mUiScale, 0.9f * size.x), 0.0f), ImGuiCond_Always);
        ImGui::Begin("working", nullptr, ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoMove);
        ImGui::TextUnformatted(task.c_str());
        char overlay[64];
        std::snprintf(overlay, sizeof overlay, "%d / %d", done, total);
        ImGui::ProgressBar(total > 0 ? static_cast<float>(done) / static_cast<float>(total) : 0.0f, ImVec2(-1.0f, 0.0f),
                           overlay);
        ImGui::End();
        ImGui::Render();
        renderImGui(size);
        mWindow->swapBuffers();
    }
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(drawFramebuffer));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(readFramebuffer));
    mInProgressFrame = false;
}

ImageRGBA8 Viewer::readWindow(glm::ivec2 size) const
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(size.x) * size.y * 4);
    glReadnPixels(0, 0, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(pixels.size()), pixels.data());
    ImageRGBA8 image;
    image.width = size.x;
    image.height = size.y;
    image.pixels.resize(pixels.size());
    const std::size_t row = static_cast<std::size_t>(size.x) * 4;
    for (int y = 0; y < size.y; ++y) // GL rows are bottom to top
        std::copy_n(&pixels[static_cast<std::size_t>(size.y - 1 - y) * row], row, &image.pixels[y * row]);
    for (std::size_t i = 3; i < image.pixels.size(); i += 4)
        image.pixels[i] = 255; // the window's alpha is not ours
    return image;
}

void Viewer::writeScreenshot(const std::string& path)
{
    std::string png = path;
    if (png.empty()) {
        std::filesystem::create_directories(mOptions.screenshotDir);
        png = nextScreenshotPath(mOptions.screenshotDir, "vplgi-" + mSession->scene().name, ".png");
    }
    writeImage(png, readWindow(mWindow->framebufferSize()));
    std::printf("screenshot %s\n", png.c_str());
    if (mScreenshotExr) {
        const std::string exr = png.substr(0, png.size() - 4) + ".exr";
        writeImage(exr, mSession->renderer().readRadiance());
        std::printf("screenshot %s\n", exr.c_str());
    }
    std::fflush(stdout);
}

} // namespace

int runView(const std::vector<std::string>& args)
{
    std::string keys;
    for (const auto& key : kKeys)
        keys += std::string(keys.empty() ? "" : "\n") + "  " + key[0] + ": " + key[1];
    OptionParser parser("vplgi view", "Opens a window on a scene with a parameter panel (Dear ImGui). Keys:\n" + keys);
    addSessionOptions(parser);
    addSizeOptions(parser, "window", 960, 540);
    parser.value("screenshot-dir", "DIR", "where F12 writes screenshots", "screenshots");
    parser.value("record-path", "FILE", "where C writes the recorded camera path (a scene file)", "camera-path.json");
    parser.value("script", "FILE", "run the frame-timed commands of FILE (app/view_script.h lists them)");
    parser.value("fps", "F", "animation playback and scripted recording advance 1/F s per frame", "30");
    parser.value("dump-panel-params", "FILE", "write the keys the panel generated after the first frame, then quit");
    parser.value("stats", "FILE", "write a CSV at the end with a row per frame: frame, ms (render, present, panel "
                 "and swap, after glFinish), internal_width, internal_height");
    parser.flag("play", "start with the scene's animations playing");
    parser.flag("no-panel", "start with the panel hidden (F2 shows it)");
    parser.flag("watch-shaders", "reload shaders when a file under glsl/ changes");
    if (!parser.parse(args)) return 0;
    ViewOptions options;
    options.size = imageSize(parser, 1, 16384);
    options.screenshotDir = parser.get("screenshot-dir");
    options.recordPath = parser.get("record-path");
    options.scriptPath = parser.get("script");
    options.fps = parser.getFloat("fps", 0.001f, 10000.0f);
    options.dumpPanelParams = parser.get("dump-panel-params");
    options.play = parser.has("play");
    options.panel = !parser.has("no-panel");
    options.watchShaders = parser.has("watch-shaders");
    options.session = sessionOptions(parser);
    options.statsPath = parser.get("stats");
    if (!options.statsPath.empty()) checkWritableDirectory(options.statsPath);
    // viewer.renderScale: automatic by default; 1 under --script, whose frames must not depend on
    // the machine's speed (an explicit --set viewer.renderScale=auto still adapts).
    if (!options.scriptPath.empty()) options.renderScale.set("viewer.renderScale", "1");
    options.renderScale.take(options.session.settings);
    Viewer viewer(options);
    viewer.run();
    return 0;
}

} // namespace vplgi
