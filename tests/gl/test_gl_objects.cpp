// GL wrappers and the structs shared between C++ and GLSL, checked against the driver.
#include <catch2/catch.hpp>

#include <cstddef>
#include <random>

#include "core/util/error.h"
#include "gl/api/debug.h"
#include "gl/api/objects.h"
#include "gl/passes/compute_pass.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/brdf.h"
#include "glsl/shared/tonemap.h"
#include "gl_test_context.h"

using namespace vplgi;

namespace {

gl::ShaderLoader probeLoader()
{
    return gl::ShaderLoader(std::string(VPLGI_SOURCE_DIR) + "/glsl");
}

} // namespace

TEST_CASE("buffers and textures are created, labelled and round-trip data", "[gl]")
{
    test::ensureGLContext();
    const float data[4] = {1.0f, 2.0f, 3.0f, 4.0f};
    gl::Buffer buffer("test buffer", sizeof data, data);
    CHECK(test::objectLabel(GL_BUFFER, buffer.id()) == "test buffer");
    const float update = 9.0f;
    buffer.upload(sizeof(float), sizeof update, &update);
    float back[4] = {};
    glGetNamedBufferSubData(buffer.id(), 0, sizeof back, back);
    CHECK(back[1] == 9.0f);
    CHECK(back[3] == 4.0f);

    gl::TextureDesc desc;
    desc.format = GL_RGBA32F;
    desc.width = 4;
    desc.height = 2;
    gl::Texture texture("test texture", desc);
    CHECK(test::objectLabel(GL_TEXTURE, texture.id()) == "test texture");
    std::vector<float> pixels(4 * 2 * 4);
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<float>(i);
    glTextureSubImage2D(texture.id(), 0, 0, 0, 4, 2, GL_RGBA, GL_FLOAT, pixels.data());
    CHECK(gl::readTextureRGBA32F(texture) == pixels);

    gl::Texture moved = std::move(texture);
    CHECK_FALSE(texture);
    CHECK(moved);
    gl::checkDebugMessages();
}

TEST_CASE("an incomplete framebuffer is an error naming it", "[gl]")
{
    test::ensureGLContext();
    gl::Framebuffer empty("nothing attached");
    empty.setDrawBuffers(1);
    CHECK_THROWS_WITH(empty.checkComplete(), Catch::Contains("framebuffer nothing attached incomplete"));
}

TEST_CASE("a GL error is reported by checkDebugMessages", "[gl]")
{
    test::ensureGLContext();
    gl::checkDebugMessages();
    const int before = gl::highSeverityMessageCount();
    glBindTextureUnit(0, 987654); // not a texture name
    CHECK(gl::highSeverityMessageCount() > before);
    CHECK_THROWS_AS(gl::checkDebugMessages(), Error);
    // glGetError keeps the flag until read (NVIDIA's driver: the next test's glGetError saw it).
    while (glGetError() != GL_NO_ERROR) {
    }
}

TEST_CASE("shared struct offsets match the driver's std140/std430 layout", "[gl]")
{
    test::ensureGLContext();
    gl::Program program = probeLoader().load("layout probe", {{GL_COMPUTE_SHADER, "../tests/gl/glsl/layout_probe.comp"}});
    auto uniformOffset = [&](const char* name) {
        GLuint index = GL_INVALID_INDEX;
        glGetUniformIndices(program.id(), 1, &name, &index);
        REQUIRE(index != GL_INVALID_INDEX);
        GLint offset = -1;
        glGetActiveUniformsiv(program.id(), 1, &index, GL_UNIFORM_OFFSET, &offset);
        return offset;
    };
    using shared::FrameUniforms;
    CHECK(uniformOffset("frame.clipFromWorld") == offsetof(FrameUniforms, clipFromWorld));
    CHECK(uniformOffset("frame.viewFromWorld") == offsetof(FrameUniforms, viewFromWorld));
    CHECK(uniformOffset("frame.worldFromClip") == offsetof(FrameUniforms, worldFromClip));
    CHECK(uniformOffset("frame.cameraPosition") == offsetof(FrameUniforms, cameraPosition));
    CHECK(uniformOffset("frame.viewport") == offsetof(FrameUniforms, viewport));
    CHECK(uniformOffset("frame.counts") == offsetof(FrameUniforms, counts));
    CHECK(uniformOffset("frame.shadow") == offsetof(FrameUniforms, shadow));
    CHECK(uniformOffset("frame.toneMap") == offsetof(FrameUniforms, toneMap));
    GLint blockSize = 0;
    glGetActiveUniformBlockiv(program.id(), glGetUniformBlockIndex(program.id(), "FrameBlock"), GL_UNIFORM_BLOCK_DATA_SIZE,
                              &blockSize);
    CHECK(blockSize == static_cast<GLint>(sizeof(FrameUniforms)));

    auto bufferVariable = [&](const char* name, GLenum property) {
        GLuint index = glGetProgramResourceIndex(program.id(), GL_BUFFER_VARIABLE, name);
        REQUIRE(index != GL_INVALID_INDEX);
        GLint value = -1;
        glGetProgramResourceiv(program.id(), GL_BUFFER_VARIABLE, index, 1, &property, 1, nullptr, &value);
        return value;
    };
    using shared::PointEmitter;
    CHECK(bufferVariable("pointEmitters[0].intensity", GL_OFFSET) == offsetof(PointEmitter, intensity));
    CHECK(bufferVariable("pointEmitters[0].cosInner", GL_OFFSET) == offsetof(PointEmitter, cosInner));
    CHECK(bufferVariable("pointEmitters[0].positionProfile", GL_TOP_LEVEL_ARRAY_STRIDE) ==
          sizeof(PointEmitter));
    CHECK(bufferVariable("directionalEmitters[0].irradiance", GL_OFFSET) ==
          offsetof(shared::DirectionalEmitter, irradiance));
    CHECK(bufferVariable("directionalEmitters[0].direction", GL_TOP_LEVEL_ARRAY_STRIDE) ==
          sizeof(shared::DirectionalEmitter));
}

TEST_CASE("the BRDF and tone map give the same values in GLSL and C++", "[gl][brdf]")
{
    test::ensureGLContext();
    struct Case {
        glm::vec4 baseColorMetallic, roughnessSpecular, n, v, l;
    };
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    auto direction = [&] {
        glm::vec3 d(u(rng) * 2 - 1, u(rng), u(rng) * 2 - 1); // upper hemisphere mostly
        return glm::normalize(d + glm::vec3(0, 0.05f, 0));
    };
    std::vector<Case> cases;
    for (int i = 0; i < 256; ++i) {
        Case c;
        c.baseColorMetallic = glm::vec4(u(rng), u(rng), u(rng), i % 3 == 0 ? 1.0f : u(rng));
        c.roughnessSpecular = glm::vec4(i % 5 == 0 ? 0.0f : u(rng), i % 4 == 0 ? 0.0f : 1.0f, 0, 0);
        c.n = glm::vec4(0, 1, 0, 0);
        c.v = glm::vec4(direction(), 0);
        c.l = glm::vec4(direction(), 0);
        cases.push_back(c);
    }
    ComputePass probe(probeLoader(), "brdf probe", "../tests/gl/glsl/brdf_probe.comp");
    gl::Buffer input("brdf cases", static_cast<GLsizeiptr>(cases.size() * sizeof(Case)), cases.data());
    gl::Buffer output("brdf results", static_cast<GLsizeiptr>(cases.size() * 2 * sizeof(glm::vec4)));
    bindStorageBuffer(0, input);
    bindStorageBuffer(1, output);
    probe.program().set("uCount", static_cast<int>(cases.size()));
    probe.dispatch(static_cast<int>(cases.size()), 1, NextRead::BufferReadback);
    std::vector<glm::vec4> results(cases.size() * 2);
    glGetNamedBufferSubData(output.id(), 0, output.size(), results.data());
    int nonZero = 0;
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const Case& c = cases[i];
        shared::SurfaceMaterial m{glm::vec3(c.baseColorMetallic), c.baseColorMetallic.a, c.roughnessSpecular.x,
                                  c.roughnessSpecular.y};
        glm::vec3 f = shared::evaluateBRDF(m, glm::vec3(c.n), glm::vec3(c.v), glm::vec3(c.l));
        glm::vec3 t = shared::toneMapReinhard(f, 0.7f);
        for (int k = 0; k < 3; ++k) {
            CHECK(results[2 * i][k] == Approx(f[k]).epsilon(1e-3).margin(1e-5));
            CHECK(results[2 * i + 1][k] == Approx(shared::encodeSRGB(t[k])).epsilon(1e-4).margin(1e-5));
        }
        if (f.x > 0.0f) ++nonZero;
    }
    CHECK(nonZero > 100); // the cases exercise lit configurations, not just zeros
}
