#include "objects.h"

#include <algorithm>
#include <vector>

#include "core/util/error.h"

namespace vplgi::gl {

namespace {

void label(GLenum identifier, GLuint id, const std::string& name)
{
    glObjectLabel(identifier, id, static_cast<GLsizei>(name.size()), name.c_str());
}

int fullMipCount(int width, int height)
{
    int levels = 1;
    for (int size = std::max(width, height); size > 1; size /= 2) ++levels;
    return levels;
}

} // namespace

Buffer::Buffer(const std::string& name, GLsizeiptr size, const void* data, bool dynamic) : mSize(size)
{
    require(size > 0, "buffer " + name + ": size must be > 0");
    glCreateBuffers(1, &mId);
    glNamedBufferStorage(mId, size, data, dynamic ? GL_DYNAMIC_STORAGE_BIT : 0);
    label(GL_BUFFER, mId, name);
}

void Buffer::upload(GLintptr offset, GLsizeiptr size, const void* data) const
{
    if (size > 0) glNamedBufferSubData(mId, offset, size, data);
}

Texture::Texture(const std::string& name, const TextureDesc& desc) : mDesc(desc)
{
    require(desc.width > 0 && desc.height > 0 && desc.layers > 0, "texture " + name + ": size must be > 0");
    if (mDesc.levels <= 0) mDesc.levels = fullMipCount(desc.width, desc.height);
    glCreateTextures(desc.target, 1, &mId);
    switch (desc.target) {
    case GL_TEXTURE_2D:
    case GL_TEXTURE_CUBE_MAP:
        glTextureStorage2D(mId, mDesc.levels, desc.format, desc.width, desc.height);
        break;
    case GL_TEXTURE_2D_ARRAY:
    case GL_TEXTURE_CUBE_MAP_ARRAY:
    case GL_TEXTURE_3D:
        glTextureStorage3D(mId, mDesc.levels, desc.format, desc.width, desc.height, desc.layers);
        break;
    default: throw Error("texture " + name + ": unsupported target");
    }
    label(GL_TEXTURE, mId, name);
}

Texture Texture::makeView(const std::string& name, const Texture& source, GLenum target, int level, int firstLayer,
                          int layers)
{
    const TextureDesc& from = source.desc();
    require(source && level >= 0 && level < from.levels && firstLayer >= 0 && layers > 0 &&
                firstLayer + layers <= from.layers,
            "texture view " + name + ": level or layers outside the source texture");
    Texture view;
    view.mDesc = from;
    view.mDesc.target = target;
    view.mDesc.width = std::max(1, from.width >> level);
    view.mDesc.height = std::max(1, from.height >> level);
    view.mDesc.layers = layers;
    view.mDesc.levels = 1;
    // glTextureView needs a name that was never bound: glGenTextures, not glCreateTextures.
    glGenTextures(1, &view.mId);
    glTextureView(view.mId, target, source.id(), from.format, static_cast<GLuint>(level), 1,
                  static_cast<GLuint>(firstLayer), static_cast<GLuint>(layers));
    glTextureParameteri(view.mId, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(view.mId, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    label(GL_TEXTURE, view.mId, name);
    return view;
}

Texture Texture::placeholder(const std::string& name, GLenum target, GLenum format)
{
    TextureDesc desc;
    desc.target = target;
    desc.format = format;
    desc.layers = target == GL_TEXTURE_CUBE_MAP_ARRAY ? 6 : 1;
    Texture texture(name, desc);
    const bool depth = format == GL_DEPTH_COMPONENT32F || format == GL_DEPTH_COMPONENT24 ||
                       format == GL_DEPTH_COMPONENT16;
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    glClearTexImage(texture.id(), 0, depth ? GL_DEPTH_COMPONENT : GL_RGBA, GL_FLOAT, zero);
    return texture;
}

Sampler::Sampler(const std::string& name, const SamplerDesc& desc)
{
    glCreateSamplers(1, &mId);
    glSamplerParameteri(mId, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(desc.minFilter));
    glSamplerParameteri(mId, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(desc.magFilter));
    glSamplerParameteri(mId, GL_TEXTURE_WRAP_S, static_cast<GLint>(desc.wrap));
    glSamplerParameteri(mId, GL_TEXTURE_WRAP_T, static_cast<GLint>(desc.wrap));
    glSamplerParameteri(mId, GL_TEXTURE_WRAP_R, static_cast<GLint>(desc.wrap));
    if (desc.maxAnisotropy > 1.0f) glSamplerParameterf(mId, GL_TEXTURE_MAX_ANISOTROPY, desc.maxAnisotropy);
    label(GL_SAMPLER, mId, name);
}

Framebuffer::Framebuffer(const std::string& name) : mName(name)
{
    glCreateFramebuffers(1, &mId);
    label(GL_FRAMEBUFFER, mId, name);
}

void Framebuffer::attach(GLenum attachment, const Texture& texture, int level, int layer) const
{
    if (layer < 0) glNamedFramebufferTexture(mId, attachment, texture.id(), level);
    else glNamedFramebufferTextureLayer(mId, attachment, texture.id(), level, layer);
}

void Framebuffer::setDrawBuffers(int colorCount) const
{
    std::vector<GLenum> buffers;
    for (int i = 0; i < colorCount; ++i) buffers.push_back(GL_COLOR_ATTACHMENT0 + i);
    if (buffers.empty()) glNamedFramebufferDrawBuffer(mId, GL_NONE);
    else glNamedFramebufferDrawBuffers(mId, static_cast<GLsizei>(buffers.size()), buffers.data());
}

void Framebuffer::checkComplete() const
{
    GLenum status = glCheckNamedFramebufferStatus(mId, GL_FRAMEBUFFER);
    require(status == GL_FRAMEBUFFER_COMPLETE,
            "framebuffer " + mName + " incomplete (status 0x" + [status] {
                char b[16];
                std::snprintf(b, sizeof b, "%04x", status);
                return std::string(b);
            }() + ")");
}

VertexArray::VertexArray(const std::string& name)
{
    glCreateVertexArrays(1, &mId);
    label(GL_VERTEX_ARRAY, mId, name);
}

Program::Program(const std::string& name, GLuint linkedProgram) : mName(name)
{
    mId = linkedProgram;
    label(GL_PROGRAM, mId, name);
}

Query::Query(const std::string& name, GLenum target)
{
    glCreateQueries(target, 1, &mId);
    label(GL_QUERY, mId, name);
}

std::vector<float> readTextureRGBA32F(const Texture& texture, int layer)
{
    const int w = texture.width(), h = texture.height();
    std::vector<float> pixels(static_cast<std::size_t>(w) * h * 4);
    glGetTextureSubImage(texture.id(), 0, 0, 0, layer, w, h, 1, GL_RGBA, GL_FLOAT,
                         static_cast<GLsizei>(pixels.size() * sizeof(float)), pixels.data());
    return pixels;
}

void uploadTopDownRGBA32F(const Texture& texture, const std::vector<float>& topDownPixels, int width, int height)
{
    const std::size_t row = static_cast<std::size_t>(width) * 4;
    std::vector<float> flipped(topDownPixels.size());
    for (int y = 0; y < height; ++y)
        std::copy_n(&topDownPixels[static_cast<std::size_t>(height - 1 - y) * row], row,
                    &flipped[static_cast<std::size_t>(y) * row]);
    glTextureSubImage2D(texture.id(), 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, flipped.data());
}

} // namespace vplgi::gl
