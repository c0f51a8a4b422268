#include "metropolis_chains.h"

#include <algorithm>

#include "core/util/error.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/importance.h"

namespace vplgi {

MetropolisChains::MetropolisChains(const gl::ShaderLoader& shaders, std::string name)
    : mName(std::move(name)), mPass(shaders, mName, "passes/metropolis_chains.comp")
{
}

void MetropolisChains::resize(int count)
{
    require(count >= 0, mName + ": negative chain count");
    const auto n = static_cast<GLsizeiptr>(std::max(count, 1));
    if (mStates.size() < n * static_cast<GLsizeiptr>(sizeof(std::uint32_t))) {
        mStates = gl::Buffer(mName + " states", n * static_cast<GLsizeiptr>(sizeof(std::uint32_t)));
        mSamples = gl::Buffer(mName + " draws", n * static_cast<GLsizeiptr>(sizeof(shared::ImportanceSample)));
    }
    if (!mCounters) mCounters = gl::Buffer(mName + " counters", static_cast<GLsizeiptr>(sizeof(std::uint32_t)));
    mCount = count;
}

void MetropolisChains::start(const gl::Texture& importance, const ImportanceSampler& tables, int count, NextRead next)
{
    resize(count);
    bindImage(shared::kImageImportance, importance, GL_READ_ONLY);
    bindStorageBuffer(shared::kBindingImportanceMarginal, tables.marginal());
    bindStorageBuffer(shared::kBindingImportanceSamples, tables.samples());
    bindStorageBuffer(shared::kBindingChainStates, mStates);
    bindStorageBuffer(shared::kBindingChainCounters, mCounters);
    mPass.program().set("uMode", 0);
    mPass.program().set("uCount", count);
    mPass.dispatch(count, 1, next | NextRead::StorageBuffer);
}

void MetropolisChains::setStates(const std::vector<std::uint32_t>& states)
{
    resize(static_cast<int>(states.size()));
    if (!states.empty())
        glNamedBufferSubData(mStates.id(), 0, static_cast<GLsizeiptr>(states.size() * sizeof(std::uint32_t)),
                             states.data());
}

void MetropolisChains::step(const gl::Texture& importance, const ImportanceSampler& tables, int iterations,
                            std::uint32_t seed, const MetropolisProposal& proposal, NextRead next, gl::PassTimer* timer)
{
    require(static_cast<bool>(mStates), mName + ": step() before start()");
    require(iterations >= 0, mName + ": negative iteration count");
    const std::uint32_t zero = 0;
    glNamedBufferSubData(mCounters.id(), 0, sizeof zero, &zero);
    bindImage(shared::kImageImportance, importance, GL_READ_ONLY);
    bindStorageBuffer(shared::kBindingImportanceMarginal, tables.marginal());
    bindStorageBuffer(shared::kBindingImportanceSamples, mSamples);
    bindStorageBuffer(shared::kBindingChainStates, mStates);
    bindStorageBuffer(shared::kBindingChainCounters, mCounters);
    const gl::Program& program = mPass.program();
    program.set("uMode", 1);
    program.set("uCount", mCount);
    program.set("uIterations", iterations);
    program.set("uGlobalProbability", std::clamp(proposal.globalProbability, 0.0f, 1.0f));
    program.set("uStepRadius", std::max(proposal.stepRadius, 1));
    glProgramUniform1ui(program.id(), program.uniformLocation("uSeed"), seed);
    mPass.dispatch(mCount, 1, next | NextRead::BufferReadback, timer);
}

int MetropolisChains::movedInLastStep() const
{
    if (!mCounters) return 0;
    std::uint32_t moved = 0;
    glGetNamedBufferSubData(mCounters.id(), 0, sizeof moved, &moved);
    return static_cast<int>(moved);
}

} // namespace vplgi
