#version 450 core
// RSM rasterisation from a light: one draw per light into layer uLayer of the RSM target
// (vertex-shader gl_Layer, as passes/shadow.vert).
#extension GL_ARB_shader_viewport_layer_array : require

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aTexcoord;
layout(location = 3) in vec4 aTangent;
layout(location = 4) in vec2 aTexcoord1;
layout(location = 5) in vec4 aColor;

uniform mat4 uWorldFromObject;
uniform mat4 uNormalFromObject; // inverse transpose of the upper 3x3, as a mat4
uniform mat4 uClipFromWorld;    // the light's view-projection
uniform int uLayer;

layout(location = 0) out vec3 vWorldPosition;
layout(location = 1) out vec3 vNormal;
layout(location = 2) out vec2 vTexcoord;
layout(location = 3) out vec4 vTangent;
layout(location = 4) out vec2 vTexcoord1;
layout(location = 5) out vec4 vColor; // COLOR_0

void main()
{
    vec4 world = uWorldFromObject * vec4(aPosition, 1.0);
    vWorldPosition = world.xyz;
    vNormal = mat3(uNormalFromObject) * aNormal;
    vTexcoord = aTexcoord;
    vTexcoord1 = aTexcoord1;
    vColor = aColor;
    vTangent = vec4(mat3(uWorldFromObject) * aTangent.xyz, aTangent.w);
    gl_Layer = uLayer;
    gl_Position = uClipFromWorld * world;
}
