#version 450 core
// RSM mip level l+1 from level l (gl/passes/rsm_pass.h, "Mips"): one invocation per target texel
// and layer reads its 2x2 children in a fixed order, so the result does not depend on scheduling.
//  - coverage (normal.w) and flux: plain means of the children (empty texels count as 0), so the
//    level-l flux summed and scaled by 4^l is the level-0 total;
//  - everything else: means weighted by w_i = flux_r + flux_g + flux_b of child i (its coverage
//    times the mean flux of its covered texels); where all four carry no flux, weighted by
//    coverage instead; where none is covered, 0.
#include "../shared/bindings.h"
#include "../shared/rsm.h"

layout(local_size_x = kRSMDownsampleGroupSize, local_size_y = kRSMDownsampleGroupSize, local_size_z = 1) in;

// Level l is read with texelFetch and level l+1 written as images: six image uniforms, within
// the GL minimum of eight (GL_MAX_COMPUTE_IMAGE_UNIFORMS) that some drivers do not exceed.
layout(binding = kUnitRSMSource) uniform sampler2DArray uSource[kRSMAttachmentCount];
layout(rgba32f, binding = kImageRSMTarget) writeonly uniform image2DArray uTarget[kRSMAttachmentCount];

uniform ivec2 uTargetSize; // level l+1 size; level l is exactly twice (power-of-two RSMs)
uniform int uSourceLevel;  // l

void main()
{
    ivec3 texel = ivec3(gl_GlobalInvocationID);
    if (texel.x >= uTargetSize.x || texel.y >= uTargetSize.y) return;

    ivec3 child[4];
    child[0] = ivec3(2 * texel.x, 2 * texel.y, texel.z);
    child[1] = child[0] + ivec3(1, 0, 0);
    child[2] = child[0] + ivec3(0, 1, 0);
    child[3] = child[0] + ivec3(1, 1, 0);

    vec4 flux[4];
    vec4 normal[4];
    for (int i = 0; i < 4; ++i) {
        flux[i] = texelFetch(uSource[kRSMFlux], child[i], uSourceLevel);
        normal[i] = texelFetch(uSource[kRSMNormal], child[i], uSourceLevel);
    }
    float weight[4];
    float total = 0.0;
    for (int i = 0; i < 4; ++i) {
        weight[i] = flux[i].r + flux[i].g + flux[i].b;
        total += weight[i];
    }
    if (!(total > 0.0)) {
        total = 0.0;
        for (int i = 0; i < 4; ++i) {
            weight[i] = normal[i].w;
            total += weight[i];
        }
    }
    float scale = total > 0.0 ? 1.0 / total : 0.0;

    vec4 fluxMean = 0.25 * (((flux[0] + flux[1]) + flux[2]) + flux[3]);
    float coverage = 0.25 * (((normal[0].w + normal[1].w) + normal[2].w) + normal[3].w);
    vec3 normalMean = (((weight[0] * normal[0].xyz + weight[1] * normal[1].xyz) + weight[2] * normal[2].xyz) +
                       weight[3] * normal[3].xyz) * scale;
    imageStore(uTarget[kRSMFlux], texel, fluxMean);
    imageStore(uTarget[kRSMNormal], texel, vec4(normalMean, coverage));

    // The attachments averaged with the weights (constant indices: the loop unrolls).
    for (int a = 0; a < kRSMAttachmentCount; ++a) {
        if (a == kRSMFlux || a == kRSMNormal) continue;
        vec4 sum = vec4(0.0);
        for (int i = 0; i < 4; ++i) sum += weight[i] * texelFetch(uSource[a], child[i], uSourceLevel);
        imageStore(uTarget[a], texel, sum * scale);
    }
}
