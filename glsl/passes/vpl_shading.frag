#version 450 core
// Deferred VPL shading with interleaved sampling (SMCIR section 4, eq. 5; gl/techniques/
// vpl_technique.h): every pixel of a uTile x uTile tile gathers its own 1/uTile^2 of the VPLs
// (glsl/shared/vpl.h) with the shared BRDF, the clamped geometry term and paraboloid shadow-map
// visibility; uTile = 1 gathers every VPL at every pixel (the paper's "All VPLs - shadow maps").
#include "../lib/frame.glsl"
#include "../shared/brdf.h"
#include "../shared/shadow_atlas.h"
#include "../shared/vpl.h"
#include "../shared/ism.h"
#include "../shared/normals.h"

layout(binding = kUnitGBufferPosition) uniform sampler2D uPosition;
layout(binding = kUnitGBufferNormal) uniform sampler2D uNormal;
layout(binding = kUnitGBufferBaseColor) uniform sampler2D uBaseColor;
layout(binding = kUnitGBufferEmission) uniform sampler2D uEmission;
layout(binding = kUnitGBufferSurfaceNormals) uniform sampler2D uSurfaceNormals;
layout(binding = kUnitVPLShadowMaps) uniform sampler2DArray uMaps;

layout(std430, binding = kBindingVPLs) readonly buffer VPLs {
    GpuVPL vpls[];
};

uniform int uTile;           // interleaving tile size (4: the paper; 1: every VPL at every pixel)
uniform int uValidCount;     // n: the valid VPLs
uniform float uClampGeometry; // G_max [1/m^2]; 0 = none
uniform int uVisibility;     // 0 = none, 1 = paraboloid shadow maps, 2 = a 1x1 texture fetch (cost probe)
uniform int uMapSize;
uniform int uMapTilesPerRow;
uniform float uNormalOffset; // shaded point lifted along its normal by this many map texels at its distance
uniform float uDepthBias;    // lit while |x - y| <= stored distance * (1 + uDepthBias)

layout(location = 0) out vec4 outRadiance;

float visibility(int slot, vec3 vplPosition, vec3 vplNormal, vec3 p, vec3 n)
{
    if (uVisibility == 0) return 1.0;
    if (uVisibility == 2) return texelFetch(uMaps, ivec3(0), 0).r > -1.0 ? 1.0 : 0.0;
    // The lookup the imperfect shadow maps share (glsl/shared/ism.h): lift p along n by
    // uNormalOffset map texels at its distance, read the light's paraboloid texel, relative bias.
    vec3 q = ismLookupPoint(vplPosition, p, n, uNormalOffset, uMapSize);
    float stored = texelFetch(uMaps, ismLookupTexel(slot, vplPosition, vplNormal, q, uMapSize, uMapTilesPerRow), 0).r;
    return ismVisibilityFromStored(length(q - vplPosition), stored, uDepthBias);
}

void main()
{
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 position = texelFetch(uPosition, pixel, 0);
    if (position.w == 0.0 || uValidCount == 0) {
        outRadiance = vec4(0.0);
        return;
    }
    vec4 normalRoughness = texelFetch(uNormal, pixel, 0);
    vec4 baseMetallic = texelFetch(uBaseColor, pixel, 0);
    vec4 emissionSpecular = texelFetch(uEmission, pixel, 0);
    vec3 p = position.xyz;
    vec3 n = normalize(normalRoughness.xyz);
    // n_g, the G-buffer's geometric normal: a light below the triangle's plane (n_g . w <= 0) adds
    // nothing, as the path tracer drops a direction below the geometric surface (issue "Every light
    // type in the RSM techniques", part 2; the shading normal alone let a normal map tilt light in).
    vec3 ng = octDecode(texelFetch(uSurfaceNormals, pixel, 0).xy);
    vec3 wo = normalize(frame.cameraPosition.xyz - p);
    SurfaceMaterial m = SurfaceMaterial(baseMetallic.rgb, baseMetallic.a, normalRoughness.w, emissionSpecular.a);

    int classes = uTile * uTile;
    vec3 sum = vec3(0.0);
    for (int i = vplInterleaveClass(pixel, uTile); i < vpls.length(); i += classes) { // eq. (5), subset S_c
        GpuVPL vpl = vpls[i];
        if (vpl.positionValid.w == 0.0) continue;
        vec3 toVPL = vpl.positionValid.xyz - p;
        if (dot(ng, toVPL) <= 0.0) continue;
        float g = vplGeometryTerm(n, vpl.normal.xyz, toVPL, uClampGeometry);
        if (g <= 0.0) continue;
        float v = visibility(i, vpl.positionValid.xyz, vpl.normal.xyz, p, n);
        if (v == 0.0) continue;
        sum += evaluateBRDF(m, n, wo, normalize(toVPL)) * vpl.intensity.rgb * (g * v);
    }
    outRadiance = vec4(sum * vplEstimatorScale(uValidCount, uTile), 1.0);
}
