#include "view_script.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/util/error.h"
#include "gl/techniques/technique.h"

namespace vplgi {

namespace {

bool isOnOff(const std::string& s)
{
    return s == "on" || s == "off";
}

// Checks one command's arguments; returns an error message or "".
std::string checkCommand(const ScriptCommand& c)
{
    const std::size_t n = c.args.size();
    auto count = [&](std::size_t min, std::size_t max, const char* usage) -> std::string {
        return n < min || n > max ? std::string("usage: ") + usage : "";
    };
    if (c.name == "set") {
        if (n == 0) return "usage: set KEY=VALUE...";
        for (const std::string& a : c.args)
            if (a.find('=') == std::string::npos || a.front() == '=') return "set: \"" + a + "\" is not KEY=VALUE";
        return "";
    }
    if (c.name == "technique") {
        if (n != 1) return "usage: technique NAME";
        const std::vector<std::string> names = techniqueNames();
        if (std::find(names.begin(), names.end(), c.args[0]) != names.end()) return "";
        std::string known;
        for (const std::string& t : names)
            known += (known.empty() ? "" : ", ") + t;
        return "unknown technique \"" + c.args[0] + "\" (known: " + known + ")";
    }
    if (c.name == "display") return count(1, 1, "display VIEW");
    if (c.name == "pip") return count(1, 1, "pip VIEW|off");
    if (c.name == "panel" || c.name == "screenshot-panel" || c.name == "play" || c.name == "vsync")
        return n == 1 && isOnOff(c.args[0]) ? "" : "usage: " + c.name + " on|off";
    if (c.name == "screenshot") {
        if (n > 1) return "usage: screenshot [PATH]";
        if (n == 1 && (c.args[0].size() < 5 || c.args[0].substr(c.args[0].size() - 4) != ".png"))
            return "screenshot: \"" + c.args[0] + "\" must end in .png";
        return "";
    }
    if (c.name == "key") {
        if (n != 1) return "usage: key NAME";
        return scriptKeyCode(c.args[0]) >= 0 ? ""
                                             : "unknown key \"" + c.args[0] + "\" (F1..F12, A..Z, 0..9, ESCAPE, SPACE)";
    }
    if (c.name == "dump-params") return count(1, 1, "dump-params FILE");
    if (c.name == "wait-file") return count(1, 1, "wait-file PATH");
    if (c.name == "camera") {
        if (n != 6) return "usage: camera PX PY PZ TX TY TZ";
        for (const std::string& a : c.args) {
            char* end = nullptr;
            const double v = std::strtod(a.c_str(), &end);
            if (a.empty() || *end != '\0' || !std::isfinite(v)) return "camera: \"" + a + "\" is not a number";
        }
        return "";
    }
    if (c.name == "record") {
        if (n == 1 && c.args[0] == "start") return "";
        if (n == 2 && c.args[0] == "stop") return "";
        return "usage: record start | record stop FILE";
    }
    if (c.name == "video") {
        if (n == 1 && c.args[0] == "stop") return "";
        if (n < 1 || n > 2 || c.args[0] != "start") return "usage: video start [FILE.mp4|FILE.mkv] | video stop";
        const std::string extension = n == 2 ? std::filesystem::path(c.args[1]).extension().string() : ".mp4";
        return extension == ".mp4" || extension == ".mkv" ? ""
                                                          : "video: \"" + c.args[1] + "\" must end in .mp4 or .mkv";
    }
    if (c.name == "reload" || c.name == "quit") return count(0, 0, c.name == "reload" ? "reload" : "quit");
    if (c.name == "resize") {
        if (n != 2) return "usage: resize W H";
        for (const std::string& a : c.args) {
            char* end = nullptr;
            long v = std::strtol(a.c_str(), &end, 10);
            if (a.empty() || *end != '\0' || v < 1 || v > 16384)
                return "resize: \"" + a + "\" is not a size in 1..16384";
        }
        return "";
    }
    return "unknown command \"" + c.name +
           "\" (set, technique, display, pip, panel, screenshot-panel, screenshot, key, dump-params, camera, record, "
           "video, play, wait-file, "
           "reload, vsync, resize, quit)";
}

} // namespace

int scriptKeyCode(const std::string& name)
{
    if (name.size() == 1 && name[0] >= 'A' && name[0] <= 'Z') return GLFW_KEY_A + (name[0] - 'A');
    if (name.size() == 1 && name[0] >= '0' && name[0] <= '9') return GLFW_KEY_0 + (name[0] - '0');
    if (name.size() >= 2 && name.size() <= 3 && name[0] == 'F') {
        const int f = std::atoi(name.c_str() + 1);
        if (f >= 1 && f <= 12 && name.substr(1) == std::to_string(f)) return GLFW_KEY_F1 + f - 1;
    }
    if (name == "ESCAPE") return GLFW_KEY_ESCAPE;
    if (name == "SPACE") return GLFW_KEY_SPACE;
    return -1;
}

ViewScript ViewScript::load(const std::string& path)
{
    std::ifstream in(path);
    require(in.good(), path + ": cannot read the script");
    std::stringstream text;
    text << in.rdbuf();
    return parse(text.str(), path);
}

ViewScript ViewScript::parse(const std::string& text, const std::string& path)
{
    ViewScript script;
    script.mPath = path;
    std::istringstream lines(text);
    std::string line;
    int lineNumber = 0;
    int frame = 0;
    while (std::getline(lines, line)) {
        ++lineNumber;
        const std::size_t hash = line.find('#');
        if (hash != std::string::npos) line.erase(hash);
        std::istringstream words(line);
        std::vector<std::string> tokens;
        for (std::string w; words >> w;)
            tokens.push_back(w);
        if (tokens.empty()) continue;
        const std::string where = path + ":" + std::to_string(lineNumber) + ": ";
        std::size_t first = 0;
        if (tokens[0] == "at") {
            require(tokens.size() >= 3, where + "usage: at FRAME COMMAND [ARGS...]");
            char* end = nullptr;
            const long f = std::strtol(tokens[1].c_str(), &end, 10);
            require(*end == '\0' && f >= 0 && f <= 100000000, where + "\"" + tokens[1] + "\" is not a frame number");
            frame = static_cast<int>(f);
            first = 2;
        }
        ScriptCommand command;
        command.frame = frame;
        command.line = lineNumber;
        command.name = tokens[first];
        command.args.assign(tokens.begin() + static_cast<std::ptrdiff_t>(first) + 1, tokens.end());
        const std::string problem = checkCommand(command);
        require(problem.empty(), where + problem);
        script.mCommands.push_back(command);
    }
    std::stable_sort(script.mCommands.begin(), script.mCommands.end(),
                     [](const ScriptCommand& a, const ScriptCommand& b) { return a.frame < b.frame; });
    return script;
}

std::vector<ScriptCommand> ViewScript::due(int frame) const
{
    std::vector<ScriptCommand> out;
    for (const ScriptCommand& c : mCommands)
        if (c.frame == frame) out.push_back(c);
    return out;
}

std::string ViewScript::where(const ScriptCommand& command) const
{
    return mPath + ":" + std::to_string(command.line);
}

} // namespace vplgi
