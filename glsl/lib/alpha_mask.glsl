// The alpha mask of every pass that rasterizes the scene (glsl/shared/alpha_mask.h has the rule).
// GpuScene::draw uses a pass's program variant compiled with VPLGI_ALPHA_MASK for masked materials
// only and sets uAlphaMask there, so opaque draws keep a fragment shader without discard (and early
// depth tests). Call discardMasked last in main(): a discard before implicit derivatives (texture(),
// dFdx) would leave them undefined for the quad.
#include "../shared/alpha_mask.h"
#include "material_uv.glsl"

#ifdef VPLGI_ALPHA_MASK
uniform vec2 uAlphaMask; // x alphaCutoff, y the base colour factor's alpha
#endif

// uv0, uv1: TEXCOORD_0 and _1; vertexAlpha: COLOR_0's alpha.
void discardMasked(sampler2D baseColorTexture, vec2 uv0, vec2 uv1, float vertexAlpha)
{
#ifdef VPLGI_ALPHA_MASK
    float alpha = uAlphaMask.y * vertexAlpha * textureLod(baseColorTexture, materialUV(kUnitBaseColor, uv0, uv1), 0.0).a;
    if (!alphaMaskKeeps(alpha, uAlphaMask.x)) discard;
#endif
}
