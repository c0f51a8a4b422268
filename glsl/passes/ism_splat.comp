#version 450 core
// Imperfect shadow maps (gl/passes/imperfect_shadow_maps.h): splats each light's run of scene
// points into its paraboloid map as one-texel points, nearest distance wins. Invocation (k, light):
// point (start + k) mod P of the point set, start = light * uPointsPerMap mod P. The distance is
// positive, so its float bits order like the floats and imageAtomicMin on them is a depth test whose
// result does not depend on the order the invocations run in.
#include "../shared/bindings.h"
#include "../shared/ism.h"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(binding = kImageISMMaps, r32ui) uniform uimage2DArray uMaps;

layout(std430, binding = kBindingISMPoints) readonly buffer Points {
    vec4 points[]; // xyz world position [m], w unused
};

layout(std430, binding = kBindingISMLights) readonly buffer Lights {
    vec4 lightRecords[]; // per light uStride vec4s: (position, valid), (unit normal, -), ...
};

uniform int uCount;
uniform int uStride;
uniform int uPointsPerMap;
uniform int uPointCount;
uniform int uMapSize;
uniform int uTilesPerRow;

void main()
{
    int k = int(gl_GlobalInvocationID.x);
    int light = int(gl_GlobalInvocationID.y);
    if (k >= uPointsPerMap || light >= uCount) return;
    vec4 positionValid = lightRecords[light * uStride];
    if (positionValid.w == 0.0) return;
    vec3 normal = lightRecords[light * uStride + 1].xyz;
    // The C++ side keeps lights * pointsPerMap below 2^32.
    uint start = (uint(light) * uint(uPointsPerMap)) % uint(uPointCount);
    vec3 point = points[(start + uint(k)) % uint(uPointCount)].xyz;
    ivec3 texel = ismSplatTexel(light, positionValid.xyz, lightViewBasis(normal), point, uMapSize, uTilesPerRow);
    if (texel.x < 0) return;
    imageAtomicMin(uMaps, texel, floatBitsToUint(length(point - positionValid.xyz)));
}
