// Techniques `vsgl` and `vpl-brsm` (gl/techniques/vsgl_technique.h): VSGL generation (mip level,
// radius, flux, lobe; VSGL section 3.2) against a CPU evaluation on a synthetic RSM, convergence of
// both techniques to the one-bounce path tracer on an unoccluded scene, and determinism.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <vector>

#include "core/scene/builtin_scenes.h"
#include "core/scene/scene_loader.h"
#include "core/trace/path_tracer.h"
#include "core/trace/ray_scene.h"
#include "core/util/metrics.h"
#include "gl/passes/compute_pass.h"
#include "gl/passes/importance_sampler.h"
#include "gl/passes/rsm_pass.h"
#include "gl/techniques/vsgl_technique.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/importance.h"
#include "glsl/shared/normals.h"
#include "glsl/shared/rsm.h"
#include "glsl/shared/sg.h"
#include "buffer_readback.h"
#include "determinism.h"
#include "gl_test_context.h"
#include "measured.h"
#include "shared_assets.h"
#include "technique_determinism.h"
#include "test_scenes.h"

using namespace vplgi;

namespace {

// ---- A synthetic RSM and its CPU twin -------------------------------------------------------------

using Attachments = std::vector<std::vector<glm::vec4>>; // [attachment][y * size + x]

// Level 0 of a 32^2 RSM over a bumpy, tilted patch, every texel covered and lit by the same flux
// (so the mips' flux-weighted means are plain means: the CPU twin below needs no weights).
Attachments syntheticRSM(int size)
{
    Attachments a(shared::kRSMAttachmentCount, std::vector<glm::vec4>(static_cast<std::size_t>(size * size)));
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const std::size_t k = static_cast<std::size_t>(y * size + x);
            const float u = static_cast<float>(x), v = static_cast<float>(y);
            const glm::vec3 p(0.05f * u + 0.3f, 0.08f * std::sin(u / 3.0f) * std::cos(v / 5.0f) + 0.01f * v,
                              0.05f * v - 0.4f);
            const glm::vec3 n = glm::normalize(glm::vec3(0.2f * std::sin(v / 4.0f), 1.0f, 0.1f * std::cos(u / 2.0f)));
            const glm::vec3 axis = glm::normalize(glm::vec3(0.3f * std::cos(u / 6.0f), 1.0f, 0.2f * std::sin(v / 7.0f)));
            const float sharpness = 5.0f + 40.0f * (0.5f + 0.5f * std::sin((u + v) / 5.0f));
            a[shared::kRSMPosition][k] = glm::vec4(p, glm::dot(p, p));
            a[shared::kRSMNormal][k] = glm::vec4(n, 1.0f);
            a[shared::kRSMFlux][k] = glm::vec4(0.2f, 0.2f, 0.2f, 0.0f);
            a[shared::kRSMDiffuse][k] = glm::vec4(0.2f + 0.6f * u / size, 0.5f, 0.8f - 0.6f * v / size, 0.0f);
            a[shared::kRSMSpecular][k] = glm::vec4(0.04f, 0.04f, 0.04f, 0.3f + 0.4f * v / size);
            a[shared::kRSMLobe][k] = glm::vec4(shared::toksvigEncode(axis, sharpness), 0.5f + 0.3f * u / size);
        }
    return a;
}

// Plain 2x2 means, level by level (equal flux everywhere: the kernel's weights are all equal).
std::vector<Attachments> cpuMips(const Attachments& level0, int size)
{
    std::vector<Attachments> levels{level0};
    for (int n = size / 2; n >= 1; n /= 2) {
        const Attachments& fine = levels.back();
        Attachments coarse(fine.size(), std::vector<glm::vec4>(static_cast<std::size_t>(n * n)));
        for (std::size_t a = 0; a < fine.size(); ++a)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    auto at = [&](int i, int j) { return fine[a][static_cast<std::size_t>(j * 2 * n + i)]; };
                    coarse[a][static_cast<std::size_t>(y * n + x)] =
                        0.25f * (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1));
                }
        levels.push_back(std::move(coarse));
    }
    return levels;
}

// GL's trilinear filtering (GL 4.5 section 8.14): bilinear at each of the two levels around `lod`
// (clamp to edge), then linear between them.
glm::vec4 trilinear(const std::vector<Attachments>& levels, int attachment, glm::vec2 uv, float lod)
{
    auto bilinear = [&](int l) {
        const int n = static_cast<int>(std::lround(std::sqrt(static_cast<double>(levels[static_cast<std::size_t>(l)][0].size()))));
        const glm::vec2 t = uv * static_cast<float>(n) - 0.5f;
        const glm::ivec2 i0 = glm::ivec2(glm::floor(t));
        const glm::vec2 f = t - glm::floor(t);
        auto texel = [&](int x, int y) {
            x = std::clamp(x, 0, n - 1);
            y = std::clamp(y, 0, n - 1);
            return levels[static_cast<std::size_t>(l)][static_cast<std::size_t>(attachment)][static_cast<std::size_t>(y * n + x)];
        };
        return glm::mix(glm::mix(texel(i0.x, i0.y), texel(i0.x + 1, i0.y), f.x),
                        glm::mix(texel(i0.x, i0.y + 1), texel(i0.x + 1, i0.y + 1), f.x), f.y);
    };
    const int top = static_cast<int>(levels.size()) - 1;
    const int l0 = std::min(static_cast<int>(std::floor(lod)), top);
    const float f = lod - static_cast<float>(l0);
    if (l0 >= top || f == 0.0f) return bilinear(l0);
    return glm::mix(bilinear(l0), bilinear(l0 + 1), f);
}

struct Draw {
    int x, y;
    float probability;
};

// Level 0 of a size^2 RSM-layout target from `level0`, its mips by the RSM pass's own kernel.
gl::RenderTarget uploadRSM(const char* name, const Attachments& level0, int size)
{
    gl::RenderTarget rsm = makeRSMLayoutTarget(name, false);
    rsm.resize(size, size, 1);
    for (int a = 0; a < shared::kRSMAttachmentCount; ++a)
        glTextureSubImage3D(rsm.color(a).id(), 0, 0, 0, 0, size, size, 1, GL_RGBA, GL_FLOAT,
                            level0[static_cast<std::size_t>(a)].data());
    ComputePass downsample(test::shaders(), "rsm downsample", "passes/rsm_downsample.comp");
    memoryBarrier(NextRead::TextureFetch);
    downsampleRSMLayout(downsample, rsm);
    return rsm;
}

// vsgl_generate.comp in draw mode (uMode 0) for `count` draws of a size^2 single-layer RSM, smoothness
// k, reading the draws from `draws` and writing the lights to `lights` (footprint: the uniform's 0,
// texel, until the caller sets uFootprint).
ComputePass drawGeneration(int count, int size, int levels, float k, const gl::Buffer& draws, const gl::Buffer& lights)
{
    ComputePass generate(test::shaders(), "VSGL generation", "passes/vsgl_generate.comp");
    bindStorageBuffer(shared::kBindingImportanceSamples, draws);
    bindStorageBuffer(shared::kBindingVSGLights, lights);
    generate.program().set("uMode", 0);
    generate.program().set("uCount", count);
    generate.program().set("uSize", size);
    generate.program().set("uLevels", levels);
    generate.program().set("uLevel", 0);
    generate.program().set("uLayers", 1);
    generate.program().set("uSmoothness", k);
    return generate;
}

// An R32F importance map (the .r of `values`) with `levels` box mips by the technique's own pass.
gl::Texture uploadImportance(const char* name, const std::vector<glm::vec4>& values, int size, int levels)
{
    std::vector<float> texels;
    for (const glm::vec4& v : values) texels.push_back(v.r);
    gl::Texture map = test::uploadR32F(name, texels, size, size, levels);
    memoryBarrier(NextRead::Image);
    ImportanceSampler(test::shaders()).buildMips(map, NextRead::TextureFetch);
    return map;
}

// Binds the RSM's attachments, and the importance mips when given, with a trilinear sampler, as the
// VSGL technique reads them; the samplers are unbound when it goes out of scope.
class TrilinearInputs {
public:
    TrilinearInputs(const gl::RenderTarget& rsm, const gl::Texture* importanceMips)
        : mSampler("VSGL test trilinear", trilinearDesc())
    {
        for (int a = 0; a < shared::kRSMAttachmentCount; ++a) {
            glBindTextureUnit(static_cast<GLuint>(shared::kUnitRSMSource + a), rsm.color(a).id());
            glBindSampler(static_cast<GLuint>(shared::kUnitRSMSource + a), mSampler.id());
        }
        if (importanceMips) {
            glBindTextureUnit(static_cast<GLuint>(shared::kUnitImportanceMips), importanceMips->id());
            glBindSampler(static_cast<GLuint>(shared::kUnitImportanceMips), mSampler.id());
        }
    }
    ~TrilinearInputs()
    {
        for (int a = 0; a < shared::kRSMAttachmentCount; ++a)
            glBindSampler(static_cast<GLuint>(shared::kUnitRSMSource + a), 0);
        glBindSampler(static_cast<GLuint>(shared::kUnitImportanceMips), 0);
    }
    TrilinearInputs(const TrilinearInputs&) = delete;
    TrilinearInputs& operator=(const TrilinearInputs&) = delete;

private:
    static gl::SamplerDesc trilinearDesc()
    {
        gl::SamplerDesc desc;
        desc.minFilter = GL_LINEAR_MIPMAP_LINEAR;
        return desc;
    }
    gl::Sampler mSampler;
};

} // namespace

TEST_CASE("VSGL generation: mip level, radius, flux and lobe of each draw match a CPU evaluation", "[vsgl][numbers]")
{
    test::ensureGLContext();
    const int size = 32;
    const int levels = 6;
    const Attachments level0 = syntheticRSM(size);
    const gl::RenderTarget rsm = uploadRSM("synthetic RSM", level0, size);
    const std::vector<Attachments> mips = cpuMips(level0, size);

    // N = 8 draws, k = 4: P = k / (N 4^h) puts draw i at level h; the last two clamp to the top level
    // and to 0 (MATH.md 5.2).
    const float k = 4.0f;
    const int count = 8;
    const float wanted[count] = {0.0f, 1.0f, 1.5f, 2.0f, 2.75f, 3.2f, 9.0f, -1.0f};
    const glm::ivec2 texels[count] = {{3, 4}, {10, 20}, {31, 0}, {16, 16}, {7, 29}, {25, 9}, {0, 0}, {12, 5}};
    std::vector<shared::ImportanceSample> draws(count);
    for (int i = 0; i < count; ++i) {
        draws[static_cast<std::size_t>(i)] = {texels[i].x, texels[i].y,
                                             k / (static_cast<float>(count) * std::pow(4.0f, wanted[i])), 1.0f};
    }
    gl::Buffer drawBuffer("VSGL test draws", static_cast<GLsizeiptr>(draws.size() * sizeof(shared::ImportanceSample)),
                          draws.data());
    gl::Buffer lightBuffer("VSGL test lights", count * static_cast<GLsizeiptr>(sizeof(shared::VSGLight)));
    const ComputePass generate = drawGeneration(count, size, levels, k, drawBuffer, lightBuffer);
    {
        const TrilinearInputs inputs(rsm, nullptr);
        generate.dispatch(count, 1, NextRead::BufferReadback);
    }
    const std::vector<shared::VSGLight> gpu = test::readBuffer<shared::VSGLight>(lightBuffer, count);

    double worstPosition = 0.0, worstRadius = 0.0, worstFlux = 0.0, worstNormal = 0.0, worstAxis = 0.0,
           worstSharpness = 0.0, worstCoefficient = 0.0;
    for (int i = 0; i < count; ++i) {
        const shared::ImportanceSample& d = draws[static_cast<std::size_t>(i)];
        const float lod = std::clamp(0.5f * std::log2(k / (count * d.probability)), 0.0f, static_cast<float>(levels - 1));
        CHECK(lod == Approx(std::clamp(wanted[i], 0.0f, 5.0f)).margin(1e-5));
        const glm::vec2 uv = (glm::vec2(d.x, d.y) + 0.5f) / static_cast<float>(size);
        const glm::vec4 position = trilinear(mips, shared::kRSMPosition, uv, lod);
        const glm::vec4 normal = trilinear(mips, shared::kRSMNormal, uv, lod);
        const glm::vec4 flux = trilinear(mips, shared::kRSMFlux, uv, lod);
        const glm::vec4 lobe = trilinear(mips, shared::kRSMLobe, uv, lod);
        const glm::vec4 diffuse = trilinear(mips, shared::kRSMDiffuse, uv, lod);
        // MATH.md 5.3: r^2 = 2 (E|x|^2 - |E x|^2).
        const double r2 = 2.0 * std::max(0.0, static_cast<double>(position.w) - glm::dot(glm::dvec3(position), glm::dvec3(position)));
        const shared::VSGLight& g = gpu[static_cast<std::size_t>(i)];
        REQUIRE(g.normalValid.w == 1.0f);
        worstPosition = std::max(worstPosition, static_cast<double>(glm::length(glm::vec3(g.positionRadius2) - glm::vec3(position))));
        worstRadius = std::max(worstRadius, std::abs(g.positionRadius2.w - r2) / std::max(r2, 1e-4));
        // Phi_h / (N P_j); the mean normal's length (the footprint's diffuse cosine: vsgl_generate.comp)
        // scales the diffuse coefficient.
        const float normalLength = std::min(glm::length(glm::vec3(normal)), 1.0f);
        worstFlux = std::max(worstFlux, static_cast<double>(std::abs(g.flux.r * count * d.probability - flux.r) / flux.r));
        if (lod >= 3.0f) CHECK(normalLength < 0.999f); // the synthetic normals spread: the length matters
        worstNormal = std::max(worstNormal, static_cast<double>(glm::length(glm::vec3(g.normalValid) - glm::normalize(glm::vec3(normal)))));
        glm::vec3 axis;
        float sharpness = 0.0f;
        shared::toksvigDecode(glm::vec3(lobe), axis, sharpness);
        const glm::vec4 axisSharpness(axis, sharpness);
        worstAxis = std::max(worstAxis, static_cast<double>(glm::length(glm::vec3(g.lobe) - glm::vec3(axisSharpness))));
        worstSharpness = std::max(worstSharpness, static_cast<double>(std::abs(g.lobe.w - axisSharpness.w) / axisSharpness.w));
        worstCoefficient = std::max({worstCoefficient, static_cast<double>(std::abs(g.specular.w - lobe.w)),
                                     static_cast<double>(glm::length(glm::vec3(g.diffuse) - glm::vec3(diffuse) * normalLength))});
        if (lod >= 1.0f) CHECK(g.positionRadius2.w > 0.0f); // a footprint of several texels has an extent
    }
    MEASURED("VSGL generation vs CPU twin (32^2 synthetic RSM, 8 draws, levels 0-5): worst position "
             << worstPosition << " m, radius^2 (relative) " << worstRadius << ", flux " << worstFlux << ", normal "
             << worstNormal << ", lobe axis " << worstAxis << ", sharpness " << worstSharpness << ", coefficients "
             << worstCoefficient);
    // llvmpipe filters float textures in float, so only rounding separates the two. Measured: position
    // 1.2e-7 m, r^2 9.6e-5 (E|x|^2 - |E x|^2 cancels about four digits), flux 0, normal 6e-8, axis
    // 6e-8, sharpness 1.2e-6, coefficients 1.3e-7; each bound is about 3x that (flux: a few ulps).
    // On an H200, whose trilinear filter weighs the texels and levels with 8-bit fixed-point weights
    // (test::twinTolerance): position 8.1e-4 m, r^2 3.4e-3, flux 9.7e-6, normal 4.0e-4, axis 2.3e-4,
    // sharpness 2.7e-3, coefficients 3.0e-4.
    CHECK(worstPosition < test::twinTolerance(4e-7, 2e-3));
    CHECK(worstRadius < test::twinTolerance(3e-4, 9e-3));
    CHECK(worstFlux < test::twinTolerance(1e-6, 2.5e-5));
    CHECK(worstNormal < test::twinTolerance(2e-7, 1e-3));
    CHECK(worstAxis < test::twinTolerance(2e-7, 6e-4));
    CHECK(worstSharpness < test::twinTolerance(4e-6, 7e-3));
    CHECK(worstCoefficient < test::twinTolerance(4e-7, 8e-4));

    // vsgl.footprint = cell: the same draws, each at the coarsest mip cell around it holding at most
    // k expected draws (N P_cell <= k), flux Phi_cell / (N P_cell), both the leaf cell's own (its box
    // means: the 4^l factors cancel), position and the rest bilinear at the leaf's level. The map: a smooth bump whose cells' expected
    // draws grow through k at different levels for different draws, and each draw's texel set to
    // P_j * total (consistent draws).
    Attachments importance(1, std::vector<glm::vec4>(static_cast<std::size_t>(size * size)));
    float total = 0.0f;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float value = 0.005f + std::exp(-0.05f * static_cast<float>((x - 11) * (x - 11) + (y - 19) * (y - 19)));
            importance[0][static_cast<std::size_t>(y * size + x)] = glm::vec4(value);
            total += value;
        }
    std::vector<shared::ImportanceSample> consistent = draws;
    for (shared::ImportanceSample& d : consistent) {
        d.importance = importance[0][static_cast<std::size_t>(d.y * size + d.x)].r;
        d.probability = d.importance / total;
    }
    const gl::Texture importanceMap = uploadImportance("VSGL test importance", importance[0], size, levels);
    const std::vector<Attachments> importanceMips = cpuMips(importance, size);
    gl::Buffer consistentBuffer("VSGL test draws with importance",
                                static_cast<GLsizeiptr>(consistent.size() * sizeof(shared::ImportanceSample)),
                                consistent.data());
    bindStorageBuffer(shared::kBindingImportanceSamples, consistentBuffer);
    generate.program().set("uFootprint", 1);
    generate.program().set("uMaxLeaf", 12); // no cap
    {
        const TrilinearInputs inputs(rsm, &importanceMap);
        generate.dispatch(count, 1, NextRead::BufferReadback);
    }
    generate.program().set("uFootprint", 0);
    const std::vector<shared::VSGLight> cells = test::readBuffer<shared::VSGLight>(lightBuffer, count);
    double worstCellFlux = 0.0, worstCellPosition = 0.0;
    std::vector<int> leaves;
    for (int i = 0; i < count; ++i) {
        const shared::ImportanceSample& d = consistent[static_cast<std::size_t>(i)];
        // The leaf on the CPU: box means up the chain, cell probability = 4^l mean / total.
        int leaf = 0;
        for (int l = 1; l < levels; ++l) {
            const int n = size >> l;
            const double mean = importanceMips[static_cast<std::size_t>(l)][0][static_cast<std::size_t>((d.y >> l) * n + (d.x >> l))].r;
            if (!(count * std::pow(4.0, l) * mean / total <= k)) break;
            leaf = l;
        }
        leaves.push_back(leaf);
        const float lod = static_cast<float>(leaf);
        const glm::vec2 uv = (glm::vec2(d.x, d.y) + 0.5f) / static_cast<float>(size);
        const glm::vec4 position = trilinear(mips, shared::kRSMPosition, uv, lod);
        const std::size_t cell = static_cast<std::size_t>((d.y >> leaf) * (size >> leaf) + (d.x >> leaf));
        const double fluxCell = mips[static_cast<std::size_t>(leaf)][shared::kRSMFlux][cell].r;
        const double probabilityCell = importanceMips[static_cast<std::size_t>(leaf)][0][cell].r / total;
        const double expected = fluxCell / (count * probabilityCell);
        const shared::VSGLight& g = cells[static_cast<std::size_t>(i)];
        REQUIRE(g.normalValid.w == 1.0f);
        worstCellFlux = std::max(worstCellFlux, std::abs(g.flux.r - expected) / expected);
        worstCellPosition = std::max(worstCellPosition, static_cast<double>(glm::length(glm::vec3(g.positionRadius2) - glm::vec3(position))));
    }
    std::vector<int> distinct = leaves;
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    std::ostringstream leafList;
    for (int leaf : leaves) leafList << leaf << " ";
    MEASURED("VSGL generation, cell footprints, vs CPU twin: leaves " << leafList.str() << ", worst flux " << worstCellFlux << ", position " << worstCellPosition << " m");
    CHECK(distinct.size() >= 3); // the draws exercise several leaf levels
    // Measured: leaves 4 2 4 4 3 4 4 4, flux 1.2e-7, position 1.2e-7 m (float rounding); bounds
    // ~3x. A leaf one level off takes 4x the cell's probability and a position filtered over 4x the
    // texels: both leave these bounds by orders of magnitude on this curved, unevenly important patch.
    // On a hardware GPU the flux and probability are fetched, not filtered (not yet measured there:
    // the bound allows the mip generation's rounding); the position's bound is the H200's 3.0e-7 m.
    CHECK(worstCellFlux < test::twinTolerance(4e-7, 1e-5));
    CHECK(worstCellPosition < 4e-7);
}

TEST_CASE("VSGL cell footprints are unbiased: over every texel, sum_j P_j N Phi_j equals the RSM's flux on "
          "concentrated importance",
          "[vsgl][numbers]")
{
    // The estimator sums N lights, light j of flux Phi_cell(j) / (N P_cell(j)) drawn with probability
    // P_j; its expectation, N sum_j P_j Phi_j over all texels, is the RSM's total flux exactly when the
    // leaf cells partition the map and flux and probability are the leaf's own (vsgl_generate.comp).
    // Here every texel is one "draw" with its own P_j and the GPU writes each light: the sum is the
    // expectation itself, no sampling noise. Importance = flux x a view factor concentrated in spots
    // and a band, as a BRSM's glossy receivers make it, so that P is far from proportional to Phi.
    test::ensureGLContext();
    const int size = 32, levels = 6, texels = size * size;
    Attachments level0 = syntheticRSM(size);
    Attachments importance(1, std::vector<glm::vec4>(static_cast<std::size_t>(texels)));
    double totalFlux = 0.0;
    float totalImportance = 0.0f;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const std::size_t at = static_cast<std::size_t>(y * size + x);
            float flux = 0.2f + 0.8f * std::exp(-0.01f * static_cast<float>((x - 20) * (x - 20) + (y - 10) * (y - 10)));
            if (x == 17 && y > 3 && y < 29) flux = 3.0f; // a bright ridge
            level0[shared::kRSMFlux][at] = glm::vec4(flux, flux, flux, 0.0f);
            // The view factor (what a BRSM's glossy receivers make of each texel): concentrated in a
            // few spots and a narrow band, independent of the flux.
            float view = 0.01f;
            if ((x == 5 && y == 7) || (x == 22 && y == 13) || (x == 9 && y == 27)) view = 100.0f;
            if (y == 20 && x > 2 && x < 30) view = 5.0f;
            importance[0][at] = glm::vec4(flux * view);
            totalFlux += flux;
            totalImportance += flux * view;
        }
    const gl::RenderTarget rsm = uploadRSM("concentrated RSM", level0, size);

    const gl::Texture importanceMap = uploadImportance("VSGL test concentrated importance", importance[0], size, levels);

    std::vector<shared::ImportanceSample> everyTexel;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float value = importance[0][static_cast<std::size_t>(y * size + x)].r;
            everyTexel.push_back({x, y, value / totalImportance, value});
        }
    gl::Buffer drawBuffer("VSGL test every texel",
                          static_cast<GLsizeiptr>(everyTexel.size() * sizeof(shared::ImportanceSample)), everyTexel.data());
    gl::Buffer lightBuffer("VSGL test lights", texels * static_cast<GLsizeiptr>(sizeof(shared::VSGLight)));
    const TrilinearInputs inputs(rsm, &importanceMap);
    // k = 16: leaves from level 0 (the spots) to level 5 (the dim floor far from the view factor).
    const float k = 16.0f;
    const ComputePass generate = drawGeneration(texels, size, levels, k, drawBuffer, lightBuffer);
    // Runs: texel footprints; cell footprints; cell footprints with leaves capped at level 2
    // (vsgl.maxLeaf: the cells of one level still partition the map).
    double ratio[3] = {0.0, 0.0, 0.0};
    for (int run : {0, 1, 2}) {
        generate.program().set("uFootprint", run == 0 ? 0 : 1);
        generate.program().set("uMaxLeaf", run == 2 ? 2 : 12);
        generate.dispatch(texels, 1, NextRead::BufferReadback);
        const std::vector<shared::VSGLight> lights = test::readBuffer<shared::VSGLight>(lightBuffer, texels);
        double expectation = 0.0;
        for (int j = 0; j < texels; ++j)
            expectation += static_cast<double>(everyTexel[static_cast<std::size_t>(j)].probability) * texels *
                           lights[static_cast<std::size_t>(j)].flux.r;
        ratio[run] = expectation / totalFlux;
    }
    MEASURED("VSGL estimator's expectation / RSM flux on concentrated importance (k = " << k << ", N = " << texels
             << "): cell 1 + " << ratio[1] - 1.0 << ", cell with leaves capped at level 2: 1 + " << ratio[2] - 1.0
             << ", texel (the paper's reading) " << ratio[0]);
    // Measured: cell 1 + 7.6e-9 (float rounding); the bound leaves room for a 1024-term float sum
    // on other drivers. The bilinear flux over bilinear probability this replaced gave 0.448 on this
    // map. The texel reading is printed, not asserted: its expectation sum_j Phi_h(j) is biased by
    // design (docs/vsgl.md).
    CHECK(std::abs(ratio[1] - 1.0) < test::twinTolerance(1e-6, 1e-4));
    CHECK(std::abs(ratio[2] - 1.0) < test::twinTolerance(1e-6, 1e-4));
}

TEST_CASE("VSGL leaf edges: no leaf holds a step or a crease, the leaves still partition the map, and a leaf reads "
          "its own cell",
          "[vsgl][numbers]")
{
    // vsgl.leafEdges and vsgl.leafReads = cell (passes/vsgl_generate.comp, leafHasEdge; ours). A 32^2
    // RSM of three surfaces: a floor (x < 20, y < 24), the same floor raised 0.5 m (x >= 20, y < 24:
    // a step, same normal) and a wall standing on the floor's far edge (y >= 24: a 90-degree crease).
    // Every texel is one draw with its own probability from a smooth bump of importance, so the leaves
    // grow to every level (k = 16, no cap).
    test::ensureGLContext();
    const int size = 32, levels = 6, texels = size * size;
    Attachments level0(shared::kRSMAttachmentCount, std::vector<glm::vec4>(static_cast<std::size_t>(texels)));
    std::vector<glm::vec3> geometricNormal(static_cast<std::size_t>(texels));
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const std::size_t at = static_cast<std::size_t>(y * size + x);
            const float u = 0.05f * static_cast<float>(x), v = 0.05f * static_cast<float>(y);
            glm::vec3 p(u, x >= 20 ? 0.5f : 0.0f, v), n(0.0f, 1.0f, 0.0f);
            if (y >= 24) {
                p = glm::vec3(u, 0.05f * static_cast<float>(y - 23), 0.05f * 24.0f);
                n = glm::vec3(0.0f, 0.0f, -1.0f);
            }
            const glm::vec2 oct = shared::octEncode(n);
            geometricNormal[at] = shared::octDecode(oct);
            level0[shared::kRSMPosition][at] = glm::vec4(p, glm::dot(p, p));
            level0[shared::kRSMNormal][at] = glm::vec4(n, 1.0f);
            level0[shared::kRSMFlux][at] = glm::vec4(0.2f, 0.2f, 0.2f, oct.x); // equal flux: plain means
            level0[shared::kRSMDiffuse][at] = glm::vec4(0.5f, 0.5f, 0.5f, oct.y);
            level0[shared::kRSMSpecular][at] = glm::vec4(0.04f, 0.04f, 0.04f, 0.5f);
            level0[shared::kRSMLobe][at] = glm::vec4(shared::toksvigEncode(n, 20.0f), 0.5f);
        }
    const gl::RenderTarget rsm = uploadRSM("stepped RSM", level0, size);
    const std::vector<Attachments> mips = cpuMips(level0, size);
    Attachments importance(1, std::vector<glm::vec4>(static_cast<std::size_t>(texels)));
    float totalImportance = 0.0f;
    std::vector<shared::ImportanceSample> everyTexel;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float value = 0.005f + std::exp(-0.02f * static_cast<float>((x - 8) * (x - 8) + (y - 10) * (y - 10)));
            importance[0][static_cast<std::size_t>(y * size + x)] = glm::vec4(value);
            totalImportance += value;
        }
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float value = importance[0][static_cast<std::size_t>(y * size + x)].r;
            everyTexel.push_back({x, y, value / totalImportance, value});
        }
    const gl::Texture importanceMap = uploadImportance("VSGL test leaf-edge importance", importance[0], size, levels);
    const std::vector<Attachments> importanceMips = cpuMips(importance, size);

    // The CPU twin of leafHasEdge: every pair of neighbouring texels inside the cell, on different
    // surfaces by normal (over 30 degrees) or plane (off by over half their distance). The rule itself
    // is the shared rsmSurfacesDiffer (C++ and GLSL from one definition); the twin checks the scan,
    // the monotone leaf choice and the geometry fed to it, and the surfaces' answers are clear-cut
    // here (dot 1 or 0, plane offsets 0 or the whole distance).
    auto edgeBetween = [&](int ax, int ay, int bx, int by) {
        const std::size_t a = static_cast<std::size_t>(ay * size + ax), b = static_cast<std::size_t>(by * size + bx);
        const glm::vec3 d = glm::vec3(level0[shared::kRSMPosition][b]) - glm::vec3(level0[shared::kRSMPosition][a]);
        return shared::rsmSurfacesDiffer(geometricNormal[a], geometricNormal[b], d); // shared/rsm.h, as the shader
    };
    auto cellHasEdge = [&](int cx, int cy, int l) {
        const int side = 1 << l;
        for (int y = cy * side; y < (cy + 1) * side; ++y)
            for (int x = cx * side; x < (cx + 1) * side; ++x) {
                if (x + 1 < (cx + 1) * side && edgeBetween(x, y, x + 1, y)) return true;
                if (y + 1 < (cy + 1) * side && edgeBetween(x, y, x, y + 1)) return true;
            }
        return false;
    };
    const float k = 16.0f;
    auto cpuLeaf = [&](int x, int y, bool edges) {
        int leaf = 0;
        for (int l = 1; l < levels; ++l) {
            const double mean = importanceMips[static_cast<std::size_t>(l)][0][static_cast<std::size_t>((y >> l) * (size >> l) + (x >> l))].r;
            if (!(texels * std::pow(4.0, l) * mean / totalImportance <= k)) break;
            if (edges && cellHasEdge(x >> l, y >> l, l)) break;
            leaf = l;
        }
        return leaf;
    };
    // Without the rule some leaves span the step or the crease (the scene gives the rule work).
    int spanning = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const int l = cpuLeaf(x, y, false);
            if (l > 0 && cellHasEdge(x >> l, y >> l, l)) ++spanning;
        }

    gl::Buffer drawBuffer("VSGL test leaf-edge draws",
                          static_cast<GLsizeiptr>(everyTexel.size() * sizeof(shared::ImportanceSample)), everyTexel.data());
    gl::Buffer lightBuffer("VSGL test leaf-edge lights", texels * static_cast<GLsizeiptr>(sizeof(shared::VSGLight)));
    const TrilinearInputs inputs(rsm, &importanceMap);
    const ComputePass generate = drawGeneration(texels, size, levels, k, drawBuffer, lightBuffer);
    generate.program().set("uFootprint", 1);
    generate.program().set("uMaxLeaf", 12);
    generate.program().set("uLeafEdges", 1);
    generate.program().set("uLeafReads", 1);
    generate.dispatch(texels, 1, NextRead::BufferReadback);
    const std::vector<shared::VSGLight> lights = test::readBuffer<shared::VSGLight>(lightBuffer, texels);

    double expectation = 0.0, worstPosition = 0.0, worstRadius = 0.0;
    int leafCount[levels] = {};
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const std::size_t j = static_cast<std::size_t>(y * size + x);
            const shared::VSGLight& g = lights[j];
            REQUIRE(g.normalValid.w == 1.0f);
            expectation += static_cast<double>(everyTexel[j].probability) * texels * g.flux.r;
            // The leaf cell's own means (texelFetch at its level): a leaf one level off reads a cell
            // of 4x or 1/4 the texels, whose mean position differs by centimetres here.
            const int leaf = cpuLeaf(x, y, true);
            ++leafCount[leaf];
            const std::size_t cell = static_cast<std::size_t>((y >> leaf) * (size >> leaf) + (x >> leaf));
            const glm::vec4 position = mips[static_cast<std::size_t>(leaf)][shared::kRSMPosition][cell];
            worstPosition = std::max(worstPosition, static_cast<double>(glm::length(glm::vec3(g.positionRadius2) - glm::vec3(position))));
            const double r2 = 2.0 * std::max(0.0, static_cast<double>(position.w) - glm::dot(glm::dvec3(position), glm::dvec3(position)));
            worstRadius = std::max(worstRadius, std::abs(static_cast<double>(g.positionRadius2.w) - r2));
        }
    const double ratio = expectation / (0.2 * texels);
    std::ostringstream histogram;
    for (int l = 0; l < levels; ++l) histogram << leafCount[l] << (l + 1 < levels ? " " : "");
    MEASURED("VSGL leaf edges (32^2 floor, step, wall; k = " << k << ", every texel a draw): texels per leaf level 0-5 "
             << histogram.str() << "; without the rule " << spanning << " texels' leaves span an edge; expectation / flux 1 + "
             << ratio - 1.0 << ", worst position " << worstPosition << " m, radius^2 " << worstRadius << " m^2");
    CHECK(spanning > 0);
    CHECK(leafCount[0] > 0);
    CHECK(leafCount[2] + leafCount[3] + leafCount[4] + leafCount[5] > 0); // leaves still grow away from the edges
    // Measured (llvmpipe): texels per leaf level 80 224 272 448 0 0, 64 spanning without the rule;
    // expectation 1 + 3.2e-8 (float rounding: the partition holds), position 2.5e-7 m, radius^2
    // 1.7e-6 m^2 (E|x|^2 - |E x|^2 at |x| ~ 1.5 m cancels about six digits). Bounds about 3x; the
    // hardware ones allow the mips' rounding (not yet measured on a GPU). A leaf one level off reads
    // a mean position centimetres away.
    CHECK(std::abs(ratio - 1.0) < test::twinTolerance(1e-6, 1e-4));
    CHECK(worstPosition < test::twinTolerance(8e-7, 1e-5));
    CHECK(worstRadius < test::twinTolerance(5e-6, 1e-4));

    // leafReads = surface (the default): the bilinear cells around the draw at the leaf's level, less
    // those on another surface. Every light lies on its own surface's plane (a bilinear blend across
    // the step or the crease would leave it between them), and where the four cells all lie on the
    // draw's surface the blend is GL's bilinear one (the CPU trilinear at the leaf's level).
    generate.program().set("uLeafReads", 2);
    generate.dispatch(texels, 1, NextRead::BufferReadback);
    const std::vector<shared::VSGLight> surface = test::readBuffer<shared::VSGLight>(lightBuffer, texels);
    auto region = [&](int x, int y) { return y >= 24 ? 2 : (x >= 20 ? 1 : 0); }; // floor, raised, wall
    double worstOffPlane = 0.0, worstBilinear = 0.0;
    int blended = 0, pruned = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const glm::vec3 p(surface[static_cast<std::size_t>(y * size + x)].positionRadius2);
            const int r = region(x, y);
            const double off = r == 2 ? std::abs(p.z - 1.2f) : std::abs(p.y - (r == 1 ? 0.5f : 0.0f));
            worstOffPlane = std::max(worstOffPlane, off);
            const int leaf = cpuLeaf(x, y, true), n = size >> leaf;
            const glm::vec2 uv = (glm::vec2(x, y) + 0.5f) / static_cast<float>(size);
            const glm::vec2 t = uv * static_cast<float>(n) - 0.5f;
            bool oneSurface = true;
            for (int c = 0; c < 4; ++c) {
                const int cx = std::clamp(static_cast<int>(std::floor(t.x)) + (c & 1), 0, n - 1);
                const int cy = std::clamp(static_cast<int>(std::floor(t.y)) + (c >> 1), 0, n - 1);
                const int side = 1 << leaf;
                oneSurface = oneSurface && region(cx * side, cy * side) == r && region(cx * side + side - 1, cy * side + side - 1) == r;
            }
            if (oneSurface) {
                ++blended;
                const glm::vec3 expected(trilinear(mips, shared::kRSMPosition, uv, static_cast<float>(leaf)));
                worstBilinear = std::max(worstBilinear, static_cast<double>(glm::length(p - expected)));
            } else {
                ++pruned;
            }
        }
    MEASURED("VSGL leaf edges, leafReads = surface: worst distance from the light's own surface " << worstOffPlane
             << " m; " << blended << " draws with four cells on one surface, worst vs bilinear " << worstBilinear << " m; "
             << pruned << " draws beside another surface");
    CHECK(blended > 0);
    CHECK(pruned > 0);
    // Measured (llvmpipe): 1.2e-7 m off its plane, 2.7e-7 m from bilinear (float rounding), 652 and
    // 372 draws; bounds about 4x. Judging neighbours by their means alone left a light 6.3 cm off its
    // plane (a level-3 cell straddling the step: its mean on neither surface); bilinear blending across
    // the step puts one up to 0.25 m off. Hardware bilinear weights are 8-bit fixed point (H200: see the
    // first test), hence the wider hardware bounds.
    CHECK(worstOffPlane < test::twinTolerance(5e-7, 1e-4));
    CHECK(worstBilinear < test::twinTolerance(1e-6, 2e-3));
}

TEST_CASE("vsgl and vpl-brsm converge to the one-bounce path tracer on an unoccluded corner as N grows",
          "[vsgl][image][numbers]")
{
    test::ensureGLContext();
    const Scene scene = test::cornerScene(0.0f, 1.0f); // Lambertian: the SG lobes reduce to exact integrals
    const Camera& camera = scene.cameras[0];
    const int width = 48, height = 36;
    // One reference: a second seed's, which only printed the reference's own noise and was asserted
    // by nothing, is no longer rendered (docs/testing.md, "work cut").
    const ImageRGBA32F reference = test::oneBounceReference(scene, camera, width, height, 16384);

    const int counts[] = {256, 1024, 4096};
    double vsglError[3], vplError[3], between[3], vsglBias = 0.0, vplBias = 0.0;
    for (int i = 0; i < 3; ++i) {
        const std::string n = std::to_string(counts[i]);
        // The paper's footprints, uncapped (vsgl.maxLeaf 12): they shrink towards the VPLs' as N
        // grows, which is what this test follows. With the default cap (4 x 4 texels) they are
        // already near the VPLs at N = 256 (relative L1 between the two 0.008, 0.016, 0.011).
        auto render = [&](const std::string& technique) {
            std::vector<std::pair<std::string, std::string>> settings{
                {"rsm.size", "128"}, {technique + ".count", n}, {technique + ".visibility", "none"}};
            if (technique == "vsgl") settings.emplace_back("vsgl.maxLeaf", "12");
            std::unique_ptr<Renderer> renderer = test::makeTechniqueRenderer(scene, technique, settings);
            return test::renderIndirect(*renderer, camera, width, height);
        };
        const ImageRGBA32F vsgl = render("vsgl");
        const ImageRGBA32F vpl = render("vpl-brsm");
        vsglError[i] = test::relativeL1(vsgl, reference);
        vplError[i] = test::relativeL1(vpl, reference);
        between[i] = test::relativeL1(vsgl, vpl);
        if (i == 2) {
            vsglBias = test::meanLuminance(vsgl) / test::meanLuminance(reference) - 1.0;
            vplBias = test::meanLuminance(vpl) / test::meanLuminance(reference) - 1.0;
            test::saveTestImage("vsgl_corner_4096", vsgl);
            test::saveTestImage("vpl_brsm_corner_4096", vpl);
            test::saveTestImage("corner_onebounce_reference", reference);
        }
    }
    MEASURED("unoccluded corner (48x36, RSM 128^2, onebounce reference 16384 spp): relative L1 vs reference at "
             "N = 256/1024/4096: vsgl " << vsglError[0] << " " << vsglError[1] << " " << vsglError[2] << ", vpl-brsm "
             << vplError[0] << " " << vplError[1] << " " << vplError[2] << "; vsgl vs vpl-brsm " << between[0] << " "
             << between[1] << " " << between[2] << "; mean bias at N = 4096: vsgl " << vsglBias << ", vpl-brsm " << vplBias);
    CHECK(vsglError[1] < vsglError[0]);
    CHECK(vsglError[2] < vsglError[1]);
    CHECK(between[2] < between[0]);
    // Measured relative L1 vsgl 0.176 / 0.093 / 0.063, vpl-brsm 0.140 / 0.074 / 0.055 at N = 256 /
    // 1024 / 4096, and mean biases at N = 4096 of -4.2% (vsgl) and -2.8% (vpl-brsm): the RSM's
    // 128^2 texels near the corner. Bounds 2x the errors; the biases one-sided below at about 2x
    // (the sign is known) and at +2% above, where a doubled or leaked light would show.
    const double vsglBound[3] = {0.35, 0.19, 0.13}, vplBound[3] = {0.28, 0.15, 0.11};
    for (int i = 0; i < 3; ++i) {
        INFO("N = " << counts[i]);
        CHECK(vsglError[i] < vsglBound[i]);
        CHECK(vplError[i] < vplBound[i]);
    }
    CHECK(vsglBias > -0.09);
    CHECK(vsglBias < 0.02);
    CHECK(vplBias > -0.06);
    CHECK(vplBias < 0.02);
}

TEST_CASE("vpl-brsm: glossy indirect light on a metal floor like the one-bounce path tracer", "[vsgl][image][numbers]")
{
    // An RSM technique's glossy receivers (GGX at every VPL) against the one-bounce path tracer: only
    // the Lambertian wall sends light (tests/common/test_scenes.h), unoccluded, so visibility is off.
    test::ensureGLContext();
    const Scene scene = test::glossyFloorScene();
    const Camera& camera = scene.cameras[0];
    const int width = 48, height = 32;
    const ImageRGBA32F reference = test::oneBounceReference(scene, camera, width, height, 4096);
    std::unique_ptr<Renderer> renderer = test::makeTechniqueRenderer(
        scene, "vpl-brsm", {{"rsm.size", "128"}, {"vpl-brsm.count", "4096"}, {"vpl-brsm.visibility", "none"}});
    const ImageRGBA32F image = test::renderIndirect(*renderer, camera, width, height);
    const double bias = test::meanLuminance(image) / test::meanLuminance(reference) - 1.0;
    const double error = test::relativeL1(image, reference);
    MEASURED("vpl-brsm on the glossy metal floor (48x32, N = 4096, RSM 128^2) vs the one-bounce path tracer "
             "(4096 spp): mean bias " << bias << ", relative L1 " << error);
    // Measured mean bias +0.01% and relative L1 0.028. The bias bound, 1%, is the reference's own
    // accuracy at 4096 spp, not 3x a number that small; the L1 bound is 2.5x.
    CHECK(std::abs(bias) < 0.01);
    CHECK(error < 0.07);
}

TEST_CASE("vsgl and vpl-brsm images are bit-identical over runs", "[vsgl][vsgl-determinism]")
{
    test::ensureGLContext();
    const Scene scene = test::cornerScene(1.0f, 0.3f); // glossy: the SG paths too
    for (const std::string technique : {"vsgl", "vpl-brsm"})
        test::checkTechniqueBitIdentical(scene, technique, {{"rsm.size", "64"}, {technique + ".count", "300"}}, 32, 24);
}

TEST_CASE("vsgl and vpl-brsm: the imperfect shadow maps occlude the lights of both", "[vsgl][image][numbers]")
{
    // The glossy room's objects shadow part of the floor's indirect light; visibility on must
    // remove light for both light representations (the ISM pass reads each record's valid flag
    // where the VSGLight layout keeps it, in the normal's w; a VPL's r^2 = 0 is not "empty").
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("glossy");
    const Camera& camera = scene.cameras[0];
    for (const std::string technique : {"vsgl", "vpl-brsm"}) {
        auto mean = [&](const char* visibility) {
            std::unique_ptr<Renderer> renderer = test::makeTechniqueRenderer(
                scene, technique, {{"rsm.size", "64"}, {technique + ".count", "256"}, {technique + ".visibility", visibility}});
            const ImageRGBA32F image = test::renderIndirect(*renderer, camera, 48, 27);
            double sum = 0.0;
            for (std::size_t i = 0; i < image.pixels.size(); i += 4) sum += image.pixels[i + 1];
            return sum;
        };
        const double with = mean("ism"), without = mean("none");
        MEASURED(technique << " on the glossy room (48x27, N = 256): indirect light with imperfect shadow maps / without: "
                           << with / without);
        // Measured 0.950 (vsgl) and 0.948 (vpl-brsm); before the valid flag was read from the normal's
        // w, vpl-brsm's maps stayed empty (1.0). The bound asks for at least 3% of the light removed.
        CHECK(with < 0.97 * without);
        CHECK(with > 0.3 * without);
    }
}

TEST_CASE("vsgl on the shared CornellBox.glb (millimetres, a spot light added): one-bounce light like the path tracer",
          "[vsgl][image][shared][numbers]")
{
    // A scene made elsewhere, in millimetres: the RSM and ISM depth ranges, the lights' radii and
    // cones all scale with it, and a leak through the box's walls or an ISM self-shadowing bias
    // would show against the path tracer. Its emissive quad is switched off (RSMs see punctual
    // lights only) and a spot light under the ceiling added; the reference is the one-bounce path
    // tracer of the same light.
    const std::optional<std::filesystem::path> file = test::findSharedAsset("scenes/cornell-box/CornellBox.glb");
    if (!file) return;
    test::ensureGLContext();
    Scene scene = loadGltf(file->string());
    for (Material& material : scene.materials) material.emission = glm::vec3(0.0f);
    const AABB bounds = scene.worldBounds();
    const glm::vec3 centre = 0.5f * (bounds.lower + bounds.upper);
    const glm::vec3 extent = bounds.upper - bounds.lower;
    scene.lights.push_back(test::makeTestSpot("spot", centre + glm::vec3(0.0f, 0.4f * extent.y, 0.0f),
                                              {0.2f, -1.0f, 0.1f}, 1.0e6f, 0.4f, 0.6f));
    scene.validate();
    const Camera& camera = scene.cameras[0];
    const int width = 48, height = 48;
    const ImageRGBA32F reference = test::oneBounceReference(scene, camera, width, height, 2048);
    const double referenceMean = test::meanLuminance(reference);
    REQUIRE(referenceMean > 0.0);
    double bias[3], error[3];
    const char* runs[3] = {"vsgl", "vsgl texel", "vpl-brsm"};
    for (int i = 0; i < 3; ++i) {
        const std::string technique = i == 2 ? "vpl-brsm" : "vsgl";
        Settings settings = {{"rsm.size", "128"}};
        if (i == 1) settings.emplace_back("vsgl.footprint", "texel");
        std::unique_ptr<Renderer> renderer = test::makeTechniqueRenderer(scene, technique, settings);
        const ImageRGBA32F image = test::renderIndirect(*renderer, camera, width, height);
        bias[i] = test::meanLuminance(image) / referenceMean - 1.0;
        error[i] = test::relativeL1(image, reference);
    }
    MEASURED("CornellBox.glb with a spot light (48x48, N = 1024, RSM 128^2, ISMs; onebounce 2048 spp): mean bias / "
             "relative L1: " << runs[0] << " " << bias[0] << " / " << error[0] << ", " << runs[1] << " " << bias[1]
             << " / " << error[1] << ", " << runs[2] << " " << bias[2] << " / " << error[2]);
    // Measured: vsgl -5.4% / 0.164, texel -2.0% / 0.216, vpl-brsm -2.9% / 0.105 (the reference's own
    // noise is part of the L1). vsgl's bounds are about 1.5x (bias) and 3x (L1). vpl-brsm's bias:
    // the imperfect shadow maps' footprint splats shadow a little too much (a disk overhangs its
    // surface's edge: -1.6% of the visible fraction per receiver against Embree in the built-in
    // Cornell box, tests/gl/test_imperfect_shadow_maps.cpp), and here -2.4%, -2.9%, -3.5% at splat
    // scales 1, 1.25, 1.5; one-texel points with pull-push gave +0.4%, false lit and false shadows
    // cancelling. So the bound is one-sided: above +2% fails (a doubled part of the light; the
    // reference's mean is good to about 0.3% at 2048 spp), below -5% fails (a lost part). The
    // L1 bound is 2.9x.
    CHECK(std::abs(bias[0]) < 0.08);
    CHECK(error[0] < 0.45);
    CHECK(bias[2] < 0.02);
    CHECK(bias[2] > -0.05);
    CHECK(error[2] < 0.3);
}

TEST_CASE("Fig. 4a: on the caustics scene the original BRSM point-formula PDF makes vpl-brsm far noisier than the "
          "VSGL paper's PDF",
          "[vsgl][image][numbers]")
{
    // VSGL Fig. 4 (a, b): "The original BRSM technique cannot produce an appropriate PDF for specular
    // surfaces, and thus generates VPLs with high variance" (spiky artifacts). Measured as the
    // per-pixel noise over seeds: sqrt(mean over pixels of the variance over seeds) / the mean
    // image's mean. Same scene, N and seeds; only vpl-brsm.pdf differs.
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("caustics");
    const Camera& camera = scene.cameras[0];
    const int seeds = 6, width = 32, height = 18;
    auto spread = [&](const std::string& technique, const std::string& pdf) {
        std::vector<ImageRGBA32F> images;
        for (int seed = 1; seed <= seeds; ++seed) {
            std::unique_ptr<Renderer> renderer = test::makeTechniqueRenderer(
                scene, technique,
                {{technique + ".pdf", pdf}, {technique + ".seed", std::to_string(seed)}, {technique + ".visibility", "none"}});
            images.push_back(test::renderIndirect(*renderer, camera, width, height));
        }
        double variance = 0.0, mean = 0.0;
        const int pixels = width * height;
        for (int p = 0; p < pixels; ++p) {
            std::vector<double> values;
            for (const ImageRGBA32F& image : images) {
                values.push_back(test::pixelLuminance(&image.pixels[static_cast<std::size_t>(4 * p)]));
            }
            double m = 0.0, v = 0.0;
            for (double x : values) m += x / seeds;
            for (double x : values) v += (x - m) * (x - m) / (seeds - 1);
            mean += m / pixels;
            variance += v / pixels;
        }
        return std::sqrt(variance) / mean;
    };
    const double sg = spread("vpl-brsm", "sg"), point = spread("vpl-brsm", "point");
    const double vsglSG = spread("vsgl", "sg"), vsglPoint = spread("vsgl", "point");
    MEASURED("caustics (N = 1024, RSM 256^2, no visibility, 32x18, " << seeds << " seeds): per-pixel noise over seeds / "
             "mean, vpl-brsm: SG PDF " << sg << ", point-formula PDF " << point << " (" << point / sg << "x); vsgl: SG PDF "
             << vsglSG << ", point-formula PDF " << vsglPoint << " (" << vsglPoint / vsglSG << "x)");
    // Measured (seeds 1-6; seeds 7-12 in brackets): vpl-brsm 8.67 vs 16.7, 1.93x [8.04 vs 12.3, 1.53x]
    // (both spiky: unclamped VPLs, Fig. 4b); vsgl 1.76 vs 5.25, 2.99x with the default leaf cap
    // (before it: 0.93 vs 2.19, 2.36x [0.84 vs 2.95, 3.52x]). The bounds are about 0.7-0.8x the
    // smaller ratio of each. conform over 8 seeds at 64x36 agrees
    // (docs/vsgl.md, "VSGL made exact").
    CHECK(point > 1.2 * sg);
    CHECK(vsglPoint > 1.6 * vsglSG);
}
