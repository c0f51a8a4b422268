#version 450 core
// Evaluates the shared light-view maths on the GPU for inputs given by the test
// (tests/gl/test_light_view_probe.cpp compares with the same functions in C++).
layout(local_size_x = 64) in;
#include "shared/light_view.h"

struct Case {
    vec4 positionNear; // xyz light / VPL position, w = zNear
    vec4 normalFar;    // xyz unit normal, w = zFar
    vec4 direction;    // xyz unit direction with direction.n >= 0, w = distance along it
    vec4 uvTexel;      // xy map coordinates, z texel index (row-major), w = resolution
};
layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform int uCount;

const int kResultsPerCase = 8;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount) return;
    Case c = cases[i];
    vec3 p = c.positionNear.xyz;
    vec3 n = c.normalFar.xyz;
    vec3 w = c.direction.xyz;
    float zNear = c.positionNear.w;
    float zFar = c.normalFar.w;
    vec3 q = p + c.direction.w * w;
    int base = kResultsPerCase * i;

    int cubeFace = lightViewCubeFace(w);
    mat3 cube = lightViewHemisphereBasis(n);
    vec3 dc = transpose(cube) * w;
    int hemisphereFace = lightViewHemisphereFace(dc);
    results[base + 0] = vec4(float(cubeFace), float(hemisphereFace), lightViewHemisphereFaceUV(dc, hemisphereFace));
    results[base + 1] = lightViewCubeFaceClipFromWorld(p, cubeFace, zNear, zFar) * vec4(q, 1.0);
    results[base + 2] = lightViewHemisphereFaceClipFromWorld(p, cube, hemisphereFace, zNear, zFar) * vec4(q, 1.0);
    mat3 frame = lightViewBasis(n);
    vec3 local = transpose(frame) * (q - p);
    int resolution = int(c.uvTexel.w);
    int texel = int(c.uvTexel.z);
    results[base + 3] = vec4(paraboloidMapFromPoint(local, zNear, zFar),
                             paraboloidTexelSolidAngle(ivec2(texel % resolution, texel / resolution), resolution));
    results[base + 4] = vec4(paraboloidDirectionFromMap(c.uvTexel.xy), paraboloidSolidAngleDensity(c.uvTexel.xy));
    results[base + 5] = lightViewDirectionalFit(-w, p - vec3(zFar), p + vec3(zNear, zFar, 2.0 * zNear)) * vec4(q, 1.0);
    results[base + 6] = vec4(cube * vec3(1.0, 2.0, 3.0), 0.0);
    results[base + 7] = vec4(frame * vec3(1.0, 2.0, 3.0), 0.0);
}
