#include "shadow_atlas.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>

#include "../api/debug.h"
#include "../api/limits.h"
#include "core/util/error.h"
#include "core/util/power_of_two.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/shadow_atlas.h"
#include "glsl/shared/vpl.h"

namespace vplgi {

namespace {

SceneProgram loadProgram(const gl::ShaderLoader& shaders, const std::string& name)
{
    return SceneProgram(shaders, name,
                        {{GL_VERTEX_SHADER, "passes/shadow_atlas.vert"}, {GL_FRAGMENT_SHADER, "passes/shadow_atlas.frag"}});
}

constexpr double kBytesPerTexel = 4.0; // DEPTH32F
constexpr double kMiB = 1024.0 * 1024.0;

} // namespace

ShadowAtlasLayout ShadowAtlas::chooseLayout(const std::string& name, const ShadowAtlasParams& params,
                                            int maxTextureSize, int maxLayers)
{
    const std::string prefix = "shadow atlas " + name + ": ";
    require(params.tileSize > 0 && params.slots > 0 && params.viewsPerSlot > 0,
            prefix + "tileSize, slots and viewsPerSlot must be positive (got " + std::to_string(params.tileSize) +
                ", " + std::to_string(params.slots) + ", " + std::to_string(params.viewsPerSlot) + ")");
    require(params.tilesPerRow == 0 || isPowerOfTwo(params.tilesPerRow),
            prefix + "tilesPerRow must be 0 (automatic) or a power of two (got " + std::to_string(params.tilesPerRow) +
                ")");
    const std::int64_t tiles = static_cast<std::int64_t>(params.slots) * params.viewsPerSlot;
    const std::string what = std::to_string(params.slots) + " slots x " + std::to_string(params.viewsPerSlot) +
                             " views = " + std::to_string(tiles) + " tiles of " + std::to_string(params.tileSize) +
                             "^2 texels";
    require(params.tileSize <= maxTextureSize, prefix + what + " do not fit: the tile is larger than " +
                                                   "GL_MAX_TEXTURE_SIZE " + std::to_string(maxTextureSize));
    const int maxPerRow = maxTextureSize / params.tileSize;
    int perRow = 1;
    if (params.tilesPerRow > 0) {
        require(params.tilesPerRow <= maxPerRow, prefix + "tilesPerRow " + std::to_string(params.tilesPerRow) +
                                                     " x tileSize " + std::to_string(params.tileSize) +
                                                     " exceeds GL_MAX_TEXTURE_SIZE " + std::to_string(maxTextureSize));
        perRow = params.tilesPerRow;
    } else {
        // The smallest power of two whose layers hold every tile (small layers leave less of the
        // last layer empty).
        while (static_cast<std::int64_t>(perRow) * perRow * maxLayers < tiles && perRow * 2 <= maxPerRow)
            perRow *= 2;
    }
    const std::int64_t perLayer = static_cast<std::int64_t>(perRow) * perRow;
    const std::int64_t layers = (tiles + perLayer - 1) / perLayer;
    require(layers <= maxLayers && tiles <= std::numeric_limits<int>::max(),
            prefix + what + " do not fit: at most " + std::to_string(perRow) +
                "^2 tiles per layer (GL_MAX_TEXTURE_SIZE " + std::to_string(maxTextureSize) + ") x " +
                std::to_string(maxLayers) +
                " layers (GL_MAX_ARRAY_TEXTURE_LAYERS) = " + std::to_string(perLayer * maxLayers) + " tiles");
    ShadowAtlasLayout layout;
    layout.tileSize = params.tileSize;
    layout.tilesPerRow = perRow;
    layout.layerSize = perRow * params.tileSize;
    layout.layers = static_cast<int>(layers);
    layout.tileCount = static_cast<int>(tiles);
    layout.memoryMiB = static_cast<double>(layers) * layout.layerSize * layout.layerSize * kBytesPerTexel / kMiB;
    require(layout.memoryMiB <= params.memoryBudgetMiB,
            prefix + what + " need " + std::to_string(static_cast<long long>(layout.memoryMiB + 0.5)) + " MiB (" +
                std::to_string(layout.layers) + " layers of " + std::to_string(layout.layerSize) +
                "^2 DEPTH32F), over the budget of " + std::to_string(static_cast<long long>(params.memoryBudgetMiB)) +
                " MiB");
    return layout;
}

ShadowAtlas::ShadowAtlas(const gl::ShaderLoader& shaders, std::string name, const ShadowAtlasParams& params)
    : mName(std::move(name)), mParams(params)
{
    const gl::Limits limits = gl::queryLimits();
    mLayout = chooseLayout(mName, mParams, limits.maxTextureSize, limits.maxArrayTextureLayers);
    mProgram = loadProgram(shaders, "shadow atlas " + mName);

    gl::SamplerDesc samplerDesc;
    samplerDesc.minFilter = GL_NEAREST;
    samplerDesc.magFilter = GL_NEAREST;
    mSampler = gl::Sampler("shadow atlas " + mName + " sampler", samplerDesc);

    gl::RenderTargetDesc desc;
    desc.depthFormat = GL_DEPTH_COMPONENT32F;
    desc.textureTarget = GL_TEXTURE_2D_ARRAY;
    mTarget = gl::RenderTarget("shadow atlas " + mName, desc);
    while (glGetError() != GL_NO_ERROR) {
    }
    mTarget.resize(mLayout.layerSize, mLayout.layerSize, mLayout.layers);
    require(glGetError() != GL_OUT_OF_MEMORY, "shadow atlas " + mName + ": the driver could not allocate " +
                                                  std::to_string(static_cast<long long>(mLayout.memoryMiB + 0.5)) +
                                                  " MiB (" + std::to_string(mLayout.layers) + " layers of " +
                                                  std::to_string(mLayout.layerSize) + "^2 DEPTH32F)");
    mTarget.clear(); // depth 1 everywhere: a tile never rendered shadows nothing

    mMatrices.assign(static_cast<std::size_t>(mLayout.tileCount), glm::mat4(1.0f));
    mMatrixBuffer = gl::Buffer("shadow atlas " + mName + " matrices",
                               static_cast<GLsizeiptr>(mMatrices.size() * sizeof(glm::mat4)), mMatrices.data());
}

void ShadowAtlas::reloadShaders(const gl::ShaderLoader& shaders)
{
    mProgram = loadProgram(shaders, "shadow atlas " + mName);
}

void ShadowAtlas::renderDirty(const GpuScene& scene, const std::vector<std::uint32_t>& slots,
                              const std::vector<glm::mat4>& clipFromWorldPerSlotView)
{
    const int views = mParams.viewsPerSlot;
    require(clipFromWorldPerSlotView.size() == slots.size() * static_cast<std::size_t>(views),
            "shadow atlas " + mName + ": renderDirty got " + std::to_string(clipFromWorldPerSlotView.size()) +
                " matrices for " + std::to_string(slots.size()) + " slots x " + std::to_string(views) + " views");
    if (slots.empty()) return;
    gl::DebugGroup group("shadow atlas " + mName);

    std::vector<char> seen(static_cast<std::size_t>(mParams.slots), 0);
    std::vector<int> drawTiles;
    drawTiles.reserve(clipFromWorldPerSlotView.size());
    for (std::size_t i = 0; i < slots.size(); ++i) {
        const std::uint32_t slot = slots[i];
        require(slot < static_cast<std::uint32_t>(mParams.slots) && !seen[slot],
                "shadow atlas " + mName + ": renderDirty slot " + std::to_string(slot) +
                    (slot < static_cast<std::uint32_t>(mParams.slots)
                         ? " given twice"
                         : " out of range (slots: " + std::to_string(mParams.slots) + ")"));
        seen[slot] = 1;
        for (int v = 0; v < views; ++v) {
            const int tile = shared::shadowAtlasTileIndex(static_cast<int>(slot), v, views);
            mMatrices[static_cast<std::size_t>(tile)] =
                clipFromWorldPerSlotView[i * views + static_cast<std::size_t>(v)];
            drawTiles.push_back(tile);
        }
    }
    // The matrix buffer mirrors every tile (readers index it by tile index): upload the span that
    // changed in one call.
    const auto [lowest, highest] = std::minmax_element(drawTiles.begin(), drawTiles.end());
    const std::size_t first = static_cast<std::size_t>(*lowest);
    mMatrixBuffer.upload(static_cast<GLintptr>(first * sizeof(glm::mat4)),
                         static_cast<GLsizeiptr>((static_cast<std::size_t>(*highest) + 1 - first) * sizeof(glm::mat4)),
                         &mMatrices[first]);
    gl::uploadVector(mDrawTiles, "shadow atlas " + mName + " draw tiles", drawTiles);

    std::vector<int> sorted = drawTiles;
    std::sort(sorted.begin(), sorted.end());
    clearTiles(sorted);

    mTarget.bindForDrawing();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    // Required by the spec for the shader's clip distances to clip. llvmpipe (Mesa 22.3) clips with
    // written clip distances even without these enables, so the bleed test cannot see them missing there.
    for (GLenum plane = 0; plane < 4; ++plane)
        glEnable(GL_CLIP_DISTANCE0 + plane);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kBindingShadowAtlasMatrices, mMatrixBuffer.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kBindingShadowAtlasDraw, mDrawTiles.id());
    mProgram.set("uTilesPerRow", mLayout.tilesPerRow);
    scene.draw(mProgram, GpuScene::Bind::Geometry, static_cast<GLsizei>(drawTiles.size()));
    glUseProgram(0);
    for (GLenum plane = 0; plane < 4; ++plane)
        glDisable(GL_CLIP_DISTANCE0 + plane);
    glDisable(GL_DEPTH_TEST);
}

void ShadowAtlas::clearTiles(const std::vector<int>& sortedTiles) const
{
    // Runs of consecutive tile indices become as few rectangles as the layout allows: whole layers
    // when a layer holds one tile, otherwise whole rows of a layer and the partial rows around them.
    const float one = 1.0f;
    const int n = mLayout.tilesPerRow;
    const int size = mLayout.tileSize;
    const GLuint texture = mTarget.depth().id();
    for (std::size_t i = 0; i < sortedTiles.size();) {
        std::size_t end = i + 1;
        while (end < sortedTiles.size() && sortedTiles[end] == sortedTiles[end - 1] + 1)
            ++end;
        int tile = sortedTiles[i];
        const int stop = sortedTiles[end - 1] + 1;
        while (tile < stop) {
            const glm::ivec3 t = shared::shadowAtlasTileFromIndex(tile, n);
            int width = 1, height = 1, depth = 1;
            if (n == 1) {
                depth = stop - tile;
            } else if (t.x == 0 && stop - tile >= n) {
                height = std::min((stop - tile) / n, n - t.y);
                width = n;
            } else {
                width = std::min(stop - tile, n - t.x);
            }
            glClearTexSubImage(texture, 0, t.x * size, t.y * size, t.z, width * size, height * size, depth,
                               GL_DEPTH_COMPONENT, GL_FLOAT, &one);
            tile += width * height * depth;
        }
        i = end;
    }
}

void ShadowAtlas::bindForReading() const
{
    glBindTextureUnit(shared::kUnitShadowAtlas, mTarget.depth().id());
    glBindSampler(shared::kUnitShadowAtlas, mSampler.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, shared::kBindingShadowAtlasMatrices, mMatrixBuffer.id());
}

gl::Texture makeParaboloidMapAtlas(const std::string& name, int mapSize, int slots, int levels,
                                   ShadowAtlasLayout& layout, GLenum format)
{
    require(format == GL_R32F || format == GL_R32UI, name + ": paraboloid map atlases are r32f or r32ui");
    const gl::Limits limits = gl::queryLimits();
    // 4 bytes per texel as the shadow atlas's DEPTH32F: its memory estimate holds for level 0.
    ShadowAtlasParams params;
    params.tileSize = mapSize;
    params.slots = slots;
    params.viewsPerSlot = 1;
    layout = ShadowAtlas::chooseLayout(name, params, limits.maxTextureSize, limits.maxArrayTextureLayers);

    gl::TextureDesc desc;
    desc.target = GL_TEXTURE_2D_ARRAY;
    desc.format = format;
    desc.width = layout.layerSize;
    desc.height = layout.layerSize;
    desc.layers = layout.layers;
    desc.levels = levels;
    while (glGetError() != GL_NO_ERROR) {
    }
    gl::Texture maps(name, desc);
    const double mipFactor = levels > 1 ? 4.0 / 3.0 : 1.0;
    require(glGetError() != GL_OUT_OF_MEMORY,
            name + ": the driver could not allocate " +
                std::to_string(static_cast<long long>(layout.memoryMiB * mipFactor + 0.5)) + " MiB");
    const float none = shared::kVPLNoOccluder;
    const std::uint32_t allBits = 0xFFFFFFFFu;
    for (int level = 0; level < levels; ++level) {
        if (format == GL_R32F)
            glClearTexImage(maps.id(), level, GL_RED, GL_FLOAT, &none);
        else
            glClearTexImage(maps.id(), level, GL_RED_INTEGER, GL_UNSIGNED_INT, &allBits);
    }
    return maps;
}

} // namespace vplgi
