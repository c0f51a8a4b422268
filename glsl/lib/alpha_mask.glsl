// The alpha mask of every pass that rasterizes the scene (glsl/shared/alpha_mask.h has the rule).
// GpuScene::draw uses a pass's program variant compiled with VPLGI_ALPHA_MASK for masked materials
// only and sets uAlphaMask there, so opaque draws keep a fragment shader without discard (and early
// depth tests). Call discardMasked last in main(): a discard before implicit derivatives (texture(),
// dFdx) would leave them undefined for the quad.
#include "../shared/alpha_mask.h"

#ifdef VPLGI_ALPHA_MASK
uniform vec2 uAlphaMask; // x alphaCutoff, y the base colour factor's alpha
#endif

void discardMasked(sampler2D baseColorTexture, vec2 uv)
{
#ifdef VPLGI_ALPHA_MASK
    if (!alphaMaskKeeps(uAlphaMask.y * textureLod(baseColorTexture, uv, 0.0).a, uAlphaMask.x)) discard;
#endif
}
