#include "video_writer.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "core/util/error.h"

extern char** environ;

namespace vplgi {

namespace {

std::string lowerExtension(const std::string& path)
{
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension;
}

// The ffmpeg executable as the shell would find it; "" when it is not on PATH.
std::string findFfmpeg()
{
    const char* path = std::getenv("PATH");
    std::string directories = path ? path : "";
    std::size_t start = 0;
    while (start <= directories.size()) {
        std::size_t end = directories.find(':', start);
        if (end == std::string::npos) end = directories.size();
        const std::string directory = directories.substr(start, end - start);
        const std::string candidate = (directory.empty() ? std::string(".") : directory) + "/ffmpeg";
        if (::access(candidate.c_str(), X_OK) == 0) return candidate;
        start = end + 1;
    }
    return "";
}

// True when `ffmpeg -encoders` lists libx264 (Debian's ffmpeg has it; a minimal build may not).
bool hasLibx264(const std::string& ffmpeg)
{
    const std::string command = "'" + ffmpeg + "' -hide_banner -encoders 2>/dev/null";
    FILE* pipe = ::popen(command.c_str(), "r");
    if (!pipe) return false;
    char line[512];
    bool found = false;
    while (std::fgets(line, sizeof line, pipe))
        if (std::strstr(line, " libx264 ")) found = true;
    ::pclose(pipe);
    return found;
}

} // namespace

void VideoWriter::check(const std::string& path)
{
    const std::string extension = lowerExtension(path);
    require(extension == ".mp4" || extension == ".mkv", path + ": a video must end in .mp4 or .mkv");
    checkWritableDirectory(path);
    const std::string ffmpeg = findFfmpeg();
    require(!ffmpeg.empty(), "ffmpeg is not installed (not on PATH): videos need Debian's ffmpeg (./scripts/deps "
                             "installs it)");
    require(hasLibx264(ffmpeg), ffmpeg + " has no libx264 encoder (Debian's ffmpeg has it)");
}

VideoWriter::VideoWriter(const std::string& path, int width, int height, float fps)
    : mPath(path), mPartial(path + ".partial"), mWidth(width), mHeight(height)
{
    check(path);
    require(width > 0 && height > 0 && fps > 0.0f, "video: bad frame size or rate");
    std::signal(SIGPIPE, SIG_IGN); // a write to a stopped ffmpeg returns EPIPE instead of ending vplgi

    // ffmpeg's messages go to a log file: its last line is the error we report.
    char log[] = "/tmp/vplgi-ffmpeg-XXXXXX";
    const int logFd = ::mkstemp(log);
    require(logFd >= 0, std::string("video: cannot create a log file: ") + std::strerror(errno));
    ::close(logFd);
    mLog = log;

    char rate[32], size[32], pad[64];
    std::snprintf(rate, sizeof rate, "%g", static_cast<double>(fps));
    std::snprintf(size, sizeof size, "%dx%d", width, height);
    std::snprintf(pad, sizeof pad, "pad=%d:%d", width + (width & 1), height + (height & 1));
    const std::vector<std::string> args = {
        findFfmpeg(), "-hide_banner", "-nostdin", "-loglevel", "error", "-y",
        // Input: raw RGBA frames on standard input, one per rendered frame at `fps`.
        "-f", "rawvideo", "-pix_fmt", "rgba", "-video_size", size, "-framerate", rate, "-i", "pipe:0",
        // Output: H.264 for every player; CRF 18 is visually lossless for rendered images.
        "-vf", pad, "-c:v", "libx264", "-preset", "medium", "-crf", "18", "-pix_fmt", "yuv420p",
        "-f", lowerExtension(path) == ".mkv" ? "matroska" : "mp4", mPartial};
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);

    int fds[2];
    require(::pipe2(fds, O_CLOEXEC) == 0, std::string("video: cannot create a pipe: ") + std::strerror(errno));
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], 0); // dup2 clears close-on-exec on stdin
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, mLog.c_str(), O_WRONLY | O_TRUNC, 0);
    const int spawned = ::posix_spawn(&mPid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(fds[0]);
    if (spawned != 0) {
        ::close(fds[1]);
        std::remove(mLog.c_str());
        throw Error(std::string("video: cannot start ffmpeg: ") + std::strerror(spawned));
    }
    mPipe = fds[1];
}

VideoWriter::~VideoWriter()
{
    if (mFinished) return;
    if (mPid > 0) ::kill(mPid, SIGTERM);
    stop();
    std::remove(mPartial.c_str());
    std::remove(mLog.c_str());
}

void VideoWriter::add(const ImageRGBA8& frame)
{
    require(frame.width == mWidth && frame.height == mHeight,
            "video: a frame of " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                " in a video of " + std::to_string(mWidth) + "x" + std::to_string(mHeight));
    const std::uint8_t* data = frame.pixels.data();
    std::size_t left = frame.pixels.size();
    while (left > 0) {
        const ssize_t n = ::write(mPipe, data, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            stop();
            throw Error(mPath + ": ffmpeg stopped: " + lastLogLine());
        }
        data += n;
        left -= static_cast<std::size_t>(n);
    }
    ++mFrames;
}

void VideoWriter::finish()
{
    stop();
    const bool ok = WIFEXITED(mStatus) && WEXITSTATUS(mStatus) == 0;
    const std::string message = ok ? "" : lastLogLine();
    mFinished = true;
    std::remove(mLog.c_str());
    if (!ok) {
        std::remove(mPartial.c_str());
        throw Error(mPath + ": ffmpeg failed: " + message);
    }
    std::filesystem::rename(mPartial, mPath);
}

void VideoWriter::stop()
{
    if (mPipe >= 0) ::close(mPipe);
    mPipe = -1;
    if (mPid <= 0) return;
    while (::waitpid(mPid, &mStatus, 0) < 0 && errno == EINTR) {
    }
    mPid = -1;
}

std::string VideoWriter::lastLogLine() const
{
    std::ifstream log(mLog);
    std::string line, last = "(no message)";
    while (std::getline(log, line))
        if (!line.empty()) last = line;
    return last;
}

} // namespace vplgi
