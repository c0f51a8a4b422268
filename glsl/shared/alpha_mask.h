// Alpha masks (glTF 2.0 alphaMode MASK, section 3.9.4): one rule for the rasterizer and the rays.
// A point of a masked material is present where its alpha, the base colour factor's alpha times the
// base colour texture's alpha (level 0, bilinear, linear: sRGB decoding leaves alpha alone), is
// >= alphaCutoff; elsewhere it is absent: no fragment in any pass (glsl/lib/alpha_mask.glsl), no ray
// hit (core/trace/ray_scene.cpp), no surface sample (core/scene/surface_points.cpp).
// Level 0 (not the mips GL would pick) so that every pass and every ray cut the same outline: a
// mip-filtered alpha tested at a fixed cutoff thins foliage with distance and differs between a
// shadow map's texel footprint and the camera's. Not in glTF, which leaves filtering open.
#ifndef VPLGI_SHARED_ALPHA_MASK_H
#define VPLGI_SHARED_ALPHA_MASK_H
#include "compat.h"

VPLGI_SHARED_BEGIN

VPLGI_FUNC bool alphaMaskKeeps(float alpha, float cutoff)
{
    return alpha >= cutoff;
}

VPLGI_SHARED_END

#endif
