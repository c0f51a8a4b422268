#include "shader_loader.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/util/error.h"

namespace vplgi::gl {

namespace fs = std::filesystem;

namespace {

// #line numbers carry the file: line = file index * kLineStride + line in file. Source-string
// numbers (`#line L S`) would be the natural carrier, but Mesa reports some errors (e.g. undeclared
// identifiers) with source string 0 regardless, so only the line number is trusted.
constexpr int kLineStride = 100000;

std::string lineDirective(int fileIndex, int line)
{
    return "#line " + std::to_string(fileIndex * kLineStride + line) + "\n";
}

} // namespace

std::string sourceLocation(const PreprocessedSource& source, long reportedLine)
{
    std::size_t fileIndex = static_cast<std::size_t>(reportedLine / kLineStride);
    std::string file = fileIndex < source.files.size() ? source.files[fileIndex] : source.files.at(0);
    return "glsl/" + file + ":" + std::to_string(reportedLine % kLineStride);
}

ShaderLoader::ShaderLoader(std::string glslDirectory) : mDirectory(std::move(glslDirectory))
{
    require(fs::is_directory(mDirectory), "shader directory " + mDirectory + " not found (set VPLGI_GLSL_DIR)");
}

std::string ShaderLoader::defaultDirectory()
{
    if (const char* env = std::getenv("VPLGI_GLSL_DIR"); env && *env) return env;
    return VPLGI_GLSL_DIR;
}

namespace {

std::string readText(const fs::path& path, const std::string& shown)
{
    std::ifstream in(path, std::ios::binary);
    require(in.good(), shown + ": cannot open shader file");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string normalizeRelative(const fs::path& path)
{
    return path.lexically_normal().generic_string();
}

} // namespace

void ShaderLoader::appendFile(const std::string& file, PreprocessedSource& out, std::vector<std::string>& stack) const
{
    const int index = static_cast<int>(out.files.size());
    out.files.push_back(file);
    stack.push_back(file);
    if (index > 0) out.text += lineDirective(index, 1);
    std::istringstream lines(readText(fs::path(mDirectory) / file, "glsl/" + file));
    static const std::regex includeLine(R"(^\s*#\s*include\s+"([^"]+)\"\s*$)");
    std::string line;
    int lineNumber = 0;
    bool first = index == 0;
    while (std::getline(lines, line)) {
        ++lineNumber;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::smatch match;
        if (std::regex_match(line, match, includeLine)) {
            fs::path relative = fs::path(file).parent_path() / match[1].str();
            std::string target = normalizeRelative(relative);
            if (!fs::exists(fs::path(mDirectory) / target)) target = normalizeRelative(match[1].str());
            require(fs::exists(fs::path(mDirectory) / target),
                    "glsl/" + file + ":" + std::to_string(lineNumber) + ": cannot find include \"" + match[1].str() + "\"");
            require(std::find(stack.begin(), stack.end(), target) == stack.end(),
                    "glsl/" + file + ":" + std::to_string(lineNumber) + ": recursive include of \"" + target + "\"");
            bool already = std::find(out.files.begin(), out.files.end(), target) != out.files.end();
            if (!already) {
                appendFile(target, out, stack);
                out.text += lineDirective(index, lineNumber + 1);
            } else {
                out.text += "\n"; // keep line numbers: each file is included once
            }
            continue;
        }
        out.text += line + "\n";
        if (first && lineNumber == 1) {
            require(line.rfind("#version", 0) == 0, "glsl/" + file + ":1: the first line must be #version");
        }
        if (stack.size() > 1 && lineNumber == 1 && line.rfind("#version", 0) == 0) {
            throw Error("glsl/" + file + ":1: included files must not have #version");
        }
    }
    stack.pop_back();
}

PreprocessedSource ShaderLoader::preprocess(const std::string& file, const std::vector<std::string>& defines) const
{
    PreprocessedSource body;
    std::vector<std::string> stack;
    // The #version line moves to the front below, followed by the defines.
    appendFile(file, body, stack);
    std::size_t firstNewline = body.text.find('\n');
    std::string versionLine = body.text.substr(0, firstNewline + 1);
    std::string rest = body.text.substr(firstNewline + 1);
    PreprocessedSource out;
    out.files = body.files;
    out.text = versionLine;
    for (const std::string& define : defines) {
        std::string d = define;
        std::replace(d.begin(), d.end(), '=', ' ');
        out.text += "#define " + d + "\n";
    }
    out.text += lineDirective(0, 2) + rest;
    return out;
}

namespace {

// Maps the driver's "<string>:<line>(<col>): message" (Mesa) or "<string>(<line>) : message"
// (NVIDIA) to "glsl/<file>:<line>: message".
std::string mapLog(const std::string& log, const PreprocessedSource& source, const std::string& fallbackFile)
{
    static const std::regex mesa(R"(^\s*(\d+):(\d+)\(\d+\):\s*(.*)$)");
    static const std::regex nvidia(R"(^\s*(\d+)\((\d+)\)\s*:\s*(.*)$)");
    std::istringstream lines(log);
    std::string line, firstError, firstLine;
    int errors = 0;
    while (std::getline(lines, line)) {
        std::smatch m;
        std::string mapped;
        if (std::regex_match(line, m, mesa) || std::regex_match(line, m, nvidia)) {
            mapped = sourceLocation(source, std::stol(m[2].str())) + ": " + m[3].str();
        } else if (!line.empty()) {
            mapped = "glsl/" + fallbackFile + ": " + line;
        } else {
            continue;
        }
        if (firstLine.empty()) firstLine = mapped;
        if (mapped.find("error") != std::string::npos) {
            if (firstError.empty()) firstError = mapped;
            ++errors;
        }
    }
    std::string result = firstError.empty() ? firstLine : firstError;
    if (result.empty()) result = "glsl/" + fallbackFile + ": compilation failed";
    if (errors > 1) result += " (and " + std::to_string(errors - 1) + " more errors)";
    return result;
}

} // namespace

Program ShaderLoader::load(const std::string& name, const std::vector<ShaderStage>& stages,
                           const std::vector<std::string>& defines) const
{
    GLuint program = glCreateProgram();
    std::vector<GLuint> shaders;
    auto cleanup = [&] {
        for (GLuint s : shaders) glDeleteShader(s);
    };
    for (const ShaderStage& stage : stages) {
        PreprocessedSource source = preprocess(stage.file, defines);
        GLuint shader = glCreateShader(stage.type);
        shaders.push_back(shader);
        const char* text = source.text.c_str();
        glShaderSource(shader, 1, &text, nullptr);
        glCompileShader(shader);
        GLint ok = GL_FALSE;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (ok != GL_TRUE) {
            GLint length = 0;
            glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
            std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
            glGetShaderInfoLog(shader, length, nullptr, log.data());
            cleanup();
            glDeleteProgram(program);
            throw Error(mapLog(log, source, stage.file));
        }
        glAttachShader(program, shader);
    }
    glLinkProgram(program);
    cleanup();
    GLint linked = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    if (linked != GL_TRUE) {
        GLint length = 0;
        glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program, length, nullptr, log.data());
        glDeleteProgram(program);
        std::string firstLine = log.substr(0, log.find('\n'));
        throw Error("program " + name + ": link failed: " + firstLine);
    }
    return Program(name, program);
}

} // namespace vplgi::gl
