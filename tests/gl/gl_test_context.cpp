#include "gl_test_context.h"

#include <filesystem>
#include <memory>

#include "gl/api/context.h"

namespace vplgi::test {

void ensureGLContext()
{
    static std::unique_ptr<gl::Context> context = [] {
        gl::ContextOptions options;
        options.debug = true;
        options.throwOnHighSeverity = true;
        return gl::createHeadlessContext(options);
    }();
    context->makeCurrent();
}

const gl::ShaderLoader& shaders()
{
    static gl::ShaderLoader loader(std::string(VPLGI_SOURCE_DIR) + "/glsl");
    return loader;
}

std::string saveTestImage(const std::string& name, const ImageRGBA32F& image)
{
    std::filesystem::create_directories(VPLGI_TEST_OUTPUT_DIR);
    std::string path = std::string(VPLGI_TEST_OUTPUT_DIR) + "/" + name + ".exr";
    writeImage(path, image);
    return path;
}

std::string objectLabel(GLenum identifier, GLuint id)
{
    char label[256] = {};
    GLsizei length = 0;
    glGetObjectLabel(identifier, id, sizeof label, &length, label);
    return std::string(label, static_cast<std::size_t>(length));
}

} // namespace vplgi::test
