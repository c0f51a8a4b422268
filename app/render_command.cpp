// `vplgi render`: headless EGL rendering to PNG (tone-mapped display image) or EXR (linear).
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <epoxy/gl.h>
#include <unistd.h>

#include "cli.h"
#include "commands.h"
#include "core/scene/builtin_scenes.h"
#include "core/util/error.h"
#include "core/util/image_io.h"
#include "core/util/params.h"
#include "gl/api/context.h"
#include "gl/api/debug.h"
#include "session.h"
#include "video_writer.h"

namespace vplgi {

namespace {

// --out with one printf-style frame number ("frames/%04d.png"): the whole sequence is written, frame
// i to the pattern formatted with i. Returns false for a plain path; throws Error for other '%' uses.
bool isSequencePattern(const std::string& out)
{
    const std::size_t percent = out.find('%');
    if (percent == std::string::npos) return false;
    std::size_t i = percent + 1;
    while (i < out.size() && i < percent + 4 && std::isdigit(static_cast<unsigned char>(out[i]))) ++i;
    require(i < out.size() && out[i] == 'd' && out.find('%', i) == std::string::npos,
            out + ": a sequence pattern has one frame number such as %04d (and no other '%')");
    return true;
}

std::string framePath(const std::string& pattern, int frame)
{
    char path[4096];
    std::snprintf(path, sizeof path, pattern.c_str(), frame);
    return path;
}

void writeOutput(Session& session, const std::string& path)
{
    if (isFloatImagePath(path)) writeImage(path, session.renderer().readRadiance());
    else writeImage(path, session.renderer().readDisplay());
}

// Resident set size of this process [KiB] from /proc/self/statm (0 where there is none).
long residentKiB()
{
    std::ifstream statm("/proc/self/statm");
    long pages = 0, resident = 0;
    if (!(statm >> pages >> resident)) return 0;
    return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

// Pixels of `image` with a NaN or infinite colour channel (alpha is the tone map's constant 1).
long countNonFinitePixels(const ImageRGBA32F& image)
{
    long count = 0;
    for (std::size_t i = 0; i + 3 < image.pixels.size(); i += 4)
        if (!std::isfinite(image.pixels[i]) || !std::isfinite(image.pixels[i + 1]) || !std::isfinite(image.pixels[i + 2]))
            ++count;
    return count;
}

// render --stats: one CSV row per frame for the soak (scripts/soak). The frame time brackets
// renderFrame() with glFinish (GPU timer queries are not trustworthy on llvmpipe, ENVIRONMENT.md);
// the radiance readback and the NaN count come after it, outside the time.
class FrameStats {
public:
    FrameStats() : mLastErrors(gl::highSeverityMessageCount()) { mRows << "frame,ms,rss_kb,gl_errors,nonfinite_pixels\n"; }
    void begin()
    {
        glFinish();
        mStart = std::chrono::steady_clock::now();
    }
    void end(int frame, Renderer& renderer)
    {
        glFinish();
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - mStart).count();
        const long nonFinite = countNonFinitePixels(renderer.readRadiance());
        const int errors = gl::highSeverityMessageCount();
        mRows << frame << ',' << ms << ',' << residentKiB() << ',' << (errors - mLastErrors) << ',' << nonFinite << '\n';
        mLastErrors = errors;
    }
    // Written once at the end through a temporary name: no half file when a frame fails.
    void write(const std::string& path) const
    {
        const std::string temporary = path + ".partial";
        {
            std::ofstream file(temporary);
            file << mRows.str();
            require(static_cast<bool>(file.flush()), path + ": cannot write");
        }
        std::filesystem::rename(temporary, path);
    }

private:
    std::ostringstream mRows;
    std::chrono::steady_clock::time_point mStart;
    int mLastErrors = 0;
};

// --list-params: every parameter of the technique(s), no GL context needed.
int listParams(const OptionParser& parser)
{
    SessionOptions options;
    options.sceneSpec = parser.has("scene") ? parser.get("scene") : "cornell";
    options.camera = parser.get("camera");
    for (const std::string& s : parser.getAll("set")) options.settings.push_back(parseSetting(s));
    const std::string technique = parser.get("technique");
    std::vector<std::string> techniques = technique == "all" ? techniqueNames() : std::vector<std::string>{technique};
    for (const std::string& t : techniques) {
        options.technique = t;
        options.rejectUnknownSettings = techniques.size() == 1;
        Session session(options);
        std::printf("technique = %s\n%s", session.techniqueName().c_str(), session.parameterList().c_str());
    }
    return 0;
}

} // namespace

int runRender(const std::vector<std::string>& args)
{
    OptionParser parser("vplgi render", "Renders a scene headless (EGL, no window) and writes one image:\n"
                                        "a .png holds the tone-mapped display image, an .exr the linear radiance.");
    addSessionOptions(parser);
    addSizeOptions(parser, "image", 640, 360);
    addAnimationOptions(parser, "frames to render; the last is written (every one with a %04d --out pattern)", 1);
    parser.value("out", "FILE", "output image (.png or .exr); its directory must exist; with a frame number "
                 "pattern such as 'frames/%04d.png' every frame is written", "out/render.png");
    parser.value("video", "FILE", "also write every frame to a video (.mp4 or .mkv, H.264 through Debian's "
                 "ffmpeg, one video frame per rendered frame at --fps); --out is then written only when given");
    parser.flag("list-params", "print every parameter key of the technique (--technique all: of each) with "
                "its value, range or choices and doc, then exit (--scene defaults to cornell)");
    parser.flag("headless", "accepted for symmetry: render is always headless");
    parser.flag("quiet", "do not print the configuration and timings");
    parser.value("stats", "FILE", "write a CSV with one row per frame: frame, ms (renderFrame bracketed by "
                 "glFinish), rss_kb, gl_errors (KHR_debug errors in the frame), nonfinite_pixels (NaN/Inf in "
                 "the radiance output, read back every frame); for scripts/soak");
    if (!parser.parse(args)) return 0;
    if (parser.has("list-params")) return listParams(parser);

    // Everything that can be wrong with the input is checked before a context exists.
    const ImageSize size = imageSize(parser, 1, 16384);
    const AnimationOptions animation = animationOptions(parser, 1000000);
    const std::string out = parser.get("out");
    checkOutputPath(out);
    const std::string statsPath = parser.get("stats");
    if (!statsPath.empty()) {
        const std::filesystem::path statsDir = std::filesystem::path(statsPath).parent_path();
        require(statsDir.empty() || std::filesystem::is_directory(statsDir),
                statsPath + ": directory " + statsDir.string() + " does not exist");
    }
    const bool sequence = isSequencePattern(out);
    const bool defaultOut = !parser.has("out");
    const std::string videoPath = parser.get("video");
    if (!videoPath.empty()) VideoWriter::check(videoPath);
    const bool writeImageOut = videoPath.empty() || !defaultOut;
    std::filesystem::path outDir = std::filesystem::path(out).parent_path();
    // The directory must exist (the default's is created) and take a file: checked before the
    // render, not after it.
    if (!defaultOut || outDir.empty() || std::filesystem::is_directory(outDir))
        checkWritableDirectory(sequence ? framePath(out, 0) : out);
    std::unique_ptr<gl::Context> context; // declared first: destroyed after the session's GL objects
    Session session(sessionOptions(parser));
    const bool quiet = parser.has("quiet");
    if (!quiet) std::printf("%s", session.configuration().c_str());

    context = gl::createHeadlessContext();
    if (!quiet) std::printf("context = %s\n", context->description().c_str());
    session.createRenderer();
    std::unique_ptr<FrameStats> stats = statsPath.empty() ? nullptr : std::make_unique<FrameStats>();
    std::unique_ptr<VideoWriter> video =
        videoPath.empty() ? nullptr
                          : std::make_unique<VideoWriter>(videoPath, size.width, size.height, animation.fps);
    for (int frame = 0; frame < animation.frames; ++frame) {
        session.applyAnimations(animation.timeOf(frame));
        if (stats) stats->begin();
        session.renderer().renderFrame(session.camera(), size.width, size.height, animation.timeOf(frame));
        if (stats) stats->end(frame, session.renderer());
        if (video) video->add(session.renderer().readDisplay());
        if (sequence) {
            writeOutput(session, framePath(out, frame));
            if (!quiet) std::printf("%s\n", framePath(out, frame).c_str());
        }
    }
    if (!quiet) {
        gl::PassTimer& timer = session.renderer().timer();
        timer.resolve(true); // GPU timestamps lag a few frames; waiting here makes them the last frame's
        std::printf("timings (last frame, %s):\n",
                    timer.mode() == gl::PassTimer::Mode::TimestampQueries ? "GPU timestamp queries"
                                                                          : "glFinish + wall clock");
        for (const gl::PassTime& t : timer.times()) // nested scopes indented under their parent
            std::printf("  %*s%-*s %9.2f ms\n", 2 * t.depth, "", std::max(1, 16 - 2 * t.depth), t.name.c_str(),
                        t.milliseconds);
    }
    if (stats) stats->write(statsPath);
    if (video) {
        video->finish();
        std::printf("%s (%d frames at %g fps)\n", videoPath.c_str(), video->frames(), static_cast<double>(animation.fps));
    }
    if (!writeImageOut) return 0;
    if (sequence) {
        if (quiet) std::printf("%s\n", framePath(out, animation.frames - 1).c_str());
        return 0;
    }
    if (defaultOut && !outDir.empty()) std::filesystem::create_directories(outDir);
    writeOutput(session, out);
    std::printf("%s\n", out.c_str());
    return 0;
}

int runScenes(const std::vector<std::string>& args)
{
    OptionParser parser("vplgi scenes", "Lists the built-in scenes and the techniques.");
    if (!parser.parse(args)) return 0;
    std::printf("built-in scenes:");
    for (const std::string& s : builtinSceneNames()) std::printf(" %s", s.c_str());
    std::printf("\ntechniques:");
    for (const std::string& t : techniqueNames()) std::printf(" %s", t.c_str());
    std::printf("\n");
    return 0;
}

} // namespace vplgi
