// GLSL loading: resolves #include "file" on the CPU (each file once, relative to the including file
// and then to the glsl/ root), injects #define lines after #version, and emits #line directives so
// that driver messages map back to `glsl/<file>:<line>: <message>`.
#pragma once

#include <epoxy/gl.h>

#include <string>
#include <vector>

#include "objects.h"

namespace vplgi::gl {

struct ShaderStage {
    GLenum type;      // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER, GL_COMPUTE_SHADER, ...
    std::string file; // relative to the glsl/ directory, e.g. "passes/gbuffer.vert"
};

struct PreprocessedSource {
    std::string text;
    std::vector<std::string> files; // source-string number -> file relative to glsl/
};

// "glsl/<file>:<line>" for a line number as a compiler reports it for `source` (the driver, or
// glslangValidator in the shader-validation test): preprocess() encodes the file in the #line numbers.
std::string sourceLocation(const PreprocessedSource& source, long reportedLine);

class ShaderLoader {
public:
    explicit ShaderLoader(std::string glslDirectory = defaultDirectory());
    // $VPLGI_GLSL_DIR if set, else the source tree's glsl/ (compiled in).
    static std::string defaultDirectory();

    // CPU only (no GL context needed): what load() hands the driver for one stage.
    PreprocessedSource preprocess(const std::string& file, const std::vector<std::string>& defines) const;
    // Compiles and links; throws Error "glsl/<file>:<line>: <message>" on the first error.
    Program load(const std::string& name, const std::vector<ShaderStage>& stages,
                 const std::vector<std::string>& defines = {}) const;

    const std::string& directory() const { return mDirectory; }

private:
    void appendFile(const std::string& file, PreprocessedSource& out, std::vector<std::string>& stack) const;
    std::string mDirectory;
};

} // namespace vplgi::gl
