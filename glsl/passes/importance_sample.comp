#version 450 core
// Importance sampler, the draws (gl/passes/importance_sampler.h): draw i turns the uniforms of
// (uSeed, i) into a texel and its probability with the binary searches of glsl/shared/importance.h
// (LightSkin eq. 12; VSGL's BRSM sampling). One invocation per draw; draws are independent.
#include "shared/bindings.h"

layout(local_size_x = 64) in;
layout(binding = kImageImportance, r32f) uniform readonly image2D uImportance;
layout(std430, binding = kBindingImportanceColumns) readonly buffer Columns { float columns[]; };
layout(std430, binding = kBindingImportanceMarginal) readonly buffer Marginal { float marginal[]; };

// The table readers glsl/shared/importance.h expects.
float importanceMarginal(int u) { return marginal[u]; }
float importanceColumn(int u, int v) { return columns[v * imageSize(uImportance).x + u]; }
float importanceValue(int u, int v) { return imageLoad(uImportance, ivec2(u, v)).r; }

#include "shared/importance.h"

layout(std430, binding = kBindingImportanceSamples) writeonly buffer Samples { ImportanceSample samples[]; };

uniform int uCount;
uniform uint uSeed;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount) return;
    ivec2 size = imageSize(uImportance);
    samples[i] = sampleImportance(size.x, size.y, importanceUniforms(uSeed, uint(i)));
}
