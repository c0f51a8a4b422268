#include "compute_pass.h"

#include <optional>

#include "core/util/error.h"

namespace vplgi {

GLbitfield memoryBarrierBits(NextRead reads)
{
    struct Mapping {
        NextRead read;
        GLbitfield bit;
    };
    static constexpr Mapping kMappings[] = {
        {NextRead::StorageBuffer, GL_SHADER_STORAGE_BARRIER_BIT},
        {NextRead::Image, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT},
        {NextRead::TextureFetch, GL_TEXTURE_FETCH_BARRIER_BIT},
        {NextRead::UniformBuffer, GL_UNIFORM_BARRIER_BIT},
        {NextRead::VertexAttributes, GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT},
        {NextRead::IndexBuffer, GL_ELEMENT_ARRAY_BARRIER_BIT},
        {NextRead::IndirectCommands, GL_COMMAND_BARRIER_BIT},
        {NextRead::BufferReadback, GL_BUFFER_UPDATE_BARRIER_BIT},
        {NextRead::TextureReadback, GL_TEXTURE_UPDATE_BARRIER_BIT},
        {NextRead::Framebuffer, GL_FRAMEBUFFER_BARRIER_BIT},
    };
    GLbitfield bits = 0;
    for (const Mapping& m : kMappings)
        if (static_cast<unsigned>(reads) & static_cast<unsigned>(m.read)) bits |= m.bit;
    return bits;
}

void memoryBarrier(NextRead reads)
{
    if (GLbitfield bits = memoryBarrierBits(reads)) glMemoryBarrier(bits);
}

void bindStorageBuffer(int binding, const gl::Buffer& buffer)
{
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(binding), buffer.id());
}

void bindImage(int unit, const gl::Texture& texture, GLenum access, int level)
{
    glBindImageTexture(static_cast<GLuint>(unit), texture.id(), level, GL_TRUE, 0, access, texture.desc().format);
}

ComputePass::ComputePass(const gl::ShaderLoader& shaders, std::string name, std::string file,
                         std::vector<std::string> defines)
    : mName(std::move(name)), mFile(std::move(file)), mDefines(std::move(defines))
{
    reloadShaders(shaders);
}

void ComputePass::reloadShaders(const gl::ShaderLoader& shaders)
{
    mProgram = shaders.load(mName, {{GL_COMPUTE_SHADER, mFile}}, mDefines);
    GLint size[3] = {1, 1, 1};
    glGetProgramiv(mProgram.id(), GL_COMPUTE_WORK_GROUP_SIZE, size);
    mWorkGroupSize = glm::ivec3(size[0], size[1], size[2]);
    for (int axis = 0; axis < 3; ++axis)
        glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, static_cast<GLuint>(axis), &mMaxGroupCount[axis]);
}

glm::ivec3 ComputePass::groupCount(glm::ivec3 invocations) const
{
    return (glm::max(invocations, glm::ivec3(0)) + mWorkGroupSize - 1) / mWorkGroupSize;
}

void ComputePass::dispatch(glm::ivec3 invocations, NextRead next, gl::PassTimer* timer) const
{
    const glm::ivec3 groups = groupCount(invocations);
    for (int axis = 0; axis < 3; ++axis)
        require(groups[axis] <= mMaxGroupCount[axis], "compute pass " + mName + ": " + std::to_string(groups[axis]) +
                                                          " work-groups on axis " + std::to_string(axis) +
                                                          ", the limit is " + std::to_string(mMaxGroupCount[axis]));
    if (groups.x == 0 || groups.y == 0 || groups.z == 0) return;
    // A timer scope pushes its own debug group; without a timer the dispatch still gets one.
    std::optional<gl::PassTimer::Scope> scope;
    std::optional<gl::DebugGroup> group;
    if (timer)
        scope.emplace(*timer, mName);
    else
        group.emplace(mName);
    glUseProgram(mProgram.id());
    glDispatchCompute(static_cast<GLuint>(groups.x), static_cast<GLuint>(groups.y), static_cast<GLuint>(groups.z));
    glUseProgram(0);
    memoryBarrier(next);
}

} // namespace vplgi
