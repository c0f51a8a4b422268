// ShadowAtlas (gl/passes/shadow_atlas.h): every tile against the same view rendered alone into a
// full-size depth map by the plain layered shadow shader (passes/shadow.vert, no squeeze, no clip
// distances); partial updates leave the other tiles bit-identical; nothing bleeds across tile
// edges; layouts and errors at the capacity limits; the same input gives the same bits.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "core/scene/builtin_scenes.h"
#include "gl/api/debug.h"
#include "gl/api/render_target.h"
#include "gl/gpu_scene.h"
#include "gl/passes/shadow_atlas.h"
#include "gl_test_context.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/light_view.h"
#include "glsl/shared/shadow_atlas.h"

using namespace vplgi;
using Catch::Matchers::Contains;

namespace {

// Depths of one tileSize^2 rectangle of layer `layer`, rows bottom to top.
std::vector<float> readDepth(const gl::Texture& texture, int x, int y, int layer, int width, int height)
{
    std::vector<float> depth(static_cast<std::size_t>(width) * height);
    glGetTextureSubImage(texture.id(), 0, x, y, layer, width, height, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                         static_cast<GLsizei>(depth.size() * sizeof(float)), depth.data());
    return depth;
}

std::vector<float> readTile(const ShadowAtlas& atlas, int slot, int view)
{
    const ShadowAtlasLayout& layout = atlas.layout();
    const glm::ivec3 tile = shared::shadowAtlasTile(slot, view, atlas.params().viewsPerSlot, layout.tilesPerRow);
    return readDepth(atlas.texture(), tile.x * layout.tileSize, tile.y * layout.tileSize, tile.z, layout.tileSize,
                     layout.tileSize);
}

std::vector<float> readAll(const ShadowAtlas& atlas)
{
    const ShadowAtlasLayout& layout = atlas.layout();
    std::vector<float> depth(static_cast<std::size_t>(layout.layerSize) * layout.layerSize * layout.layers);
    glGetTextureImage(atlas.texture().id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                      static_cast<GLsizei>(depth.size() * sizeof(float)), depth.data());
    return depth;
}

// One view rendered alone into a size^2 DEPTH32F map with the existing layered shadow shader.
class SingleViewRenderer {
public:
    explicit SingleViewRenderer(int size)
        : mProgram(test::shaders(), "single view",
                   {{GL_VERTEX_SHADER, "passes/shadow.vert"}, {GL_FRAGMENT_SHADER, "passes/shadow_atlas.frag"}})
    {
        gl::RenderTargetDesc desc;
        desc.depthFormat = GL_DEPTH_COMPONENT32F;
        desc.textureTarget = GL_TEXTURE_2D_ARRAY;
        mTarget = gl::RenderTarget("single view", desc);
        mTarget.resize(size, size, 1);
        mMatrix = gl::Buffer("single view matrix", sizeof(glm::mat4));
    }

    std::vector<float> render(const GpuScene& scene, const glm::mat4& clipFromWorld)
    {
        mMatrix.upload(0, sizeof(glm::mat4), &clipFromWorld);
        mTarget.bindForDrawing();
        mTarget.clear();
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kBindingShadowMatrices, mMatrix.id());
        mProgram.set("uFirstLayer", 0);
        scene.draw(mProgram, GpuScene::Bind::Geometry, 1);
        glDisable(GL_DEPTH_TEST);
        return readDepth(mTarget.depth(), 0, 0, 0, mTarget.width(), mTarget.height());
    }

private:
    SceneProgram mProgram;
    gl::RenderTarget mTarget;
    gl::Buffer mMatrix;
};

// SMCIR-like views: hemisphere-cube faces of VPLs at random points of the scene box with random
// normals (seeded), viewsPerSlot faces per slot.
std::vector<glm::mat4> hemisphereViews(const Scene& scene, int slots, int viewsPerSlot, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const AABB bounds = scene.worldBounds();
    const float diagonal = glm::length(bounds.extent());
    std::vector<glm::mat4> matrices;
    for (int s = 0; s < slots; ++s) {
        const glm::vec3 p = bounds.lower + bounds.extent() * glm::vec3(0.1f + 0.8f * u(rng), 0.1f + 0.8f * u(rng),
                                                                       0.1f + 0.8f * u(rng));
        const float z = 2.0f * u(rng) - 1.0f, phi = 6.2831853f * u(rng);
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const glm::mat3 basis = shared::lightViewHemisphereBasis(glm::vec3(r * std::cos(phi), r * std::sin(phi), z));
        for (int v = 0; v < viewsPerSlot; ++v)
            matrices.push_back(
                shared::lightViewHemisphereFaceClipFromWorld(p, basis, v % 3, 0.01f * diagonal, 1.5f * diagonal));
    }
    return matrices;
}

std::vector<std::uint32_t> allSlots(int slots)
{
    std::vector<std::uint32_t> list(static_cast<std::size_t>(slots));
    for (int s = 0; s < slots; ++s)
        list[static_cast<std::size_t>(s)] = static_cast<std::uint32_t>(s);
    return list;
}

// The atlas and the view rendered alone rasterize the same triangles with the same z and w, but the
// atlas clips them to the tile (new vertices) and sets up its depth planes at other window
// positions, so window-space depths differ by float rounding in most covered texels. Measured on
// llvmpipe: at most 5.6e-6 (72 tiles of 64^2, cornell; 2.7e-6 for 128^2 tiles). Coverage is
// checked exactly: a texel empty (depth 1) in one must be empty in the other. On an H200 (vertices
// snapped to its sub-pixel grid at other window positions; test::twinTolerance): at most 6.4e-4
// (64^2 tiles), 1.1e-4 (32^2) and 2.3e-4 (128^2), on steep depth slopes.
float depthTolerance()
{
    return test::twinTolerance(1.5e-5f, 1.6e-3f);
}

struct TileDifference {
    int texels = 0;       // texels whose depths differ at all
    int coverage = 0;     // texels empty in one and covered in the other
    float largest = 0.0f; // largest |atlas - alone|
};

TileDifference compare(const std::vector<float>& atlas, const std::vector<float>& alone)
{
    TileDifference d;
    for (std::size_t i = 0; i < atlas.size(); ++i) {
        if (atlas[i] == alone[i]) continue;
        ++d.texels;
        d.coverage += (atlas[i] == 1.0f) != (alone[i] == 1.0f) ? 1 : 0;
        d.largest = std::max(d.largest, std::abs(atlas[i] - alone[i]));
    }
    return d;
}

// Tiles of `atlas` for `slots` against the views rendered alone; returns the worst tile.
TileDifference compareWithAlone(const ShadowAtlas& atlas, const GpuScene& scene, SingleViewRenderer& alone,
                                const std::vector<std::uint32_t>& slots, const std::vector<glm::mat4>& matrices,
                                int* tilesWithGeometry = nullptr)
{
    const int views = atlas.params().viewsPerSlot;
    TileDifference worst;
    for (std::size_t i = 0; i < slots.size(); ++i)
        for (int v = 0; v < views; ++v) {
            const std::vector<float> tile = readTile(atlas, static_cast<int>(slots[i]), v);
            const TileDifference d =
                compare(tile, alone.render(scene, matrices[i * views + static_cast<std::size_t>(v)]));
            worst.texels = std::max(worst.texels, d.texels);
            worst.coverage += d.coverage;
            worst.largest = std::max(worst.largest, d.largest);
            if (tilesWithGeometry && *std::min_element(tile.begin(), tile.end()) < 1.0f) ++*tilesWithGeometry;
        }
    return worst;
}

} // namespace

TEST_CASE("shadow atlas: every tile holds the depths of its view rendered alone", "[gl][atlas]")
{
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("cornell");
    const GpuScene gpuScene(scene);
    ShadowAtlasParams params;
    params.tileSize = 64;
    params.slots = 24;
    params.viewsPerSlot = 3;
    params.tilesPerRow = 4; // 72 tiles in 5 layers of 4 x 4: squeezed tiles in every position of a layer
    ShadowAtlas atlas(test::shaders(), "test", params);
    REQUIRE(atlas.layout().layers == 5);
    REQUIRE(atlas.layout().layerSize == 256);
    const std::vector<glm::mat4> matrices = hemisphereViews(scene, params.slots, params.viewsPerSlot, 7);
    atlas.renderDirty(gpuScene, allSlots(params.slots), matrices);
    SingleViewRenderer alone(params.tileSize);
    int tilesWithGeometry = 0;
    const TileDifference worst =
        compareWithAlone(atlas, gpuScene, alone, allSlots(params.slots), matrices, &tilesWithGeometry);
    std::printf(
        "shadow atlas vs alone (72 tiles of 64^2, cornell): at most %d texels of a tile differ, by at most %.3g\n",
        worst.texels, static_cast<double>(worst.largest));
    CHECK(tilesWithGeometry == params.slots * params.viewsPerSlot); // inside the box every view sees a wall

    // The reader's side: GLSL lookups through shadowAtlasTile / shadowAtlasCoordinates (nearest
    // sampler) return exactly the texel the C++ side names, also at and beyond the tile's edges
    // (clamped to the border texels, never a neighbour's).
    struct Lookup {
        glm::ivec4 slotView;
        glm::vec4 tileUV;
    };
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-0.1f, 1.1f);
    std::vector<Lookup> lookups;
    for (int i = 0; i < 512; ++i)
        lookups.push_back({glm::ivec4(i % params.slots, (i / params.slots) % params.viewsPerSlot, 0, 0),
                           glm::vec4(i % 7 == 0 ? 0.0f : u(rng), i % 5 == 0 ? 1.0f : u(rng), 0.0f, 0.0f)});
    gl::Program probe =
        gl::ShaderLoader(std::string(VPLGI_SOURCE_DIR) + "/glsl")
            .load("shadow atlas probe", {{GL_COMPUTE_SHADER, "../tests/gl/glsl/shadow_atlas_probe.comp"}});
    gl::Buffer input("shadow atlas lookups", static_cast<GLsizeiptr>(lookups.size() * sizeof(Lookup)), lookups.data());
    gl::Buffer output("shadow atlas lookup results", static_cast<GLsizeiptr>(lookups.size() * sizeof(glm::vec4)));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, input.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, output.id());
    atlas.bindForReading();
    probe.set("uCount", static_cast<int>(lookups.size()));
    probe.set("uViewsPerSlot", params.viewsPerSlot);
    probe.set("uTilesPerRow", atlas.layout().tilesPerRow);
    probe.set("uTileSize", params.tileSize);
    glUseProgram(probe.id());
    glDispatchCompute(static_cast<GLuint>((lookups.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glUseProgram(0);
    std::vector<glm::vec4> results(lookups.size());
    glGetNamedBufferSubData(output.id(), 0, output.size(), results.data());
    int wrongTiles = 0, wrongDepths = 0;
    for (std::size_t i = 0; i < lookups.size(); ++i) {
        const Lookup& l = lookups[i];
        const glm::ivec3 tile = shared::shadowAtlasTile(l.slotView.x, l.slotView.y, params.viewsPerSlot, 4);
        wrongTiles += glm::vec3(tile) == glm::vec3(results[i].y, results[i].z, results[i].w) ? 0 : 1;
        const glm::ivec2 texel = glm::clamp(glm::ivec2(glm::floor(glm::vec2(l.tileUV) * float(params.tileSize))),
                                            glm::ivec2(0), glm::ivec2(params.tileSize - 1));
        const std::vector<float> depth = readTile(atlas, l.slotView.x, l.slotView.y);
        wrongDepths += depth[static_cast<std::size_t>(texel.y * params.tileSize + texel.x)] == results[i].x ? 0 : 1;
    }
    CHECK(wrongTiles == 0);
    CHECK(wrongDepths == 0);
    CHECK(worst.largest <= depthTolerance());
    CHECK(worst.coverage == 0);
    gl::checkDebugMessages();
}

TEST_CASE("shadow atlas: renderDirty of a subset leaves the other tiles bit-identical", "[gl][atlas]")
{
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("cornell");
    const GpuScene gpuScene(scene);
    ShadowAtlasParams params;
    params.tileSize = 32;
    params.slots = 21;
    params.viewsPerSlot = 3;
    params.tilesPerRow = 4;
    ShadowAtlas atlas(test::shaders(), "subset", params);
    atlas.renderDirty(gpuScene, allSlots(params.slots), hemisphereViews(scene, params.slots, params.viewsPerSlot, 11));
    const std::vector<float> before = readAll(atlas);

    // Slots whose tiles start mid-row, span a row end and a layer end (slot 5 = tiles 15..17), and
    // the last slot; in no particular order.
    const std::vector<std::uint32_t> subset = {20, 5, 1, 6, 12};
    const std::vector<glm::mat4> moved =
        hemisphereViews(scene, static_cast<int>(subset.size()), params.viewsPerSlot, 12);
    atlas.renderDirty(gpuScene, subset, moved);
    const std::vector<float> after = readAll(atlas);

    const ShadowAtlasLayout& layout = atlas.layout();
    int untouchedDiffering = 0, updatedChanged = 0, updatedTiles = 0;
    for (int slot = 0; slot < params.slots; ++slot) {
        const bool updated = std::find(subset.begin(), subset.end(), static_cast<std::uint32_t>(slot)) != subset.end();
        for (int v = 0; v < params.viewsPerSlot; ++v) {
            const glm::ivec3 tile = shared::shadowAtlasTile(slot, v, params.viewsPerSlot, layout.tilesPerRow);
            bool same = true;
            for (int y = 0; y < layout.tileSize; ++y) {
                const std::size_t row = (static_cast<std::size_t>(tile.z) * layout.layerSize +
                                         static_cast<std::size_t>(tile.y * layout.tileSize + y)) *
                                            layout.layerSize +
                                        static_cast<std::size_t>(tile.x * layout.tileSize);
                same = same && std::memcmp(&before[row], &after[row], layout.tileSize * sizeof(float)) == 0;
            }
            if (updated) {
                ++updatedTiles;
                updatedChanged += same ? 0 : 1;
            } else {
                untouchedDiffering += same ? 0 : 1;
            }
        }
    }
    // The unused tile of the last layer (63 tiles used of 64: tile (3, 3) of layer 3) stays cleared.
    CHECK(layout.tileCount == 63);
    CHECK(layout.layers == 4);
    int unusedWritten = 0;
    for (int y = 3 * layout.tileSize; y < layout.layerSize; ++y)
        for (int x = 3 * layout.tileSize; x < layout.layerSize; ++x)
            unusedWritten += after[(static_cast<std::size_t>(3 * layout.layerSize + y)) * layout.layerSize +
                                   static_cast<std::size_t>(x)] == 1.0f
                                 ? 0
                                 : 1;
    CHECK(unusedWritten == 0);
    CHECK(untouchedDiffering == 0);
    CHECK(updatedChanged == updatedTiles); // the new views differ, so a skipped update would show
    SingleViewRenderer alone(params.tileSize);
    const TileDifference worst = compareWithAlone(atlas, gpuScene, alone, subset, moved);
    std::printf(
        "shadow atlas subset update vs alone (15 tiles of 32^2): at most %d texels of a tile differ, by at most %.3g\n",
        worst.texels, static_cast<double>(worst.largest));
    CHECK(worst.largest <= depthTolerance());
    CHECK(worst.coverage == 0);
    gl::checkDebugMessages();
}

TEST_CASE("shadow atlas: geometry crossing a tile's edge does not bleed into the neighbours", "[gl][atlas]")
{
    test::ensureGLContext();
    // A 1 km ground plane seen from 1 m above through a 90 degree frustum: the plane fills the view
    // and extends far past every edge of it, so without the clip distances its squeezed triangles
    // would cover the whole layer.
    Scene scene;
    scene.materials.push_back(Material{});
    Mesh plane;
    for (int i = 0; i < 4; ++i) {
        Vertex v;
        v.position = glm::vec3(i % 2 == 0 ? -500.0f : 500.0f, 0.0f, i < 2 ? -500.0f : 500.0f);
        plane.vertices.push_back(v);
    }
    plane.indices = {0, 2, 1, 1, 2, 3};
    scene.meshes.push_back(plane);
    scene.instances.push_back(Instance{});
    const GpuScene gpuScene(scene);
    ShadowAtlasParams params;
    params.tileSize = 32;
    params.slots = 16;
    params.tilesPerRow = 4;
    ShadowAtlas atlas(test::shaders(), "bleed", params);
    const glm::mat4 down = shared::lightViewCubeFaceClipFromWorld(glm::vec3(0.0f, 1.0f, 0.0f), 3, 0.1f, 10.0f);
    const std::uint32_t centre = 5; // tile (1, 1): neighbours on all four sides and corners
    atlas.renderDirty(gpuScene, {centre}, {down});
    const std::vector<float> depth = readAll(atlas);
    const int size = atlas.layout().layerSize;
    int insideCovered = 0, outsideWritten = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const bool inside = x / params.tileSize == 1 && y / params.tileSize == 1;
            const float d = depth[static_cast<std::size_t>(y) * size + static_cast<std::size_t>(x)];
            if (inside)
                insideCovered += d < 1.0f ? 1 : 0;
            else
                outsideWritten += d != 1.0f ? 1 : 0;
        }
    CHECK(insideCovered == params.tileSize * params.tileSize);
    CHECK(outsideWritten == 0);
    gl::checkDebugMessages();
}

TEST_CASE("shadow atlas: layouts at the capacity limits, and errors that name the numbers", "[gl][atlas]")
{
    ShadowAtlasParams params;
    params.tileSize = 128;
    params.slots = 8192;
    params.viewsPerSlot = 1;
    // llvmpipe's limits (GL_MAX_TEXTURE_SIZE 16384, GL_MAX_ARRAY_TEXTURE_LAYERS 2048).
    ShadowAtlasLayout one = ShadowAtlas::chooseLayout("one", params, 16384, 2048);
    CHECK(one.tilesPerRow == 2);
    CHECK(one.layers == 2048);
    CHECK(one.memoryMiB == 512.0);
    params.viewsPerSlot = 3;
    ShadowAtlasLayout three = ShadowAtlas::chooseLayout("three", params, 16384, 2048);
    CHECK(three.tilesPerRow == 4);
    CHECK(three.layers == 1536);
    CHECK(three.memoryMiB == 1536.0);
    params.memoryBudgetMiB = 1024.0;
    CHECK_THROWS_WITH(ShadowAtlas::chooseLayout("vpl", params, 16384, 2048),
                      "shadow atlas vpl: 8192 slots x 3 views = 24576 tiles of 128^2 texels need 1536 MiB "
                      "(1536 layers of 512^2 DEPTH32F), over the budget of 1024 MiB");
    CHECK_THROWS_WITH(
        ShadowAtlas::chooseLayout("vpl", params, 256, 2048),
        "shadow atlas vpl: 8192 slots x 3 views = 24576 tiles of 128^2 texels do not fit: at most 2^2 "
        "tiles per layer (GL_MAX_TEXTURE_SIZE 256) x 2048 layers (GL_MAX_ARRAY_TEXTURE_LAYERS) = 8192 tiles");
    params.tilesPerRow = 3;
    CHECK_THROWS_WITH(ShadowAtlas::chooseLayout("vpl", params, 16384, 2048), Contains("power of two"));
    params.tilesPerRow = 256;
    CHECK_THROWS_WITH(ShadowAtlas::chooseLayout("vpl", params, 16384, 2048), Contains("GL_MAX_TEXTURE_SIZE 16384"));

    // The driver's own limits: 8192 maps of 128^2 are allocated and usable; an impossible atlas
    // throws before allocating anything.
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("cornell");
    const GpuScene gpuScene(scene);
    ShadowAtlasParams big;
    big.tileSize = 128;
    big.slots = 8192;
    ShadowAtlas atlas(test::shaders(), "8192", big);
    std::printf("shadow atlas of 8192 x 1 maps of 128^2: %d tiles per row, %d layers of %d^2, %.0f MiB\n",
                atlas.layout().tilesPerRow, atlas.layout().layers, atlas.layout().layerSize, atlas.layout().memoryMiB);
    const std::vector<std::uint32_t> ends = {0, 1, 4097, 8191};
    const std::vector<glm::mat4> matrices = hemisphereViews(scene, 4, 1, 3);
    atlas.renderDirty(gpuScene, ends, matrices);
    SingleViewRenderer alone(big.tileSize);
    const TileDifference worst = compareWithAlone(atlas, gpuScene, alone, ends, matrices);
    std::printf(
        "shadow atlas of 8192 maps vs alone (4 tiles of 128^2): at most %d texels of a tile differ, by at most %.3g\n",
        worst.texels, static_cast<double>(worst.largest));
    CHECK(worst.largest <= depthTolerance());
    CHECK(worst.coverage == 0);
    ShadowAtlasParams impossible;
    impossible.tileSize = 4096;
    impossible.slots = 1 << 20;
    impossible.viewsPerSlot = 3;
    CHECK_THROWS_WITH(
        ShadowAtlas(test::shaders(), "impossible", impossible),
        Contains("shadow atlas impossible: 1048576 slots x 3 views = 3145728 tiles of 4096^2 texels do not fit"));
    gl::checkDebugMessages();
}

TEST_CASE("shadow atlas: renderDirty rejects bad slots and matrix counts", "[gl][atlas]")
{
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("cornell");
    const GpuScene gpuScene(scene);
    ShadowAtlasParams params;
    params.tileSize = 16;
    params.slots = 4;
    params.viewsPerSlot = 2;
    ShadowAtlas atlas(test::shaders(), "checks", params);
    const glm::mat4 m(1.0f);
    CHECK_THROWS_WITH(atlas.renderDirty(gpuScene, {0}, {m}),
                      "shadow atlas checks: renderDirty got 1 matrices for 1 slots x 2 views");
    CHECK_THROWS_WITH(atlas.renderDirty(gpuScene, {4}, {m, m}),
                      "shadow atlas checks: renderDirty slot 4 out of range (slots: 4)");
    CHECK_THROWS_WITH(atlas.renderDirty(gpuScene, {1, 1}, {m, m, m, m}),
                      "shadow atlas checks: renderDirty slot 1 given twice");
    gl::checkDebugMessages();
}

TEST_CASE("shadow atlas: the same views give the same bits", "[gl][atlas]")
{
    test::ensureGLContext();
    const Scene scene = makeBuiltinScene("cornell");
    const GpuScene gpuScene(scene);
    ShadowAtlasParams params;
    params.tileSize = 32;
    params.slots = 40;
    params.viewsPerSlot = 3;
    params.tilesPerRow = 8;
    const std::vector<glm::mat4> matrices = hemisphereViews(scene, params.slots, params.viewsPerSlot, 5);
    std::vector<float> runs[2];
    for (std::vector<float>& run : runs) {
        ShadowAtlas atlas(test::shaders(), "determinism", params);
        atlas.renderDirty(gpuScene, allSlots(params.slots), matrices);
        run = readAll(atlas);
    }
    CHECK(std::memcmp(runs[0].data(), runs[1].data(), runs[0].size() * sizeof(float)) == 0);
    gl::checkDebugMessages();
}
