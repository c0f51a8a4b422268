#version 450 core
// Writes a constant (the render-target test): layout location 2 avoids the shared locations
// (glsl/shared/bindings.h kLocation*).
layout(location = 2) uniform vec4 uValue;
layout(location = 0) out vec4 color;

void main()
{
    color = uValue;
}
