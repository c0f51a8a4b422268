#version 450 core
// Debug drawings of a VPL set (gl/techniques/vpl_technique.h, views <technique>.splats and
// <technique>.overhead): uMode 0 the scene's triangles (vertex attributes), 1 one point per VPL slot
// (pulled from the VPL SSBO by gl_VertexID; empty slots are sent outside the clip volume), 2 the
// camera frustum's 12 edges as a line list (uLines).
#include "../shared/bindings.h"
#include "../shared/vpl.h"

layout(location = 0) in vec3 aPosition;
layout(location = 2) in vec2 aTexcoord;
layout(location = 4) in vec2 aTexcoord1;
layout(location = 5) in vec4 aColor;

layout(std430, binding = kBindingVPLs) readonly buffer VPLs {
    GpuVPL vpls[];
};

uniform int uMode;
uniform mat4 uClipFromWorld;
uniform mat4 uWorldFromObject;
uniform vec3 uLines[24];
uniform float uPointSize;

out vec3 vWorld;
out vec2 vTexcoord; // uMode 0: for alpha masks (both UV sets, COLOR_0's alpha)
out vec2 vTexcoord1;
out float vAlpha;
flat out vec3 vColor;

void main()
{
    vec3 world;
    vColor = vec3(1.0, 0.85, 0.2);
    if (uMode == 0) {
        world = (uWorldFromObject * vec4(aPosition, 1.0)).xyz;
    } else if (uMode == 1) {
        GpuVPL vpl = vpls[gl_VertexID];
        world = vpl.positionValid.xyz;
        vColor = vpl.intensity.rgb;
        if (vpl.positionValid.w == 0.0) {
            gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
            return;
        }
    } else {
        world = uLines[gl_VertexID];
    }
    vWorld = world;
    vTexcoord = uMode == 0 ? aTexcoord : vec2(0.0);
    vTexcoord1 = uMode == 0 ? aTexcoord1 : vec2(0.0);
    vAlpha = uMode == 0 ? aColor.a : 1.0;
    gl_PointSize = uPointSize;
    gl_Position = uClipFromWorld * vec4(world, 1.0);
}
