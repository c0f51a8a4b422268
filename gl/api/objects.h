// RAII, move-only GL 4.5 objects created with DSA (glCreate*) from a descriptor plus a name; the
// name becomes the object's KHR_debug label. Nothing here binds; binding happens at draw time.
#pragma once

#include <epoxy/gl.h>

#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace vplgi::gl {

// Owns one GL name; DeleteFn releases it.
template <typename Tag>
class Object {
public:
    Object() = default;
    ~Object() { reset(); }
    Object(Object&& other) noexcept : mId(std::exchange(other.mId, 0)) {}
    Object& operator=(Object&& other) noexcept
    {
        if (this != &other) {
            reset();
            mId = std::exchange(other.mId, 0);
        }
        return *this;
    }
    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;

    GLuint id() const { return mId; }
    explicit operator bool() const { return mId != 0; }
    void reset()
    {
        if (mId) Tag::destroy(mId);
        mId = 0;
    }

protected:
    GLuint mId = 0;
};

struct BufferTag { static void destroy(GLuint id) { glDeleteBuffers(1, &id); } };
struct TextureTag { static void destroy(GLuint id) { glDeleteTextures(1, &id); } };
struct SamplerTag { static void destroy(GLuint id) { glDeleteSamplers(1, &id); } };
struct FramebufferTag { static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); } };
struct VertexArrayTag { static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); } };
struct ProgramTag { static void destroy(GLuint id) { glDeleteProgram(id); } };
struct QueryTag { static void destroy(GLuint id) { glDeleteQueries(1, &id); } };

// Immutable-storage buffer; `dynamic` allows later upload() calls.
class Buffer : public Object<BufferTag> {
public:
    Buffer() = default;
    Buffer(const std::string& name, GLsizeiptr size, const void* data = nullptr, bool dynamic = true);
    void upload(GLintptr offset, GLsizeiptr size, const void* data) const;
    GLsizeiptr size() const { return mSize; }

private:
    GLsizeiptr mSize = 0;
};

struct TextureDesc {
    GLenum target = GL_TEXTURE_2D;      // 2D, 2D_ARRAY, CUBE_MAP_ARRAY ...
    GLenum format = GL_RGBA8;           // sized internal format
    int width = 1;
    int height = 1;
    int layers = 1;                     // array layers (for cube-map arrays: 6 * cubes)
    int levels = 1;                     // mip levels; 0 = full chain
};

class Texture : public Object<TextureTag> {
public:
    Texture() = default;
    Texture(const std::string& name, const TextureDesc& desc);
    // A texture view (GL 4.3) of `layers` layers from `firstLayer` and one mip level of `source`,
    // as `target` (e.g. a cube-map array's faces as a 2D array), same format; nearest filtering.
    static Texture makeView(const std::string& name, const Texture& source, GLenum target, int level, int firstLayer,
                            int layers);
    // A 1x1 texture of `target` (one cube, six layers, for cube-map arrays) cleared to zero, bound where
    // a program declares a sampler that this draw does not read: GL's texture 0 there has no levels, and
    // NVIDIA's driver reports every such draw (seen on an H200, docs/conformance.md "scripts/gpu-bench").
    static Texture placeholder(const std::string& name, GLenum target, GLenum format);
    const TextureDesc& desc() const { return mDesc; }
    int width() const { return mDesc.width; }
    int height() const { return mDesc.height; }

private:
    TextureDesc mDesc;
};

struct SamplerDesc {
    GLenum minFilter = GL_LINEAR;
    GLenum magFilter = GL_LINEAR;
    GLenum wrap = GL_CLAMP_TO_EDGE;
    float maxAnisotropy = 1.0f;
};

class Sampler : public Object<SamplerTag> {
public:
    Sampler() = default;
    Sampler(const std::string& name, const SamplerDesc& desc);
};

class Framebuffer : public Object<FramebufferTag> {
public:
    Framebuffer() = default;
    explicit Framebuffer(const std::string& name);
    // layer < 0 attaches all layers (layered rendering).
    void attach(GLenum attachment, const Texture& texture, int level = 0, int layer = -1) const;
    void setDrawBuffers(int colorCount) const;
    // Throws Error naming the framebuffer when incomplete.
    void checkComplete() const;

private:
    std::string mName;
};

class VertexArray : public Object<VertexArrayTag> {
public:
    VertexArray() = default;
    explicit VertexArray(const std::string& name);
};

class Program : public Object<ProgramTag> {
public:
    Program() = default;
    Program(const std::string& name, GLuint linkedProgram);
    GLint uniformLocation(const char* uniform) const { return glGetUniformLocation(mId, uniform); }
    void set(const char* uniform, int value) const { glProgramUniform1i(mId, uniformLocation(uniform), value); }
    void set(const char* uniform, float value) const { glProgramUniform1f(mId, uniformLocation(uniform), value); }
    void set(const char* uniform, const glm::vec2& v) const { glProgramUniform2f(mId, uniformLocation(uniform), v.x, v.y); }
    void set(const char* uniform, const glm::vec3& v) const
    {
        glProgramUniform3f(mId, uniformLocation(uniform), v.x, v.y, v.z);
    }
    void set(const char* uniform, const glm::vec4& v) const
    {
        glProgramUniform4f(mId, uniformLocation(uniform), v.x, v.y, v.z, v.w);
    }
    void set(const char* uniform, const glm::mat4& m) const
    {
        glProgramUniformMatrix4fv(mId, uniformLocation(uniform), 1, GL_FALSE, &m[0][0]);
    }
    const std::string& name() const { return mName; }

private:
    std::string mName;
};

class Query : public Object<QueryTag> {
public:
    Query() = default;
    Query(const std::string& name, GLenum target);
};

// Uploads `data` to `buffer`, first (re)creating it when it is missing or too small; an empty
// vector still leaves a valid one-element buffer so the binding point is never unbound.
template <typename T>
void uploadVector(Buffer& buffer, const std::string& name, const std::vector<T>& data)
{
    const GLsizeiptr size = static_cast<GLsizeiptr>((data.empty() ? 1 : data.size()) * sizeof(T));
    if (!buffer || buffer.size() < size) buffer = Buffer(name, size);
    buffer.upload(0, static_cast<GLsizeiptr>(data.size() * sizeof(T)), data.data());
}

// Reads level 0 of a 2D texture (layer `layer` of an array) as RGBA floats, rows bottom to top (GL order).
std::vector<float> readTextureRGBA32F(const Texture& texture, int layer = 0);
// Uploads width x height RGBA float pixels given with rows top to bottom (as CPU images are) into
// level 0 of a 2D texture, whose rows run bottom to top.
void uploadTopDownRGBA32F(const Texture& texture, const std::vector<float>& topDownPixels, int width, int height);

} // namespace vplgi::gl
