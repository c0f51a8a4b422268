// Videos through Debian's `ffmpeg` command-line tool (issue 28 part 7): `vplgi render --video` and the
// viewer's M key pipe their display frames (tone mapped, what the PNG holds) to ffmpeg as raw RGBA;
// ffmpeg encodes H.264 (libx264, yuv420p, CRF 18) into MP4 or Matroska, one video frame per rendered
// frame at the given rate: the video is frame-exact. The file appears only when ffmpeg succeeded
// (written under a temporary name, renamed into place): never half a video.
#pragma once

#include <string>
#include <sys/types.h>

#include "core/util/image_io.h"

namespace vplgi {

class VideoWriter {
public:
    // What can be checked before rendering, each a one-line Error: the extension (.mp4 or .mkv), the
    // directory (exists, takes a file), ffmpeg on PATH and its libx264 encoder.
    static void check(const std::string& path);

    // Starts ffmpeg for frames of width x height at `fps` frames per second. Odd sizes are padded
    // by one black row or column (yuv420p needs even ones).
    VideoWriter(const std::string& path, int width, int height, float fps);
    // Not finished: ffmpeg is stopped and the partial file removed.
    ~VideoWriter();
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;

    // One frame, rows top to bottom, of the size given to the constructor.
    void add(const ImageRGBA8& frame);
    // Closes the pipe, waits for ffmpeg and moves the file into place; throws Error with ffmpeg's
    // last message when it failed.
    void finish();

    const std::string& path() const { return mPath; }
    int frames() const { return mFrames; }
    int width() const { return mWidth; }
    int height() const { return mHeight; }

private:
    void stop(); // closes the pipe and reaps ffmpeg; returns its exit status in mStatus
    std::string lastLogLine() const;

    std::string mPath, mPartial, mLog;
    int mWidth = 0, mHeight = 0;
    int mFrames = 0;
    int mPipe = -1; // ffmpeg's standard input
    pid_t mPid = -1;
    int mStatus = 0;
    bool mFinished = false;
};

} // namespace vplgi
