#version 450 core
// Real GPU work for the pass-timer test: a full-screen draw.
layout(location = 0) in vec2 vUV;
layout(location = 0) out vec4 color;

void main()
{
    color = vec4(vUV, 1.0 - vUV.x, 1.0);
}
