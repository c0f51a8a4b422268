#version 450 core
// Layered shadow rendering in one instanced draw per mesh: instance i renders into layer i of the
// shadow texture (cube-map array faces, light * 6 + face; or directional map layers), with the
// layer's clipFromWorld from an SSBO. gl_Layer from the vertex shader is about 2x faster than a
// geometry shader on llvmpipe (../shared/ENVIRONMENT.md).
#extension GL_ARB_shader_viewport_layer_array : require
#include "../lib/frame.glsl"

layout(location = 0) in vec3 aPosition;
layout(location = 2) in vec2 aTexcoord;
layout(location = 4) in vec2 aTexcoord1;
layout(location = 5) in vec4 aColor;

uniform mat4 uWorldFromObject;
uniform int uFirstLayer;

layout(std430, binding = kBindingShadowMatrices) readonly buffer ShadowMatrices {
    mat4 clipFromWorldPerLayer[];
};

layout(location = 0) out vec3 vWorldPosition;
layout(location = 1) flat out int vLayer;
layout(location = 2) out vec2 vTexcoord; // for alpha masks: both UV sets and COLOR_0's alpha
layout(location = 3) out vec2 vTexcoord1;
layout(location = 4) out float vAlpha;

void main()
{
    int layer = uFirstLayer + gl_InstanceID;
    vec4 world = uWorldFromObject * vec4(aPosition, 1.0);
    vWorldPosition = world.xyz;
    vLayer = layer;
    vTexcoord = aTexcoord;
    vTexcoord1 = aTexcoord1;
    vAlpha = aColor.a;
    gl_Layer = layer;
    gl_Position = clipFromWorldPerLayer[layer] * world;
}
