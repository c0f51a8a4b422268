#version 450 core
// Evaluates glsl/shared/sg.h on the GPU for inputs given by the test (tests/gl/test_sg_gpu.cpp
// compares with the same functions compiled as C++).
layout(local_size_x = 64) in;
#include "shared/sg.h"

struct Case {
    vec4 positionRoughness; // shading point position, w perceptual roughness
    vec4 normal;            // xyz shading normal
    vec4 view;              // xyz unit view
    vec4 diffuse;           // rgb rho_d
    vec4 f0;                // rgb F0
    VSGLight light;
    vec4 toLightClamp;      // xyz unit direction towards the primary light at the VSGL, w clampGeometry
    vec4 parameters;        // x biasAlpha, y probability, z count, w smoothness
};
layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform int uCount;

const int kResultsPerCase = 7;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount) return;
    Case c = cases[i];
    VSGLShadingPoint s;
    s.position = c.positionRoughness.xyz;
    s.normal = c.normal.xyz;
    s.view = c.view.xyz;
    s.diffuse = c.diffuse.rgb;
    s.f0 = c.f0.rgb;
    s.roughness = c.positionRoughness.w;
    int base = kResultsPerCase * i;

    float cancelled = -1.0;
    vec3 sg = vsglRadiance(s, c.light, c.toLightClamp.xyz, 0.0, cancelled);
    results[base + 0] = vec4(sg, cancelled);
    vec3 reduced = vsglRadiance(s, c.light, c.toLightClamp.xyz, c.parameters.x, cancelled);
    results[base + 1] = vec4(reduced, cancelled);
    results[base + 2] = vec4(vplRadiance(s, c.light, c.toLightClamp.xyz, c.toLightClamp.w),
                             vsglMipLevel(c.parameters.z, c.parameters.y, c.parameters.w, 9));
    SpecularLobe lobe = ggxReflectionLobe(s.normal, s.view, s.roughness);
    results[base + 3] = vec4(lobe.axis, lobe.sharpness);
    vec3 encoded = toksvigEncode(lobe.axis, lobe.sharpness);
    vec3 axis;
    float sharpness;
    toksvigDecode(0.5 * encoded + vec3(0.1, 0.0, 0.0), axis, sharpness);
    results[base + 4] = vec4(encoded, lobe.integral);
    results[base + 5] = vec4(axis, sharpness);
    results[base + 6] = vec4(evaluateBRDFCoefficients(c.light.diffuse.rgb, c.light.specular.rgb, c.light.diffuse.w,
                                                      c.light.normalValid.xyz, -s.view, c.toLightClamp.xyz),
                             0.0);
}
