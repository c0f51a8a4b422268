#include "importance_sampler.h"

#include <algorithm>
#include <optional>

#include "core/util/error.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/importance.h"

namespace vplgi {

ImportanceSampler::ImportanceSampler(const gl::ShaderLoader& shaders, std::string name)
    : mName(std::move(name)), mColumnPass(shaders, mName + ": column sums", "passes/importance_columns.comp"),
      mMarginalPass(shaders, mName + ": marginal sums", "passes/importance_marginal.comp"),
      mSamplePass(shaders, mName + ": draws", "passes/importance_sample.comp"),
      mMipsPass(shaders, mName + ": box mips", "passes/importance_mips.comp")
{
}

void ImportanceSampler::buildMips(const gl::Texture& importance, NextRead next, gl::PassTimer* timer) const
{
    const gl::TextureDesc& desc = importance.desc();
    require(desc.format == GL_R32F && desc.target == GL_TEXTURE_2D,
            mName + ": the importance map must be a GL_R32F 2D texture");
    for (int level = 1; level < desc.levels; ++level) {
        const int width = desc.width >> level, height = desc.height >> level;
        require(width >= 1 && height >= 1 && desc.width == width << level && desc.height == height << level,
                mName + ": box mips need sides that halve exactly at every level, not " +
                    std::to_string(desc.width) + " x " + std::to_string(desc.height) + " with " +
                    std::to_string(desc.levels) + " levels");
        bindImage(shared::kImageImportance, importance, GL_READ_ONLY, level - 1);
        bindImage(shared::kImageImportanceCoarser, importance, GL_WRITE_ONLY, level);
        mMipsPass.dispatch(width, height, level + 1 < desc.levels ? NextRead::Image : next, timer);
    }
}

void ImportanceSampler::build(const gl::Texture& importance, NextRead next, gl::PassTimer* timer)
{
    require(importance.desc().format == GL_R32F && importance.desc().target == GL_TEXTURE_2D,
            mName + ": the importance map must be a GL_R32F 2D texture");
    const int width = importance.width();
    const int height = importance.height();
    if (width != mWidth || height != mHeight) {
        const auto texels = static_cast<GLsizeiptr>(width) * height;
        mColumns = gl::Buffer(mName + " column sums", texels * static_cast<GLsizeiptr>(sizeof(float)));
        mMarginal = gl::Buffer(mName + " marginal sums", width * static_cast<GLsizeiptr>(sizeof(float)));
        mWidth = width;
        mHeight = height;
    }
    std::optional<gl::PassTimer::Scope> scope;
    if (timer) scope.emplace(*timer, mName + ": build");
    bindImage(shared::kImageImportance, importance, GL_READ_ONLY);
    bindStorageBuffer(shared::kBindingImportanceColumns, mColumns);
    bindStorageBuffer(shared::kBindingImportanceMarginal, mMarginal);
    mColumnPass.dispatch(width, 1, NextRead::StorageBuffer, timer);
    mMarginalPass.program().set("uWidth", width);
    mMarginalPass.program().set("uHeight", height);
    // Exactly one work-group; the tables are always made visible to sample() as well.
    mMarginalPass.dispatch(mMarginalPass.workGroupSize().x, 1, next | NextRead::StorageBuffer, timer);
}

void ImportanceSampler::sample(const gl::Texture& importance, int count, std::uint32_t seed, NextRead next,
                               gl::PassTimer* timer)
{
    require(importance.width() == mWidth && importance.height() == mHeight,
            mName + ": sample() needs the texture of the last build()");
    require(count >= 0, mName + ": negative sample count");
    const GLsizeiptr size = static_cast<GLsizeiptr>(std::max(count, 1)) * sizeof(shared::ImportanceSample);
    if (mSamples.size() < size) mSamples = gl::Buffer(mName + " draws", size);
    bindImage(shared::kImageImportance, importance, GL_READ_ONLY);
    bindStorageBuffer(shared::kBindingImportanceColumns, mColumns);
    bindStorageBuffer(shared::kBindingImportanceMarginal, mMarginal);
    bindStorageBuffer(shared::kBindingImportanceSamples, mSamples);
    mSamplePass.program().set("uCount", count);
    glProgramUniform1ui(mSamplePass.program().id(), mSamplePass.program().uniformLocation("uSeed"), seed);
    mSamplePass.dispatch(count, 1, next, timer);
}

} // namespace vplgi
