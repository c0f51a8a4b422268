#version 450 core
// Omnidirectional shadows store the radial distance to the emitter over the far distance, so the
// lookup compares distances directly (no per-face depth linearisation).
#include "../lib/frame.glsl"
#include "../lib/alpha_mask.glsl"

layout(location = 0) in vec3 vWorldPosition;
layout(location = 1) flat in int vLayer;
layout(location = 2) in vec2 vTexcoord;
layout(location = 3) in vec2 vTexcoord1;
layout(location = 4) in float vAlpha;

layout(binding = kUnitBaseColor) uniform sampler2D uBaseColorTexture;

uniform float uFarDistance; // [m]; stored values are distance / uFarDistance

layout(std430, binding = kBindingPointEmitters) readonly buffer PointEmitters {
    PointEmitter pointEmitters[];
};

void main()
{
    vec3 lightPosition = pointEmitters[vLayer / 6].positionProfile.xyz;
    gl_FragDepth = clamp(distance(vWorldPosition, lightPosition) / uFarDistance, 0.0, 1.0);
    discardMasked(uBaseColorTexture, vTexcoord, vTexcoord1, vAlpha);
}
