// The reflective shadow map (RSM) layout, named once for C++ and GLSL (gl/passes/rsm_pass.h has
// the prose). Every attachment is RGBA32F, a 2D array with one layer per light and a full mip chain.
#ifndef VPLGI_SHARED_RSM_H
#define VPLGI_SHARED_RSM_H
#include "compat.h"

VPLGI_SHARED_BEGIN

// Attachments (colour location = index = image-unit offset in the downsample kernel).
VPLGI_CONST int kRSMPosition = 0; // xyz world position [m], w = its squared norm |x|^2 [m^2] (VSGL 3.2)
VPLGI_CONST int kRSMNormal = 1;   // xyz normal (mips: weighted mean, not renormalised), w = coverage
VPLGI_CONST int kRSMFlux = 2;     // rgb incident flux of the texel [W] (MATH.md 1.5), w octahedral x of n_g (level 0)
VPLGI_CONST int kRSMDiffuse = 3;  // rgb diffuse reflectance (1 - metallic) baseColor, w octahedral y of n_g (level 0)
VPLGI_CONST int kRSMSpecular = 4; // rgb specular reflectance F0, w = perceptual roughness
VPLGI_CONST int kRSMLobe = 5;     // xyz specular lobe as Toksvig vector (eta/(1+eta)) xi, w its integral factor
VPLGI_CONST int kRSMAttachmentCount = 6;

// Which light an RSM layer was rendered for.
VPLGI_CONST int kRSMLightSpot = 0;
VPLGI_CONST int kRSMLightDirectional = 1;
VPLGI_CONST int kRSMLightPoint = 2; // one of six cube faces (gl/passes/rsm_pass.h says why a cube)
VPLGI_CONST int kRSMLightArea = 3;  // a cube face of a group of emissive samples (cosine emission)

// Work-group edge of rsm_downsample.comp.
VPLGI_CONST int kRSMDownsampleGroupSize = 8;

// The light of RSM layer i (RSMPass::layerLights(), an SSBO at kBindingRSMLayers): where the light
// a texel reflects comes from. A texel's lobe axis cannot tell (a rough surface's lobe has zero
// sharpness, and Toksig's encoding stores it as the zero vector).
struct RSMLayerLight {
    vec4 positionKind; // spot, point, area: xyz position [m]; directional: xyz the direction light travels;
                       // w the kRSMLight* kind
};

// Unit direction from x towards the light of `layer`.
VPLGI_FUNC vec3 rsmDirectionToLight(RSMLayerLight layer, vec3 x)
{
    if (int(layer.positionKind.w) == kRSMLightDirectional) return -normalize(vec3(layer.positionKind));
    return normalize(vec3(layer.positionKind) - x);
}

// Two RSM samples on different surfaces (vsgl.leafEdges, ours; passes/vsgl_generate.comp): unit
// normals na, nb more than 30 degrees apart (a corner: floor and wall), or b off a's plane by more
// than half their distance, d = x_b - x_a (a step: a wall's top and the floor below it).
VPLGI_FUNC bool rsmSurfacesDiffer(vec3 na, vec3 nb, vec3 d)
{
    return dot(na, nb) < 0.8660254f || abs(dot(d, na)) > 0.5f * length(d);
}

VPLGI_SHARED_END

#ifdef __cplusplus
static_assert(sizeof(vplgi::shared::RSMLayerLight) == 16, "RSMLayerLight must match std430");
#endif

#endif // VPLGI_SHARED_RSM_H
