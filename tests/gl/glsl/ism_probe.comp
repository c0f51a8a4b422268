#version 450 core
// Looks up every (receiver, light) pair in the imperfect shadow maps with the shading passes'
// ismVisibility (glsl/lib/ism.glsl), for tests/gl/test_imperfect_shadow_maps.cpp.
layout(local_size_x = 64) in;
#include "shared/bindings.h"
#include "lib/ism.glsl"

struct Receiver {
    vec4 position; // xyz [m]
    vec4 normal;   // xyz unit
};
layout(std430, binding = 0) readonly buffer Receivers { Receiver receivers[]; };
layout(std430, binding = 1) readonly buffer Lights { vec4 lightRecords[]; }; // 2 vec4s per light
layout(std430, binding = 2) writeonly buffer Results { float visibility[]; }; // [receiver * uLightCount + light]
uniform int uReceiverCount;
uniform int uLightCount;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uReceiverCount * uLightCount) return;
    int receiver = i / uLightCount;
    int light = i % uLightCount;
    vec4 positionValid = lightRecords[2 * light];
    vec3 normal = lightRecords[2 * light + 1].xyz;
    visibility[i] = ismVisibility(light, positionValid.xyz, normal, receivers[receiver].position.xyz,
                                  receivers[receiver].normal.xyz, receivers[receiver].normal.xyz);
}
