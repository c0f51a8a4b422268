// The reflective shadow map (RSM) layout, named once for C++ and GLSL (gl/passes/rsm_pass.h has
// the prose). Every attachment is RGBA32F, a 2D array with one layer per light and a full mip chain.
#ifndef VPLGI_SHARED_RSM_H
#define VPLGI_SHARED_RSM_H
#include "compat.h"

VPLGI_SHARED_BEGIN

// Attachments (colour location = index = image-unit offset in the downsample kernel).
VPLGI_CONST int kRSMPosition = 0; // xyz world position [m], w = its squared norm |x|^2 [m^2] (VSGL 3.2)
VPLGI_CONST int kRSMNormal = 1;   // xyz normal (mips: weighted mean, not renormalised), w = coverage
VPLGI_CONST int kRSMFlux = 2;     // rgb reflected flux of the texel [W] (MATH.md 1.5), w = 0
VPLGI_CONST int kRSMDiffuse = 3;  // rgb diffuse reflectance (1 - metallic) baseColor, w = 0
VPLGI_CONST int kRSMSpecular = 4; // rgb specular reflectance F0, w = perceptual roughness
VPLGI_CONST int kRSMLobe = 5;     // xyz specular lobe as Toksvig vector (eta/(1+eta)) xi, w = 0
VPLGI_CONST int kRSMAttachmentCount = 6;

// Which light an RSM layer was rendered for.
VPLGI_CONST int kRSMLightSpot = 0;
VPLGI_CONST int kRSMLightDirectional = 1;
VPLGI_CONST int kRSMLightPoint = 2; // one of six cube faces (gl/passes/rsm_pass.h says why a cube)

// Work-group edge of rsm_downsample.comp.
VPLGI_CONST int kRSMDownsampleGroupSize = 8;

VPLGI_SHARED_END

#endif // VPLGI_SHARED_RSM_H
