#include "vpl_shadow_maps.h"

#include <algorithm>
#include <string>

#include "../api/debug.h"
#include "core/util/error.h"
#include "glsl/shared/bindings.h"
#include "glsl/shared/light_view.h"
#include "glsl/shared/vpl.h"

namespace vplgi {

namespace {

ShadowAtlasParams faceAtlasParams(const VPLShadowMapParams& params)
{
    ShadowAtlasParams atlas;
    atlas.tileSize = params.faceSize > 0 ? params.faceSize : params.mapSize;
    atlas.slots = params.batchSize;
    atlas.viewsPerSlot = 3;
    return atlas;
}

} // namespace

VPLShadowMaps::VPLShadowMaps(const gl::ShaderLoader& shaders, const VPLShadowMapParams& params) : mParams(params)
{
    require(params.mapSize >= 4 && params.mapSize <= 4096, "VPL shadow maps: map size " +
                                                               std::to_string(params.mapSize) + " outside [4, 4096]");
    require(params.slots >= 1 && params.batchSize >= 1, "VPL shadow maps: slots and batch size must be >= 1");
    require(params.zNear > 0.0f && params.zFar > params.zNear, "VPL shadow maps: need 0 < zNear < zFar");
    mParams.batchSize = std::min(params.batchSize, params.slots);

    mMaps = makeParaboloidMapAtlas("VPL paraboloid maps", params.mapSize, params.slots, 1, mLayout);

    gl::SamplerDesc samplerDesc;
    samplerDesc.minFilter = GL_NEAREST;
    samplerDesc.magFilter = GL_NEAREST;
    mSampler = gl::Sampler("VPL paraboloid maps sampler", samplerDesc);

    mFaces = std::make_unique<ShadowAtlas>(shaders, "VPL hemisphere faces", faceAtlasParams(mParams));
    mResample = ComputePass(shaders, "VPL paraboloid resample", "passes/paraboloid_resample.comp");
    mBatch = gl::Buffer("VPL shadow map batch", static_cast<GLsizeiptr>(mParams.batchSize * sizeof(shared::VPLBatchItem)));
}

void VPLShadowMaps::reloadShaders(const gl::ShaderLoader& shaders)
{
    mFaces->reloadShaders(shaders);
    mResample.reloadShaders(shaders);
}

void VPLShadowMaps::update(const GpuScene& scene, const VPLSet& vpls, const std::vector<std::uint32_t>& slots,
                           const Progress& progress)
{
    mFacesRendered = 0;
    std::vector<std::uint32_t> todo;
    todo.reserve(slots.size());
    for (std::uint32_t slot : slots) {
        require(slot < static_cast<std::uint32_t>(mParams.slots) && slot < vpls.slots.size(),
                "VPL shadow maps: slot " + std::to_string(slot) + " out of range");
        if (vpls.slots[slot].valid) todo.push_back(slot);
    }
    if (todo.empty()) return;
    gl::DebugGroup group("VPL shadow maps");
    const int total = static_cast<int>(todo.size());
    for (int begin = 0; begin < total; begin += mParams.batchSize) {
        const int count = std::min(mParams.batchSize, total - begin);
        std::vector<std::uint32_t> batchSlots(static_cast<std::size_t>(count));
        std::vector<glm::mat4> matrices;
        std::vector<shared::VPLBatchItem> items(static_cast<std::size_t>(count));
        matrices.reserve(static_cast<std::size_t>(count) * 3);
        for (int i = 0; i < count; ++i) {
            const VPL& vpl = vpls.slots[todo[static_cast<std::size_t>(begin + i)]];
            batchSlots[static_cast<std::size_t>(i)] = static_cast<std::uint32_t>(i);
            // Section 4: the cube rotated so that three faces cover the hemisphere, eye at the VPL.
            const glm::mat3 cube = shared::lightViewHemisphereBasis(vpl.normal);
            for (int face = 0; face < 3; ++face)
                matrices.push_back(shared::lightViewHemisphereFaceClipFromWorld(vpl.position, cube, face, mParams.zNear,
                                                                                mParams.zFar));
            shared::VPLBatchItem& item = items[static_cast<std::size_t>(i)];
            item.position = glm::vec4(vpl.position, 1.0f);
            item.normal = glm::vec4(vpl.normal, 0.0f);
            item.slot = glm::ivec4(static_cast<int>(todo[static_cast<std::size_t>(begin + i)]), i, 0, 0);
        }
        mFaces->renderDirty(scene, batchSlots, matrices);
        mFacesRendered += 3 * count;
        mBatch.upload(0, static_cast<GLsizeiptr>(items.size() * sizeof(shared::VPLBatchItem)), items.data());
        mFaces->bindForReading();
        bindStorageBuffer(shared::kBindingVPLBatch, mBatch);
        bindImage(shared::kImageVPLShadowMaps, mMaps, GL_WRITE_ONLY);
        const gl::Program& program = mResample.program();
        program.set("uMapSize", mParams.mapSize);
        program.set("uMapTilesPerRow", mLayout.tilesPerRow);
        program.set("uFaceSize", mFaces->layout().tileSize);
        program.set("uFaceTilesPerRow", mFaces->layout().tilesPerRow);
        program.set("uZNear", mParams.zNear);
        program.set("uZFar", mParams.zFar);
        // The next batch re-renders the face atlas, and the shading pass fetches the maps.
        mResample.dispatch(glm::ivec3(mParams.mapSize, mParams.mapSize, count),
                           NextRead::TextureFetch | NextRead::Framebuffer | NextRead::Image);
        if (progress) progress(begin + count, total);
    }
}

void VPLShadowMaps::bindForReading() const
{
    glBindTextureUnit(shared::kUnitVPLShadowMaps, mMaps.id());
    glBindSampler(shared::kUnitVPLShadowMaps, mSampler.id());
}

} // namespace vplgi
