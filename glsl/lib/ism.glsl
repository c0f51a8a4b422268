// Imperfect-shadow-map visibility for shading passes (gl/passes/imperfect_shadow_maps.h): include
// after ../shared/bindings.h; ImperfectShadowMaps::bindForReading(program) binds the maps and sets
// the uniforms below.
#include "../shared/ism.h"

layout(binding = kUnitISM) uniform sampler2DArray uISMMaps;

uniform int uISMMapSize;
uniform int uISMTilesPerRow;
uniform float uISMNormalOffset; // shaded point lifted along its normal by this many map texels at its distance
uniform float uISMDepthBias;    // lit while |q - y| <= stored distance * (1 + uISMDepthBias)

// 1 = light `light` (at lightPosition, unit normal lightNormal) sees x (unit normal nx), 0 = not:
// SMCIR's paraboloid lookup (passes/vpl_shading.frag) on the light's imperfect shadow map.
float ismVisibility(int light, vec3 lightPosition, vec3 lightNormal, vec3 x, vec3 nx)
{
    vec3 q = ismLookupPoint(lightPosition, x, nx, uISMNormalOffset, uISMMapSize);
    ivec3 texel = ismLookupTexel(light, lightPosition, lightNormal, q, uISMMapSize, uISMTilesPerRow);
    float stored = texelFetch(uISMMaps, texel, 0).r;
    return ismVisibilityFromStored(length(q - lightPosition), stored, uISMDepthBias);
}
