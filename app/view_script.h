// `vplgi view --script FILE`: commands timed by frame number rather than wall clock, so a script
// does the same under Xvfb's slow llvmpipe as on a GPU (the tests drive the viewer with one).
//
//   # comment                       blank lines and comments are skipped
//   at FRAME COMMAND [ARGS...]      run COMMAND before rendering frame FRAME (0 = the first frame)
//   COMMAND [ARGS...]               without "at": the same frame as the line before (0 at the top)
//
// Commands (checked when the file is read: a bad line is one error naming FILE:LINE):
//   set KEY=VALUE...        like --set (renderer, pass and technique parameters)
//   technique NAME          switch technique (renderer.* parameters carry over)
//   display VIEW            renderer.display=VIEW (a frame view or a debug view)
//   pip VIEW | off          picture-in-picture of VIEW beside the final image
//   panel on|off            show or hide the parameter panel
//   screenshot-panel on|off whether screenshots include the panel (the F12 setting)
//   screenshot [PATH]       what the window shows as PNG (+ the linear frame as EXR beside it)
//   key NAME                a key press: F1..F12, A..Z, 0..9, ESCAPE, SPACE
//   dump-params FILE        the keys the panel generated, one a line
//   camera PX PY PZ TX TY TZ          place the camera: eye and target [m]
//   record start | record stop FILE    camera path, written as a scene-file animation
//   video start [FILE] | video stop     a video of the frames shown (.mp4/.mkv; the M key's)
//   play on|off             play the scene's animations at the fixed step 1/--fps per frame
//   reload                  reload shaders (as R: a failed compile keeps the old programs and shows
//                           the error in the window)
//   wait-file PATH          hold this frame until PATH exists (at most 120 s): lets a test change
//                           files (a shader) at a known frame
//   vsync on|off
//   resize W H              window size in screen coordinates
//   quit
#pragma once

#include <string>
#include <vector>

namespace vplgi {

struct ScriptCommand {
    int frame = 0;
    int line = 0;     // 1-based line in the file, for messages
    std::string name; // "set", "technique", ...
    std::vector<std::string> args;
};

class ViewScript {
public:
    // Reads and checks the whole file; throws Error "FILE:LINE: message" on the first bad line.
    static ViewScript load(const std::string& path);
    static ViewScript parse(const std::string& text, const std::string& path);

    // Commands due at `frame`, in file order.
    std::vector<ScriptCommand> due(int frame) const;
    // "FILE:LINE" of a command, for errors found while running it.
    std::string where(const ScriptCommand& command) const;
    bool empty() const { return mCommands.empty(); }

private:
    std::string mPath;
    std::vector<ScriptCommand> mCommands; // stably sorted by frame
};

// GLFW key code of a script key name (F1..F12, A..Z, 0..9, ESCAPE, SPACE); -1 if unknown.
int scriptKeyCode(const std::string& name);

} // namespace vplgi
