// Validates every shader entry point with glslangValidator, after the project's own preprocessing
// (gl::ShaderLoader::preprocess: #include resolved on the CPU, defines after #version, #line
// encoding), so that what is checked is what the driver gets. Errors are reported as
// glsl/<file>:<line> through the loader's own line decoding.
//
// Why a second compiler when the GL tests already compile every program on llvmpipe: Mesa accepts
// some things the GLSL spec forbids and other drivers reject; glslang is the Khronos reference
// front end. It runs without a GL context, so this check needs no driver at all.
//
//   vplgi_validate_shaders --glslang PATH --root GLSL_DIR [--define FILE:NAME[=VALUE]]... DIR...
// Every .vert .tesc .tese .geom .frag .comp under each DIR is one entry point; FILE in --define is
// its path relative to GLSL_DIR as the output shows it (the way the code names it when loading).
// Exit status: 0 all valid, 1 some invalid, 2 bad usage or nothing to validate.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/util/error.h"
#include "gl/api/shader_loader.h"

namespace fs = std::filesystem;
using namespace vplgi;

namespace {

struct Options {
    std::string glslang;
    std::string root;
    std::vector<std::string> directories;
    std::map<std::string, std::vector<std::string>> defines; // entry point -> NAME=VALUE list
};

Options parseOptions(int argc, char** argv)
{
    Options options;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        auto value = [&] {
            require(i + 1 < argc, arg + " needs a value");
            return std::string(argv[++i]);
        };
        if (arg == "--glslang") {
            options.glslang = value();
        } else if (arg == "--root") {
            options.root = value();
        } else if (arg == "--define") {
            std::string define = value();
            std::size_t colon = define.rfind(':');
            require(colon != std::string::npos && colon > 0 && colon + 1 < define.size(),
                    "--define " + define + ": expected FILE:NAME[=VALUE]");
            options.defines[define.substr(0, colon)].push_back(define.substr(colon + 1));
        } else if (!arg.empty() && arg[0] == '-') {
            throw Error("unknown option " + arg);
        } else {
            options.directories.push_back(arg);
        }
    }
    require(!options.glslang.empty() && !options.root.empty() && !options.directories.empty(),
            "usage: vplgi_validate_shaders --glslang PATH --root GLSL_DIR [--define FILE:NAME[=VALUE]]... DIR...");
    return options;
}

bool isEntryPoint(const fs::path& path)
{
    static const std::set<std::string> kStages = {".vert", ".tesc", ".tese", ".geom", ".frag", ".comp"};
    return kStages.count(path.extension().string()) > 0;
}

std::vector<std::string> findEntryPoints(const Options& options)
{
    std::vector<std::string> files;
    for (const std::string& directory : options.directories) {
        require(fs::is_directory(directory), directory + ": not a directory");
        for (const fs::directory_entry& entry : fs::recursive_directory_iterator(directory)) {
            if (entry.is_regular_file() && isEntryPoint(entry.path())) {
                files.push_back(fs::relative(entry.path(), options.root).generic_string());
            }
        }
    }
    std::sort(files.begin(), files.end());
    files.erase(std::unique(files.begin(), files.end()), files.end());
    return files;
}

std::string shellQuote(const std::string& s)
{
    require(s.find('\'') == std::string::npos, "path with a single quote: " + s);
    return "'" + s + "'";
}

struct RunResult {
    int status = -1;
    std::string output;
};

RunResult runCommand(const std::string& command)
{
    RunResult result;
    FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
    require(pipe != nullptr, "cannot run " + command);
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0)
        result.output.append(buffer, n);
    int status = ::pclose(pipe);
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128;
    return result;
}

// glslangValidator prints "ERROR: 0:<line>: message"; the line carries the loader's file encoding.
std::string mapGlslangLog(const std::string& log, const gl::PreprocessedSource& source, const std::string& tempFile)
{
    static const std::regex located(R"(^(ERROR|WARNING): \d+:(\d+): (.*)$)");
    std::istringstream lines(log);
    std::string line, mapped;
    while (std::getline(lines, line)) {
        std::smatch m;
        if (line.empty() || line == tempFile) continue; // glslangValidator echoes the file name first
        if (std::regex_match(line, m, located)) {
            mapped +=
                "  " + m[1].str() + ": " + gl::sourceLocation(source, std::stol(m[2].str())) + ": " + m[3].str() + "\n";
        } else {
            mapped += "  " + line + "\n";
        }
    }
    return mapped;
}

struct TempDirectory {
    fs::path path = fs::temp_directory_path() / ("vplgi-validate-shaders-" + std::to_string(::getpid()));
    TempDirectory() { fs::create_directories(path); }
    ~TempDirectory()
    {
        std::error_code ignored;
        fs::remove_all(path, ignored);
    }
};

int validate(const Options& options)
{
    std::vector<std::string> files = findEntryPoints(options);
    require(!files.empty(), "no shader entry points found: nothing validated");
    for (const auto& [file, defines] : options.defines) {
        require(std::find(files.begin(), files.end(), file) != files.end(),
                "--define for " + file + ", which is not an entry point found here");
    }
    gl::ShaderLoader loader(options.root);
    TempDirectory temp;
    int failures = 0;
    int index = 0;
    for (const std::string& file : files) {
        auto found = options.defines.find(file);
        const std::vector<std::string> defines =
            found == options.defines.end() ? std::vector<std::string>{} : found->second;
        std::string label = file;
        for (const std::string& d : defines)
            label += " -D" + d;
        gl::PreprocessedSource source;
        try {
            source = loader.preprocess(file, defines);
        } catch (const Error& e) {
            std::cout << "FAIL " << label << "\n  " << e.what() << "\n";
            ++failures;
            continue;
        }
        // The extension tells glslangValidator the stage.
        fs::path tempFile = temp.path / (std::to_string(index++) + fs::path(file).extension().string());
        std::ofstream(tempFile, std::ios::binary) << source.text;
        RunResult run = runCommand(shellQuote(options.glslang) + " " + shellQuote(tempFile.string()));
        std::string log = mapGlslangLog(run.output, source, tempFile.string());
        if (run.status != 0) {
            std::cout << "FAIL " << label << "\n"
                      << (log.empty() ? "  glslangValidator exit status " + std::to_string(run.status) + "\n" : log);
            ++failures;
        } else {
            std::cout << "ok   " << label << "\n" << log;
        }
    }
    std::cout << files.size() - static_cast<std::size_t>(failures) << " of " << files.size()
              << " shader entry points valid (glslangValidator)\n";
    return failures == 0 ? 0 : 1;
}

} // namespace

int main(int argc, char** argv)
{
    try {
        return validate(parseOptions(argc, argv));
    } catch (const std::exception& e) {
        std::cerr << "vplgi_validate_shaders: " << e.what() << "\n";
        return 2;
    }
}
