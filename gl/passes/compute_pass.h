// A compute pass: one .comp program (with defines) and a dispatch over W x H (x D) invocations,
// rounded up to the program's work-group size, followed by exactly the memory barrier that what
// reads the results next needs. The caller binds buffers and images at the slots named in
// glsl/shared/bindings.h (bindStorageBuffer, bindImage below) and sets uniforms on program().
// A kernel therefore must ignore invocations beyond the size it was given (the last work-groups
// are partly outside).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "../api/shader_loader.h"
#include "../api/timer.h"

namespace vplgi {

// What reads, after the dispatch, the data the dispatch wrote with image or storage-buffer stores.
// Those stores are incoherent (GL 4.5 section 7.12.2): a later command sees them only after a
// glMemoryBarrier whose bits name how it accesses the data (section 7.13.2), so the bit follows the
// reader, not the writer. Flags combine with |.
enum class NextRead : unsigned {
    None = 0,                   // nothing reads the results (or a later barrier covers them)
    StorageBuffer = 1u << 0,    // SSBO access in a shader:  GL_SHADER_STORAGE_BARRIER_BIT
    Image = 1u << 1,            // image load/store/atomics: GL_SHADER_IMAGE_ACCESS_BARRIER_BIT
    TextureFetch = 1u << 2,     // sampled (texture(), texelFetch): GL_TEXTURE_FETCH_BARRIER_BIT
    UniformBuffer = 1u << 3,    // bound as a UBO: GL_UNIFORM_BARRIER_BIT
    VertexAttributes = 1u << 4, // a vertex buffer: GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT
    IndexBuffer = 1u << 5,      // an index buffer: GL_ELEMENT_ARRAY_BARRIER_BIT
    IndirectCommands = 1u << 6, // Draw/DispatchIndirect arguments: GL_COMMAND_BARRIER_BIT
    BufferReadback = 1u << 7,   // glGetNamedBufferSubData, glCopyNamedBufferSubData, glNamedBufferSubData,
                                // buffer mapping: GL_BUFFER_UPDATE_BARRIER_BIT
    TextureReadback = 1u << 8,  // glGetTextureImage, glTextureSubImage, glCopyTextureSubImage:
                                // GL_TEXTURE_UPDATE_BARRIER_BIT
    Framebuffer = 1u << 9,      // attached and drawn into, blitted or read: GL_FRAMEBUFFER_BARRIER_BIT
};

constexpr NextRead operator|(NextRead a, NextRead b)
{
    return static_cast<NextRead>(static_cast<unsigned>(a) | static_cast<unsigned>(b));
}

// The glMemoryBarrier bits for `reads` (0 for None).
GLbitfield memoryBarrierBits(NextRead reads);
// glMemoryBarrier(memoryBarrierBits(reads)), nothing for None.
void memoryBarrier(NextRead reads);

// Binds `buffer` (all of it) to the storage-buffer slot `binding` (a kBinding* of bindings.h).
void bindStorageBuffer(int binding, const gl::Buffer& buffer);
// Binds level `level` of `texture` to image unit `unit` (a kImage* of bindings.h), all layers.
void bindImage(int unit, const gl::Texture& texture, GLenum access, int level = 0);

class ComputePass {
public:
    ComputePass() = default;
    // `file` relative to glsl/ (e.g. "passes/importance_columns.comp"); `defines` "NAME" or "NAME=VALUE".
    ComputePass(const gl::ShaderLoader& shaders, std::string name, std::string file,
                std::vector<std::string> defines = {});
    void reloadShaders(const gl::ShaderLoader& shaders);

    // Runs ceil(invocations / workGroupSize()) work-groups per axis with the program bound, inside a
    // `timer` scope named after the pass when a timer is given (a debug group otherwise), then issues
    // the barrier for `next`. Nothing is dispatched when an axis is 0. Throws Error naming the pass
    // when the group count exceeds GL_MAX_COMPUTE_WORK_GROUP_COUNT.
    void dispatch(glm::ivec3 invocations, NextRead next, gl::PassTimer* timer = nullptr) const;
    void dispatch(int width, int height, NextRead next, gl::PassTimer* timer = nullptr) const
    {
        dispatch(glm::ivec3(width, height, 1), next, timer);
    }

    // The work-groups a dispatch of `invocations` runs (rounded up per axis).
    glm::ivec3 groupCount(glm::ivec3 invocations) const;
    // local_size_x/y/z as the driver reports them (GL_COMPUTE_WORK_GROUP_SIZE).
    glm::ivec3 workGroupSize() const { return mWorkGroupSize; }
    const gl::Program& program() const { return mProgram; }
    const std::string& name() const { return mName; }

private:
    std::string mName;
    std::string mFile;
    std::vector<std::string> mDefines;
    gl::Program mProgram;
    glm::ivec3 mWorkGroupSize{1};
    glm::ivec3 mMaxGroupCount{0}; // GL_MAX_COMPUTE_WORK_GROUP_COUNT, per axis
};

} // namespace vplgi
