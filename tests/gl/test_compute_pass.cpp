// ComputePass (dispatch rounding, defines, barriers, timer scopes) and the prefix-sum kernel against
// its CPU twin, bit for bit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <vector>

#include "buffer_readback.h"
#include "core/util/random.h"
#include "gl/api/debug.h"
#include "gl/passes/compute_pass.h"
#include "gl/passes/prefix_sum_pass.h"
#include "gl_test_context.h"
#include "glsl/shared/bindings.h"
#include "prefix_sum_twin.h"

using namespace vplgi;
using test::firstBitDifference;
using test::readBuffer;

namespace {

gl::ShaderLoader probeLoader()
{
    return gl::ShaderLoader(std::string(VPLGI_SOURCE_DIR) + "/glsl");
}

// Positive floats of mixed magnitudes (2^-10 .. 2^10), so that the order of the adds changes the
// rounded sums and a different order would show up as bit differences.
std::vector<float> mixedMagnitudes(std::size_t count, std::uint64_t seed)
{
    Pcg32 rng(seed, 1);
    std::vector<float> values(count);
    for (float& v : values)
        v = (0.5f + rng.uniform()) * std::ldexp(1.0f, static_cast<int>(rng.below(21)) - 10);
    return values;
}

std::vector<float> gpuPrefixSum(PrefixSumPass& pass, const std::vector<float>& input)
{
    gl::Buffer buffer("prefix sum test values",
                      static_cast<GLsizeiptr>(std::max<std::size_t>(input.size(), 1) * sizeof(float)),
                      input.empty() ? nullptr : input.data());
    pass.run(buffer, static_cast<int>(input.size()), NextRead::BufferReadback);
    std::vector<float> result = readBuffer<float>(buffer, input.size());
    gl::checkDebugMessages();
    return result;
}

} // namespace

TEST_CASE("ComputePass rounds dispatches up to the work-group size it reads from the program", "[gl][compute]")
{
    test::ensureGLContext();
    const glm::ivec2 size(37, 19); // neither a multiple of 8 nor of 4
    for (int groupX : {8, 4}) {
        ComputePass pass(probeLoader(), "cover probe", "../tests/gl/glsl/compute_cover.comp",
                         {"GROUP_X=" + std::to_string(groupX)});
        CHECK(pass.workGroupSize() == glm::ivec3(groupX, 8, 1)); // the define reached the shader
        CHECK(pass.groupCount(glm::ivec3(size, 1)) == glm::ivec3((size.x + groupX - 1) / groupX, 3, 1));
        std::vector<std::uint32_t> zeros(static_cast<std::size_t>(size.x * size.y), 0u);
        gl::Buffer counts("cover counts", static_cast<GLsizeiptr>(zeros.size() * sizeof(std::uint32_t)), zeros.data());
        bindStorageBuffer(0, counts);
        glProgramUniform2i(pass.program().id(), pass.program().uniformLocation("uSize"), size.x, size.y);
        pass.dispatch(size.x, size.y, NextRead::BufferReadback);
        std::vector<std::uint32_t> result = readBuffer<std::uint32_t>(counts, zeros.size());
        int wrong = 0;
        for (std::uint32_t c : result)
            wrong += c != 1u;
        CHECK(wrong == 0); // every texel exactly once
        gl::checkDebugMessages();
    }
}

TEST_CASE("barrier flags map to their glMemoryBarrier bits", "[gl][compute]")
{
    CHECK(memoryBarrierBits(NextRead::None) == 0u);
    CHECK(memoryBarrierBits(NextRead::StorageBuffer) == GLbitfield(GL_SHADER_STORAGE_BARRIER_BIT));
    CHECK(memoryBarrierBits(NextRead::TextureFetch) == GLbitfield(GL_TEXTURE_FETCH_BARRIER_BIT));
    CHECK(memoryBarrierBits(NextRead::Image) == GLbitfield(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT));
    CHECK(memoryBarrierBits(NextRead::StorageBuffer | NextRead::BufferReadback) ==
          GLbitfield(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT));
    CHECK(memoryBarrierBits(NextRead::TextureReadback | NextRead::Framebuffer) ==
          GLbitfield(GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT));
    // Every flag has its own bit: none is left unmapped or shares another's.
    GLbitfield seen = 0;
    for (unsigned flag = 1; flag <= static_cast<unsigned>(NextRead::Framebuffer); flag <<= 1) {
        const GLbitfield bits = memoryBarrierBits(static_cast<NextRead>(flag));
        CHECK(bits != 0u);
        CHECK((bits & (bits - 1)) == 0u); // one bit
        CHECK((seen & bits) == 0u);
        seen |= bits;
    }
}

TEST_CASE("the compute binding slots fit the driver's limits", "[gl][compute]")
{
    test::ensureGLContext();
    GLint storageBindings = 0, imageUnits = 0;
    glGetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &storageBindings);
    glGetIntegerv(GL_MAX_IMAGE_UNITS, &imageUnits);
    CHECK(shared::kBindingImportanceSamples < storageBindings);
    CHECK(shared::kImageImportance < imageUnits);
}

TEST_CASE("the prefix sum matches its CPU twin bit for bit", "[gl][compute][determinism]")
{
    test::ensureGLContext();
    struct Case {
        int blockSize;
        std::size_t count;
    };
    // One block, a block exactly, one past, three levels (256^2 < 65539), and a small block size
    // with three levels (4097 = 64 * 64 + 1).
    const Case cases[] = {{256, 0}, {256, 1}, {256, 255}, {256, 256}, {256, 257}, {256, 65539}, {64, 4097}};
    for (const Case& c : cases) {
        INFO("block size " << c.blockSize << ", " << c.count << " values");
        PrefixSumPass pass(test::shaders(), "prefix sum", c.blockSize);
        const std::vector<float> input = mixedMagnitudes(c.count, 11 + c.count);
        std::vector<float> twin = input;
        test::prefixSumTwin(twin, c.blockSize);
        const std::vector<float> first = gpuPrefixSum(pass, input);
        const std::vector<float> second = gpuPrefixSum(pass, input);
        CHECK(firstBitDifference(first, twin) == -1);
        CHECK(firstBitDifference(second, first) == -1); // the same input twice: the same bits
    }
}

TEST_CASE("the prefix-sum twin is a prefix sum, in an order that matters", "[gl][compute][numbers]")
{
    // The twin against a double-precision serial sum, and against a float serial sum: the bit-exact
    // GPU comparison above only means something if another order would give other bits.
    for (int blockSize : {256, 64}) {
        const std::vector<float> input = mixedMagnitudes(65539, 5);
        std::vector<float> twin = input;
        test::prefixSumTwin(twin, blockSize);
        double exact = 0.0;
        float serial = 0.0f;
        double maxRelative = 0.0;
        int differsFromSerial = 0;
        for (std::size_t i = 0; i < input.size(); ++i) {
            exact += input[i];
            serial += input[i];
            maxRelative = std::max(maxRelative, std::abs(twin[i] - exact) / exact);
            differsFromSerial += twin[i] != serial;
        }
        std::cout << "prefix-sum twin, block size " << blockSize << ", 65539 values: max relative error " << maxRelative
                  << ", " << differsFromSerial << " sums differ from a serial float sum\n";
        // Measured 1.70e-7 (block 256) and 1.80e-7 (block 64), about 1.5 float ulps of the running
        // sum; tolerance about 2.8x.
        CHECK(maxRelative < 5e-7);
        CHECK(differsFromSerial > 1000);
    }
}

TEST_CASE("compute passes time every dispatch inside nested PassTimer scopes", "[gl][compute]")
{
    test::ensureGLContext();
    gl::PassTimer timer(gl::PassTimer::Mode::FinishAndWallClock);
    PrefixSumPass pass(test::shaders(), "prefix sum", 64);
    gl::Buffer values("timed values", 1000 * sizeof(float));
    timer.beginFrame();
    pass.run(values, 1000, NextRead::None, &timer);
    timer.endFrame();
    std::vector<std::string> paths;
    for (const gl::PassTime& t : timer.times())
        paths.push_back(t.path);
    // 1000 values in blocks of 64: 16 blocks, scanned in one more block, then the offsets.
    const std::vector<std::string> expected = {"prefix sum", "prefix sum / prefix sum: blocks",
                                               "prefix sum / prefix sum: blocks",
                                               "prefix sum / prefix sum: add block offsets"};
    CHECK(paths == expected);
    gl::checkDebugMessages();
}
