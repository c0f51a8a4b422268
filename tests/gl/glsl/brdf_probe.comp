#version 450 core
// Evaluates the shared BRDF and tone map on the GPU for inputs given by the test.
layout(local_size_x = 64) in;
#include "shared/brdf.h"
#include "shared/tonemap.h"

struct Case {
    vec4 baseColorMetallic;
    vec4 roughnessSpecular; // x roughness, y specular
    vec4 n;
    vec4 v;
    vec4 l;
};
layout(std430, binding = 0) readonly buffer Cases { Case cases[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform int uCount;

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount) return;
    Case c = cases[i];
    SurfaceMaterial m = SurfaceMaterial(c.baseColorMetallic.rgb, c.baseColorMetallic.a, c.roughnessSpecular.x,
                                        c.roughnessSpecular.y);
    vec3 f = evaluateBRDF(m, c.n.xyz, c.v.xyz, c.l.xyz);
    results[2 * i] = vec4(f, 0.0);
    vec3 t = toneMapReinhard(f, 0.7);
    results[2 * i + 1] = vec4(encodeSRGB(t.r), encodeSRGB(t.g), encodeSRGB(t.b), 0.0);
}
