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
// With --resource-needs it also counts what the application's shaders (those under GLSL_DIR) bind:
// the binding points glsl/shared/bindings.h numbers and, per stage, the storage and uniform blocks,
// samplers and images the busiest entry point's live code uses (glslangValidator -l -q's reflection),
// and fails unless each equals gl::kResourceNeeds (gl/api/limits.h), which every context is checked
// against when it is made.
// Exit status: 0 all valid, 1 some invalid (or a resource count differs), 2 bad usage or nothing to
// validate.
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
#include "gl/api/limits.h"
#include "gl/api/shader_loader.h"

namespace fs = std::filesystem;
using namespace vplgi;

namespace {

struct Options {
    std::string glslang;
    std::string root;
    std::vector<std::string> directories;
    std::map<std::string, std::vector<std::string>> defines; // entry point -> NAME=VALUE list
    bool resourceNeeds = false; // compare what the shaders bind with gl::kResourceNeeds
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
        } else if (arg == "--resource-needs") {
            options.resourceNeeds = true;
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
            "usage: vplgi_validate_shaders --glslang PATH --root GLSL_DIR [--define FILE:NAME[=VALUE]]... [--resource-needs] DIR...");
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

// What one stage uses of the per-stage resources GL limits (GL_MAX_<STAGE>_SHADER_STORAGE_BLOCKS,
// _UNIFORM_BLOCKS, _TEXTURE_IMAGE_UNITS, _IMAGE_UNIFORMS), counted from glslangValidator's reflection
// (`-l -q`: only what the entry point's live code reaches, as a driver counts it).
// Parses `glslangValidator -l -q`'s reflection. Blocks are listed under "Uniform block reflection"
// (storage blocks too, in Debian 12's glslang) or "Buffer block reflection"; a block is a storage
// block when the source declares `buffer <Name>`. Opaque uniforms are the "Uniform reflection" rows
// with a binding; GL's image types are 0x904C-0x906C, every other opaque type is a sampler.
gl::StageResources countResources(const std::string& reflection, const std::string& source)
{
    gl::StageResources counts;
    std::istringstream lines(reflection);
    std::string line, section;
    static const std::regex row(R"(^([A-Za-z_][A-Za-z0-9_.\[\]]*): offset (-?\d+), type ([0-9a-f]+), size (\d+),.* binding (-?\d+),)");
    while (std::getline(lines, line)) {
        if (!line.empty() && line.back() == ':' && line.find(' ') != std::string::npos) {
            section = line;
            continue;
        }
        std::smatch m;
        if (!std::regex_search(line, m, row)) continue;
        const std::string name = m[1].str();
        if (section == "Uniform block reflection:" || section == "Buffer block reflection:") {
            const std::regex declared("\\bbuffer\\s+" + name + "\\b");
            (std::regex_search(source, declared) ? counts.storageBlocks : counts.uniformBlocks) += 1;
        } else if (section == "Uniform reflection:" && std::stol(m[2].str()) == -1 && std::stol(m[5].str()) >= 0) {
            const unsigned long type = std::stoul(m[3].str(), nullptr, 16);
            const int units = std::stoi(m[4].str()); // an array of samplers takes one unit per element
            (type >= 0x904C && type <= 0x906C ? counts.images : counts.samplers) += units;
        }
    }
    return counts;
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

// The binding points glsl/shared/bindings.h numbers: one past the highest storage buffer, uniform
// buffer, texture unit and image unit ("// 6 units: ..." after a name: it takes six from there). A
// buffer binding's comment says which kind it is ("// SSBO ..." or "// UBO ...").
gl::ResourceCounts countBindingPoints(const std::string& rootDirectory, std::vector<std::string>& problems)
{
    const fs::path path = fs::path(rootDirectory) / "shared" / "bindings.h";
    std::ifstream file(path);
    require(file.good(), path.string() + ": cannot read");
    static const std::regex constant(R"(^VPLGI_CONST int k(Binding|Unit|Image)\w+ = (\d+);\s*(//\s*(.*))?$)");
    static const std::regex span(R"(^(\d+) units)");
    gl::ResourceCounts counts;
    std::string line;
    while (std::getline(file, line)) {
        std::smatch m;
        if (!std::regex_match(line, m, constant)) continue;
        const std::string comment = m[4].str();
        std::smatch s;
        const int end = std::stoi(m[2].str()) + (std::regex_search(comment, s, span) ? std::stoi(s[1].str()) : 1);
        int* count = nullptr;
        if (m[1].str() == "Unit") {
            count = &counts.textureUnits;
        } else if (m[1].str() == "Image") {
            count = &counts.imageUnits;
        } else if (comment.rfind("SSBO", 0) == 0) {
            count = &counts.storageBufferBindings;
        } else if (comment.rfind("UBO", 0) == 0) {
            count = &counts.uniformBufferBindings;
        } else {
            problems.push_back(path.string() + ": a buffer binding whose comment does not start with SSBO or UBO: " + line);
            continue;
        }
        *count = std::max(*count, end);
    }
    return counts;
}

// Compares what was counted with gl::kResourceNeeds, row by row; prints the table.
int checkResourceNeeds(const gl::ResourceCounts& counted, std::vector<std::string> problems)
{
    const gl::ResourceCounts& needs = gl::kResourceNeeds;
    std::cout << "resources (counted here / gl::kResourceNeeds, gl/api/limits.h):\n";
    auto row = [&](const std::string& what, int count, int need) {
        std::cout << "  " << what << ": " << count << " / " << need << "\n";
        if (count != need)
            problems.push_back(what + ": counted " + std::to_string(count) + ", kResourceNeeds says " +
                               std::to_string(need) + " (update gl/api/limits.h)");
    };
    row("storage buffer binding points", counted.storageBufferBindings, needs.storageBufferBindings);
    row("uniform buffer binding points", counted.uniformBufferBindings, needs.uniformBufferBindings);
    row("texture units", counted.textureUnits, needs.textureUnits);
    row("image units", counted.imageUnits, needs.imageUnits);
    const std::pair<const char*, gl::StageResources gl::ResourceCounts::*> stages[] = {
        {"vertex", &gl::ResourceCounts::vertex}, {"fragment", &gl::ResourceCounts::fragment},
        {"compute", &gl::ResourceCounts::compute}};
    for (const auto& [name, stage] : stages) {
        const gl::StageResources& c = counted.*stage;
        const gl::StageResources& n = needs.*stage;
        const std::string s = name;
        row(s + " storage blocks", c.storageBlocks, n.storageBlocks);
        row(s + " uniform blocks", c.uniformBlocks, n.uniformBlocks);
        row(s + " samplers", c.samplers, n.samplers);
        row(s + " images", c.images, n.images);
    }
    for (const std::string& p : problems)
        std::cout << "FAIL " << p << "\n";
    return problems.empty() ? 0 : 1;
}

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
    // The busiest entry point per stage, over the application's shaders (those under --root; the
    // tests' probes do not count).
    std::vector<std::string> problems;
    gl::ResourceCounts counted = options.resourceNeeds ? countBindingPoints(options.root, problems) : gl::ResourceCounts{};
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
            continue;
        }
        RunResult reflected = runCommand(shellQuote(options.glslang) + " -l -q " + shellQuote(tempFile.string()));
        if (reflected.status != 0) {
            std::cout << "FAIL " << label << ": glslangValidator -l -q (reflection) exit status " << reflected.status
                      << "\n" << reflected.output;
            ++failures;
            continue;
        }
        const gl::StageResources r = countResources(reflected.output, source.text);
        std::cout << "ok   " << label << " (storage blocks " << r.storageBlocks << ", uniform blocks " << r.uniformBlocks
                  << ", samplers " << r.samplers << ", images " << r.images << ")\n"
                  << log;
        const std::string stage = fs::path(file).extension().string();
        gl::StageResources* most = stage == ".vert"   ? &counted.vertex
                                   : stage == ".frag" ? &counted.fragment
                                   : stage == ".comp" ? &counted.compute
                                                      : nullptr;
        if (file.rfind("../", 0) == 0) continue; // a test's probe, outside --root
        if (!most) {
            problems.push_back(file + ": a stage gl::kResourceNeeds does not cover");
            continue;
        }
        most->storageBlocks = std::max(most->storageBlocks, r.storageBlocks);
        most->uniformBlocks = std::max(most->uniformBlocks, r.uniformBlocks);
        most->samplers = std::max(most->samplers, r.samplers);
        most->images = std::max(most->images, r.images);
    }
    std::cout << files.size() - static_cast<std::size_t>(failures) << " of " << files.size()
              << " shader entry points valid (glslangValidator)\n";
    const int resources = options.resourceNeeds ? checkResourceNeeds(counted, problems) : 0;
    return failures == 0 && resources == 0 ? 0 : 1;
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
