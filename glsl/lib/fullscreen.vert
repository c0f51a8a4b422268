#version 450 core
#extension GL_ARB_shader_viewport_layer_array : require
#include "../shared/bindings.h"
// One triangle that covers the viewport; no vertex buffer. uLayer selects the layer of a layered
// target (FullscreenDraw::layer; 0 for ordinary 2D targets).
layout(location = kLocationFullscreenLayer) uniform int uLayer;
layout(location = 0) out vec2 vUV;

void main()
{
    vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    vUV = p;
    gl_Layer = uLayer;
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
