// Shadow atlas: many small depth maps (a few per light or VPL) in the layers of one 2D array
// texture, re-rendered only for the slots that changed.
//
// Intro
// -----
// SMCIR and IR render three hemisphere-cube faces per VPL (glsl/shared/light_view.h) and re-render
// only the VPLs that changed (VPLSet::changed). 2048 VPLs x 3 faces are more maps than
// GL_MAX_ARRAY_TEXTURE_LAYERS (2048 on llvmpipe), so maps are tiles inside layers: a layer holds
// tilesPerRow^2 tiles of tileSize^2 texels. Slot s (a light, a VPL) owns viewsPerSlot consecutive
// tiles; glsl/shared/shadow_atlas.h maps (slot, view) -> (layer, tile x, tile y) for both the
// renderer and the passes that read the maps, and documents the formula.
//
// Overview
// --------
//  ShadowAtlas(shaders, name, params)  chooses the layout (chooseLayout), allocates the texture and
//                                      clears it to depth 1 (no occluder) everywhere
//  renderDirty(scene, slots, matrices) clears the given slots' tiles and renders them all in one
//                                      instanced draw per mesh
//  bindForReading()                    texture at kUnitShadowAtlas, the clipFromWorld of every tile
//                                      at kBindingShadowAtlasMatrices
//
// Details
// -------
//  Format: GL_DEPTH_COMPONENT32F, not an R32F distance. The atlas is the depth attachment itself,
//  so a depth-only draw with an empty fragment shader fills it (no colour write, no second depth
//  buffer, early depth test), the stored value is exactly what the same view rendered alone would
//  store (window-space depth of that view's projection), and readers may use a comparison sampler.
//  A reader that wants distances linearises with the tile's matrix (bound for reading).
//
//  Layout: tilesPerRow is a power of two (the squeeze 1/n and its offsets are exact in float), by
//  default the smallest one whose layers, at most GL_MAX_ARRAY_TEXTURE_LAYERS of them, hold every
//  tile, with the layer size tilesPerRow * tileSize within GL_MAX_TEXTURE_SIZE. Small atlases thus
//  get one map per layer, and only the last layer is partly empty. The limits are queried; when the
//  tiles cannot fit, or the texture would exceed params.memoryBudgetMiB, the constructor throws one
//  Error naming the numbers.
//
//  One instanced draw per mesh, rather than
//   - viewport arrays: GL_MAX_VIEWPORTS is 16, so a draw reaches at most 16 tiles (2048 x 3 tiles
//     would take 384 draws per mesh), and a viewport index per instance needs the same extension;
//   - one draw per tile: thousands of draws per mesh, each with its state changes and (on llvmpipe)
//     its own pass over the vertex data.
//  The vertex shader squeezes the view's clip x, y into the tile's rectangle of the layer (depth
//  untouched) and clips to the view's frustum with gl_ClipDistance[0..3], so nothing bleeds into
//  neighbouring tiles; the cost is four clip distances per vertex. No geometry shader (2x slower on
//  llvmpipe). The tiles of one draw may lie in any layers; the framebuffer is layered.
//
//  The point-light cube shadows of ShadowPass keep their own path (a cube-map array storing radial
//  distance, sampled with hardware cube-face selection); the atlas serves the many small maps of
//  SMCIR / IR VPLs and many-light shadows.
//
// References
// ----------
//  SMCIR (papers/000) Sec. 4: per-VPL hemisphere cubes, re-rendered only for VPLs that changed.
//  OpenGL 4.5 core Sec. 13.5 (clip distances), ARB_shader_viewport_layer_array (gl_Layer in a VS).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "../api/render_target.h"
#include "../api/shader_loader.h"
#include "../gpu_scene.h"

namespace vplgi {

struct ShadowAtlasParams {
    int tileSize = 128;              // resolution of one view's map [texels]
    int slots = 1;                   // lights or VPLs with maps
    int viewsPerSlot = 1;            // maps per slot (3 for SMCIR's hemisphere cube)
    int tilesPerRow = 0;             // tiles across a layer, a power of two; 0 = the smallest that fits
    double memoryBudgetMiB = 2048.0; // the largest texture allowed [MiB]
};

// Where the tiles are: chosen once from the parameters and the GL limits.
struct ShadowAtlasLayout {
    int tileSize = 0;       // [texels]
    int tilesPerRow = 0;    // tiles across (and down) a layer
    int layerSize = 0;      // tilesPerRow * tileSize [texels]
    int layers = 0;         // array layers allocated
    int tileCount = 0;      // slots * viewsPerSlot (tiles in use)
    double memoryMiB = 0.0; // layers * layerSize^2 * 4 bytes [MiB]
};

class ShadowAtlas {
public:
    // Throws Error "shadow atlas <name>: ..." naming the numbers when the tiles do not fit the GL
    // limits or the budget, or when the driver cannot allocate the texture.
    ShadowAtlas(const gl::ShaderLoader& shaders, std::string name, const ShadowAtlasParams& params);
    void reloadShaders(const gl::ShaderLoader& shaders);

    // The layout for `params` under the limits GL_MAX_TEXTURE_SIZE = maxTextureSize and
    // GL_MAX_ARRAY_TEXTURE_LAYERS = maxLayers (no GL calls); throws as the constructor does.
    static ShadowAtlasLayout chooseLayout(const std::string& name, const ShadowAtlasParams& params, int maxTextureSize,
                                          int maxLayers);

    // Clears the tiles of `slots` (distinct, each < params.slots) and renders `scene` into them:
    // view v of slots[i] with clipFromWorldPerSlotView[i * viewsPerSlot + v]. Other tiles keep their
    // contents bit for bit. One instanced draw per mesh for all of them.
    void renderDirty(const GpuScene& scene, const std::vector<std::uint32_t>& slots,
                     const std::vector<glm::mat4>& clipFromWorldPerSlotView);
    // Binds the depth texture (nearest sampler) at kUnitShadowAtlas and the clipFromWorld of every
    // tile (indexed by tile index; identity until its slot is first rendered) at
    // kBindingShadowAtlasMatrices.
    void bindForReading() const;

    const ShadowAtlasLayout& layout() const { return mLayout; }
    const ShadowAtlasParams& params() const { return mParams; }
    const gl::Texture& texture() const { return mTarget.depth(); }
    const std::string& name() const { return mName; }

private:
    void clearTiles(const std::vector<int>& sortedTiles) const;

    std::string mName;
    ShadowAtlasParams mParams;
    ShadowAtlasLayout mLayout;
    SceneProgram mProgram;
    gl::RenderTarget mTarget;         // depth only: DEPTH32F 2D array, mLayout.layers layers
    std::vector<glm::mat4> mMatrices; // clipFromWorld per tile index (CPU mirror of mMatrixBuffer)
    gl::Buffer mMatrixBuffer;
    gl::Buffer mDrawTiles; // tile index per instance of the last draw
    gl::Sampler mSampler;
};

// An atlas of r32f paraboloid distance maps (SMCIR's VPL maps, the imperfect shadow maps): one
// mapSize^2 tile per slot with the shadow atlas's addressing (one view per slot, chooseLayout's
// limits), `levels` mip levels, every texel of every level cleared to shared::kVPLNoOccluder (a map
// never written shadows nothing). `layout` receives the layout. Throws Error naming `name` when the
// layout exceeds the GL limits or the driver cannot allocate it. With format GL_R32UI (per-texel
// words in the same layout: the imperfect shadow maps' normals) every texel is 0xFFFFFFFF.
gl::Texture makeParaboloidMapAtlas(const std::string& name, int mapSize, int slots, int levels,
                                   ShadowAtlasLayout& layout, GLenum format = GL_R32F);

} // namespace vplgi
