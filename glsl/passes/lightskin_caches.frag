#version 450 core
// LightSkin's cache view: a cache point is drawn unless the G-buffer holds a nearer surface at its
// pixel (beyond 2% of the distance: the cache lies on a surface, a little off the rasterised one).
#include "../lib/frame.glsl"

layout(binding = kUnitGBufferPosition) uniform sampler2D uPosition;

in vec3 vWorld;
flat in vec3 vColor;

layout(location = 0) out vec4 outColor;

void main()
{
    vec4 surface = texelFetch(uPosition, ivec2(gl_FragCoord.xy), 0);
    float pointDistance = distance(vWorld, frame.cameraPosition.xyz);
    if (surface.w != 0.0 && distance(surface.xyz, frame.cameraPosition.xyz) < 0.98 * pointDistance) discard;
    outColor = vec4(vColor, 1.0);
}
