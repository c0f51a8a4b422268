// The GLSL loader: includes, defines, and error messages that point at glsl/<file>:<line>.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "core/util/error.h"
#include "gl/api/debug.h"
#include "gl_test_context.h"

using namespace vplgi;
namespace fs = std::filesystem;

namespace {

struct ShaderDirectory {
    fs::path root;
    ShaderDirectory()
    {
        root = fs::temp_directory_path() / ("vplgi-glsl-" + std::to_string(::getpid()));
        fs::remove_all(root);
        fs::create_directories(root / "lib");
    }
    ~ShaderDirectory() { fs::remove_all(root); }
    void write(const std::string& file, const std::string& text) const
    {
        std::ofstream(root / file) << text;
    }
};

} // namespace

TEST_CASE("includes are resolved once and defines land after #version", "[shaders]")
{
    test::ensureGLContext();
    ShaderDirectory dir;
    dir.write("lib/a.glsl", "#include \"b.glsl\"\nfloat a() { return b() + 1.0; }\n");
    dir.write("lib/b.glsl", "float b() { return VALUE; }\n");
    dir.write("main.comp", "#version 450 core\nlayout(local_size_x = 1) in;\n#include \"lib/a.glsl\"\n#include \"lib/b.glsl\"\n"
                           "layout(std430, binding = 0) buffer Out { float result; };\nvoid main() { result = a(); }\n");
    gl::ShaderLoader loader(dir.root.string());
    gl::PreprocessedSource source = loader.preprocess("main.comp", {"VALUE=41.0"});
    CHECK(source.text.rfind("#version 450 core\n#define VALUE 41.0\n", 0) == 0);
    CHECK(source.files == std::vector<std::string>{"main.comp", "lib/a.glsl", "lib/b.glsl"});

    gl::Program program = loader.load("include test", {{GL_COMPUTE_SHADER, "main.comp"}}, {"VALUE=41.0"});
    gl::Buffer out("result", sizeof(float));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, out.id());
    glUseProgram(program.id());
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    float result = 0.0f;
    glGetNamedBufferSubData(out.id(), 0, sizeof result, &result);
    CHECK(result == 42.0f);
    gl::checkDebugMessages();
}

TEST_CASE("a compile error reports the included file and line", "[shaders]")
{
    test::ensureGLContext();
    ShaderDirectory dir;
    dir.write("lib/broken.glsl", "// line 1\n// line 2\nfloat broken() { return undefinedThing; }\n");
    dir.write("main.frag", "#version 450 core\n#include \"lib/broken.glsl\"\nout vec4 color;\n"
                           "void main() { color = vec4(broken()); }\n");
    gl::ShaderLoader loader(dir.root.string());
    CHECK_THROWS_WITH(loader.load("broken", {{GL_FRAGMENT_SHADER, "main.frag"}}),
                      Catch::StartsWith("glsl/lib/broken.glsl:3: ") && Catch::Contains("undefinedThing"));
    dir.write("main2.frag", "#version 450 core\nout vec4 color;\n\nvoid main() { color = vec3(1.0); }\n");
    CHECK_THROWS_WITH(loader.load("broken2", {{GL_FRAGMENT_SHADER, "main2.frag"}}), Catch::StartsWith("glsl/main2.frag:4: "));
    dir.write("main3.frag", "#version 450 core\n#include \"lib/missing.glsl\"\n");
    CHECK_THROWS_WITH(loader.load("broken3", {{GL_FRAGMENT_SHADER, "main3.frag"}}),
                      Catch::Contains("glsl/main3.frag:2: cannot find include"));
}

TEST_CASE("every project shader compiles", "[shaders]")
{
    test::ensureGLContext();
    const gl::ShaderLoader& loader = test::shaders();
    CHECK_NOTHROW(loader.load("gbuffer", {{GL_VERTEX_SHADER, "passes/gbuffer.vert"}, {GL_FRAGMENT_SHADER, "passes/gbuffer.frag"}}));
    CHECK_NOTHROW(loader.load("direct", {{GL_VERTEX_SHADER, "lib/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "passes/direct.frag"}}));
    CHECK_NOTHROW(loader.load("tonemap", {{GL_VERTEX_SHADER, "lib/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "passes/tonemap.frag"}}));
    CHECK_NOTHROW(loader.load("shadow", {{GL_VERTEX_SHADER, "passes/shadow.vert"}, {GL_FRAGMENT_SHADER, "passes/shadow_point.frag"}}));
}
