#version 450 core
// Evaluates glsl/shared/lightskin.h on the GPU for inputs given by the test
// (tests/gl/test_lightskin_math_gpu.cpp compares with the same functions compiled as C++).
layout(local_size_x = 64) in;
#include "shared/lightskin.h"

struct Case {
    vec4 valPositionArea;          // xyz VAL position, w its area
    vec4 valNormalExpectation;     // xyz VAL normal, w P_VAL
    vec4 valFluxExponent;          // rgb VAL flux, w Phong exponent k
    vec4 receiverPositionDepth;    // xyz receiver position, w view depth (eq. 1)
    vec4 receiverNormalFactor;     // xyz receiver normal, w texel factor (eq. 1)
    vec4 viewClamp;                // xyz view direction, w importance clamp distance
    vec4 diffuseCosAxis;           // rgb rho_d, w cos(alpha)
    vec4 glossyCosSurface;         // rgb rho_g, w cos(theta_s)
    vec4 interpolation;            // distance, max distance, exponent p, cos between normals
    vec4 occluderPositionArea;     // xyz occluder position, w its area
    vec4 occluderNormalRadius;     // xyz occluder normal, w proxy sphere radius
    vec4 roughnessOverlap;         // x GGX alpha, y draw count, z overlap sum, w weight sum
    uvec4 indices;                 // x Halton index, y cache index, z occluder index, w view size
};
layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform int uCount;

const int kResultsPerCase = 9;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount) return;
    Case c = cases[i];
    int base = kResultsPerCase * i;
    vec3 valPosition = c.valPositionArea.xyz;
    float valArea = c.valPositionArea.w;
    vec3 valNormal = c.valNormalExpectation.xyz;
    float expectation = c.valNormalExpectation.w;
    vec3 flux = c.valFluxExponent.xyz;
    float k = c.valFluxExponent.w;
    vec3 x = c.receiverPositionDepth.xyz;
    vec3 n = c.receiverNormalFactor.xyz;
    vec3 view = c.viewClamp.xyz;

    vec3 diffuse = valDiffuseRadiance(flux, valPosition, valNormal, valArea, x, n, c.diffuseCosAxis.xyz, expectation);
    vec3 glossy = valGlossyRadiance(flux, valPosition, valNormal, valArea, x, n, view, c.glossyCosSurface.xyz, k,
                                    expectation);
    float perspective = lightskinValArea(c.receiverPositionDepth.w, c.receiverNormalFactor.w, false);
    results[base + 0] = vec4(diffuse, perspective);
    results[base + 1] = vec4(glossy, lightskinValArea(c.receiverPositionDepth.w, c.receiverNormalFactor.w, true));

    vec3 toVal = valPosition - x;
    float distance2 = dot(toVal, toVal);
    vec3 w = toVal * inversesqrt(max(distance2, 1e-30));
    float cosCache = dot(n, w);
    vec3 brdf = c.diffuseCosAxis.xyz * kInvPi;
    vec3 proxyFlux = proxyFluxFromRadiance(diffuse, distance2, brdf, cosCache);
    results[base + 2] = vec4(proxyFlux, lightskinValAreaTilted(perspective, c.diffuseCosAxis.w, c.glossyCosSurface.w));
    float formFactor = diskFormFactor(valArea, -dot(valNormal, w), cosCache, distance2);
    results[base + 3] = vec4(pointLightRadiance(proxyFlux, distance2, brdf, cosCache), formFactor);

    float cosMirror = dot(view, mirrorDirection(w, n));
    vec4 i4 = c.interpolation;
    results[base + 4] = vec4(proxyWeightDiffuse(formFactor, kProxyWeightEpsilon),
                             proxyWeightGlossy(formFactor, cosMirror, k, kProxyWeightEpsilon),
                             interpolationWeight(i4.x, i4.y, i4.z, i4.w),
                             valImportance(flux.y, valPosition, valNormal, x, n, c.viewClamp.w));

    uint index = c.indices.x;
    int size = int(c.indices.w);
    ivec2 pixel = haltonViewPixel(index, size, size / 2 + 1);
    results[base + 5] = vec4(halton(index, 2u), halton(index, 3u), float(pixel.x), float(pixel.y));

    mat3 frame = occlusionFrame(n);
    vec3 sphere = projectSphereToUnitDisk(valPosition - x, c.occluderNormalRadius.w, frame);
    float radius = proxySphereRadius(c.roughnessOverlap.w, toVal, toVal * toVal + c.glossyCosSurface.xyz);
    results[base + 6] = vec4(sphere, radius);
    vec3 disk = projectDiskToUnitDisk(c.occluderPositionArea.xyz - x, c.occluderNormalRadius.xyz,
                                      c.occluderPositionArea.w, frame);
    results[base + 7] = vec4(disk, squareOverlap(sphere, disk));

    bool candidate = isOccluderCandidate(int(c.indices.y), x, n, int(c.indices.z), c.occluderPositionArea.xyz, distance2);
    results[base + 8] = vec4(candidate ? 1.0 : 0.0, occlusionFromOverlap(c.roughnessOverlap.z, sphere.z),
                             phongExponentFromRoughness(c.roughnessOverlap.x),
                             valSelectionExpectation(c.roughnessOverlap.y, expectation));
}
