#version 450 core
// Imperfect shadow maps (gl/passes/imperfect_shadow_maps.h): splats each light's run of scene
// points into its paraboloid map as one-texel points, nearest distance wins. Invocation (j, light):
// points k = j * ISM_POINTS_PER_INVOCATION ... of the light's run, point (start + k) mod P of the point
// set, start = light * uPointsPerMap mod P (several points per invocation share the light's frame:
// 25% faster on llvmpipe than one each). The distance is
// positive, so its float bits order like the floats and imageAtomicMin on them is a depth test whose
// result does not depend on the order the invocations run in.
#include "../shared/bindings.h"
#include "../shared/ism.h"

#ifndef ISM_POINTS_PER_INVOCATION
#define ISM_POINTS_PER_INVOCATION 8
#endif
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(binding = kImageISMMaps, r32ui) uniform uimage2DArray uMaps;

layout(std430, binding = kBindingISMPoints) readonly buffer Points {
    vec4 points[]; // xyz world position [m], w unused
};

layout(std430, binding = kBindingISMLights) readonly buffer Lights {
    vec4 lightRecords[]; // per light uStride vec4s: (position, -), (unit normal, -), ...; w of vec4 uValidVec4: valid
};

uniform int uCount;
uniform int uStride;
uniform int uValidVec4; // the record's vec4 whose w is 0 for an empty record
uniform int uPointsPerMap;
uniform int uPointCount;
uniform int uMapSize;
uniform int uTilesPerRow;

void main()
{
    int first = int(gl_GlobalInvocationID.x) * ISM_POINTS_PER_INVOCATION;
    int light = int(gl_GlobalInvocationID.y);
    if (first >= uPointsPerMap || light >= uCount) return;
    if (lightRecords[light * uStride + uValidVec4].w == 0.0) return;
    vec4 positionValid = lightRecords[light * uStride];
    mat3 frame = lightViewBasis(lightRecords[light * uStride + 1].xyz);
    // The C++ side keeps lights * pointsPerMap below 2^32.
    uint start = (uint(light) * uint(uPointsPerMap)) % uint(uPointCount);
    int last = min(first + ISM_POINTS_PER_INVOCATION, uPointsPerMap);
    for (int k = first; k < last; ++k) {
        vec3 point = points[(start + uint(k)) % uint(uPointCount)].xyz;
        ivec3 texel = ismSplatTexel(light, positionValid.xyz, frame, point, uMapSize, uTilesPerRow);
        if (texel.x >= 0) imageAtomicMin(uMaps, texel, floatBitsToUint(length(point - positionValid.xyz)));
    }
}
