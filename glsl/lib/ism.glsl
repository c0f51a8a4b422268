// Imperfect-shadow-map visibility for shading passes (gl/passes/imperfect_shadow_maps.h): include
// after ../shared/bindings.h; ImperfectShadowMaps::bindForReading(program) binds the maps and sets
// the uniforms below.
#include "../shared/ism.h"
#include "../shared/plane_visibility.h"

layout(binding = kUnitISM) uniform sampler2DArray uISMMaps;
layout(binding = kUnitISMNormals) uniform usampler2DArray uISMNormals; // uISMPlanes only

uniform int uISMMapSize;
uniform int uISMTilesPerRow;
uniform float uISMNormalOffset; // shaded point lifted along its normal by this many map texels at its distance
uniform float uISMDepthBias;    // lit while |q - y| <= stored distance * (1 + uISMDepthBias)
uniform int uISMPlanes;         // 1: the plane rule on the four texels around the direction (glsl/shared/ism.h, planes)
uniform float uISMLift;         // the plane rule's absolute margin [m]
uniform float uISMEdgeMargin;   // the plane rule's margin at a surface's edge, relative to the distance
uniform float uISMOverhang;     // the plane rule's cut: a hit up to this far behind a plane counts as in front [m] (the splats' radius)

// Texel `texel` of a light's map (its tile at `tile`, shadowAtlasTileFromIndex) as the plane rule
// reads it: its central direction (world), distance (kPlaneMapMiss when empty) and normal facing the
// light (a texel no normal reached, filled by pull-push, counts as a plane facing the light).
void ismPlaneTexel(ivec3 tile, mat3 lightFrame, ivec2 texel, out vec3 direction, out float t, out vec3 normal)
{
    ivec3 at = ivec3(tile.xy * uISMMapSize + texel, tile.z);
    direction = lightFrame * vplParaboloidTexelDirection(texel, uISMMapSize);
    float stored = texelFetch(uISMMaps, at, 0).r;
    t = ismValid(stored) ? stored : kPlaneMapMiss;
    uint word = texelFetch(uISMNormals, at, 0).r;
    normal = word == kISMNoNormal ? -direction : octDecode(unpackSnorm2x16(word));
}

// 1 = light `light` (at lightPosition, unit normal lightNormal) sees x (shading normal nx, geometric
// normal ng), 0 = not, in between at the edge of a shadow with planes: SMCIR's paraboloid lookup
// (passes/vpl_shading.frag) on the light's imperfect shadow map, or with uISMPlanes the plane rule.
float ismVisibility(int light, vec3 lightPosition, vec3 lightNormal, vec3 x, vec3 nx, vec3 ng)
{
    if (uISMPlanes != 0) {
        mat3 frame = lightViewBasis(lightNormal);
        vec3 toX = x - lightPosition;
        vec2 f;
        ivec2 first = ismPlaneNeighbours(transpose(frame) * (toX / length(toX)), uISMMapSize, f);
        vec3 d0, d1, d2, d3, n0, n1, n2, n3;
        float t0, t1, t2, t3;
        ivec3 tile = shadowAtlasTileFromIndex(light, uISMTilesPerRow);
        ismPlaneTexel(tile, frame, first, d0, t0, n0);
        ismPlaneTexel(tile, frame, first + ivec2(1, 0), d1, t1, n1);
        ismPlaneTexel(tile, frame, first + ivec2(0, 1), d2, t2, n2);
        ismPlaneTexel(tile, frame, first + ivec2(1, 1), d3, t3, n3);
        return planeMapVisibility(lightPosition, x, ng, uISMLift, ismPlaneTexelAngle(uISMMapSize), uISMOverhang,
                                  uISMEdgeMargin, f,
                                  d0, t0, n0, d1, t1, n1, d2, t2, n2, d3, t3, n3);
    }
    vec3 q = ismLookupPoint(lightPosition, x, nx, uISMNormalOffset, uISMMapSize);
    ivec3 texel = ismLookupTexel(light, lightPosition, lightNormal, q, uISMMapSize, uISMTilesPerRow);
    float stored = texelFetch(uISMMaps, texel, 0).r;
    return ismVisibilityFromStored(length(q - lightPosition), stored, uISMDepthBias);
}
