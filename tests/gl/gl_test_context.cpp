#include "gl_test_context.h"

#include <filesystem>
#include <memory>

#include "core/util/params.h"
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

bool onHardwareGPU()
{
    ensureGLContext();
    return !gl::isSoftwareRenderer();
}

const gl::ShaderLoader& shaders()
{
    static gl::ShaderLoader loader(std::string(VPLGI_SOURCE_DIR) + "/glsl");
    return loader;
}

gl::Texture uploadR32F(const std::string& label, const std::vector<float>& texels, int width, int height, int levels)
{
    gl::TextureDesc desc;
    desc.format = GL_R32F;
    desc.width = width;
    desc.height = height;
    desc.levels = levels;
    gl::Texture texture(label, desc);
    glTextureSubImage2D(texture.id(), 0, 0, 0, width, height, GL_RED, GL_FLOAT, texels.data());
    return texture;
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

std::vector<glm::vec4> runComputeProbe(const std::string& name, const std::string& file, const void* cases,
                                       std::size_t caseBytes, int count, int resultsPerCase)
{
    gl::Program program = gl::ShaderLoader(std::string(VPLGI_SOURCE_DIR) + "/glsl")
                              .load(name, {{GL_COMPUTE_SHADER, "../tests/gl/glsl/" + file}});
    gl::Buffer input(name + " cases", static_cast<GLsizeiptr>(caseBytes), cases);
    const std::size_t results = static_cast<std::size_t>(count) * static_cast<std::size_t>(resultsPerCase);
    gl::Buffer output(name + " results", static_cast<GLsizeiptr>(results * sizeof(glm::vec4)));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, input.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, output.id());
    program.set("uCount", count);
    glUseProgram(program.id());
    glDispatchCompute(static_cast<GLuint>((count + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> out(results);
    glGetNamedBufferSubData(output.id(), 0, output.size(), out.data());
    glUseProgram(0);
    return out;
}

std::unique_ptr<Renderer> makeTechniqueRenderer(const Scene& scene, const std::string& name,
                                                const Settings& settings)
{
    std::unique_ptr<Technique> technique = createTechnique(name);
    RendererParams params;
    ParamSetter setter(settings);
    params.visitParams(setter);
    technique->visitParams(setter);
    setter.finish();
    return std::make_unique<Renderer>(shaders(), scene, params, std::move(technique));
}

ImageRGBA32F renderIndirect(Renderer& renderer, const Camera& camera, int width, int height)
{
    renderer.renderFrame(camera, width, height);
    ImageRGBA32F indirect = renderer.readRadiance();
    const ImageRGBA32F direct = renderer.readDirect();
    for (std::size_t i = 0; i < indirect.pixels.size(); ++i)
        if (i % 4 != 3) indirect.pixels[i] -= direct.pixels[i];
    return indirect;
}

} // namespace vplgi::test
