#version 450 core
// Touches every member of the shared GPU structs so the driver reports their offsets.
layout(local_size_x = 1) in;
#include "lib/frame.glsl"

layout(std430, binding = kBindingPointEmitters) buffer PointEmitters { PointEmitter pointEmitters[]; };
layout(std430, binding = kBindingDirectionalEmitters) buffer DirectionalEmitters { DirectionalEmitter directionalEmitters[]; };

void main()
{
    vec4 sum = frame.clipFromWorld[0] + frame.viewFromWorld[0] + frame.worldFromClip[0] + frame.cameraPosition +
               frame.viewport + vec4(frame.counts) + frame.shadow + frame.toneMap;
    pointEmitters[0].positionProfile = sum;
    pointEmitters[0].intensity = sum;
    pointEmitters[0].axisCosOuter = sum;
    pointEmitters[0].cosInner = sum;
    directionalEmitters[0].direction = sum;
    directionalEmitters[0].irradiance = sum;
}
