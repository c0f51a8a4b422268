// VPL shadow maps (SMCIR section 4): one paraboloid map per VPL slot, made by rendering three
// faces of a hemisphere cube around the VPL and resampling them, re-made only for the slots that
// changed.
//
// Intro
// -----
// A paraboloid map (Brabec et al. 2002) stores a VPL's whole hemisphere in one square texture,
// but rasterizing straight into it bends straight edges, which only fine tessellation hides. The
// paper instead renders a cube map with ordinary perspective and resamples it; a cube translated
// and rotated so that three of its faces cover the hemisphere needs three faces, not six, each a
// generalized perspective projection with the VPL as its centre of projection (glsl/shared/
// light_view.h, MATH.md 6.3). Maps are lazily updated: only VPLs that moved get new maps (the
// paper follows Laine et al. 2007), so static geometry is assumed between full rebuilds.
//
// Overview
// --------
//  VPLShadowMaps(shaders, params)   the paraboloid array (a map per slot, cleared to "no occluder")
//                                   and a face atlas holding the faces of one batch of VPLs
//  update(scene, vpls, slots)       per batch of at most params.batchSize slots: render the 3 faces
//                                   of each (ShadowAtlas::renderDirty: one instanced draw per mesh),
//                                   then one compute dispatch resamples them into the slots' maps
//  bindForReading()                 the paraboloid array at kUnitVPLShadowMaps
//
// Details
// -------
//  Storage: the distance from the VPL to the nearest surface [m] along each texel's direction,
//  r32f, in tiles of a 2D array texture addressed like the shadow atlas (glsl/shared/
//  shadow_atlas.h, one view per slot): 2048 maps of 128^2 are 128 MiB. Distances, not depths,
//  so the shading pass compares |x - y| directly and the faces' projection does not leak into it.
//  Texels whose centre lies outside the paraboloid's disk hold the direction on the rim nearest to
//  them (glsl/shared/vpl.h), so a lookup at the horizon reads a real direction.
//  Faces: a ShadowAtlas of batchSize x 3 tiles of faceSize^2 (DEPTH32F), reused batch after batch;
//  faceSize defaults to the map size. Each paraboloid texel reads the face its direction leaves
//  through (the largest cube-frame component) at the nearest face texel, and converts that depth
//  to a distance (vplFaceDistance, MATH.md 6.4).
//  zNear / zFar: the faces clip axial depth; zFar covers the scene's diagonal, zNear is a small
//  fraction of it (geometry closer than that to a VPL casts no shadow; the geometry term is clamped
//  there anyway).
//
// References
// ----------
//  SMCIR (papers/000) section 4; S. Brabec, T. Annen, H.-P. Seidel: Shadow Mapping for Hemispherical
//  and Omnidirectional Light Sources, 2002; R. Kooima: Generalized Perspective Projection, 2008;
//  S. Laine et al.: Incremental Instant Radiosity for Real-Time Indirect Illumination, EGSR 2007.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "../api/objects.h"
#include "../api/shader_loader.h"
#include "../gpu_scene.h"
#include "compute_pass.h"
#include "core/vpl/vpl.h"
#include "shadow_atlas.h"

namespace vplgi {

struct VPLShadowMapParams {
    int mapSize = 128;      // paraboloid map resolution [texels] (SMCIR section 4: 128 x 128)
    int faceSize = 0;       // hemisphere-cube face resolution [texels]; 0 = mapSize
    int slots = 2048;       // VPL slots (the budget I)
    int batchSize = 256;    // VPLs whose faces share the face atlas at a time
    float zNear = 1e-3f;    // [m] (the technique derives both from the scene's size)
    float zFar = 100.0f;    // [m]
};

class VPLShadowMaps {
public:
    using Progress = std::function<void(int done, int total)>;

    // Throws Error naming the numbers when the maps do not fit the GL limits.
    VPLShadowMaps(const gl::ShaderLoader& shaders, const VPLShadowMapParams& params);
    void reloadShaders(const gl::ShaderLoader& shaders);

    // Renders and resamples the maps of `slots` (distinct, < params.slots; invalid VPLs are skipped)
    // from the VPLs in `vpls.slots`. Other maps keep their texels bit for bit. Reports progress per
    // batch when given. (Faces and resampling alternate batch by batch: time the whole call.)
    void update(const GpuScene& scene, const VPLSet& vpls, const std::vector<std::uint32_t>& slots,
                const Progress& progress = {});
    // The paraboloid array at kUnitVPLShadowMaps (nearest sampler).
    void bindForReading() const;

    const VPLShadowMapParams& params() const { return mParams; }
    const ShadowAtlasLayout& layout() const { return mLayout; } // of the paraboloid array
    const gl::Texture& maps() const { return mMaps; }
    const ShadowAtlas& faces() const { return *mFaces; }
    // Faces rendered by the last update() (3 per VPL updated).
    int facesRendered() const { return mFacesRendered; }

private:
    VPLShadowMapParams mParams;
    ShadowAtlasLayout mLayout;
    gl::Texture mMaps;
    gl::Sampler mSampler;
    std::unique_ptr<ShadowAtlas> mFaces;
    ComputePass mResample;
    gl::Buffer mBatch;
    int mFacesRendered = 0;
};

} // namespace vplgi
