#version 450 core
// LightSkin + BRSM eq. (10)-(11): the bidirectional importance of every RSM texel as a virtual area
// light, its unoccluded contribution to the N_VS view samples, written into an R32F map with the
// layers side by side (layer l at columns [l W, (l + 1) W)). The VAL's flux is the diffusely
// reflected part of the texel's incident flux (gl/techniques/lightskin_technique.h), as luminance.
#include "shared/bindings.h"
#include "shared/lightskin.h"
#include "shared/lightskin_gpu.h"
#include "shared/rsm.h"
#include "shared/tonemap.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = kUnitRSMSource) uniform sampler2DArray uSource[kRSMAttachmentCount];
layout(std430, binding = kBindingViewSamples) readonly buffer Samples { ViewSample samples[]; };
layout(r32f, binding = kImageImportance) writeonly uniform image2D uImportance;

uniform int uSize;            // RSM edge [texels]
uniform int uLayers;          // RSM layers
uniform int uViewCount;       // N_VS
uniform float uClampDistance; // eq. (11)'s clamp [m]

void main()
{
    ivec2 at = ivec2(gl_GlobalInvocationID.xy);
    if (at.x >= uSize * uLayers || at.y >= uSize) return;
    ivec3 texel = ivec3(at.x % uSize, at.y, at.x / uSize);
    vec4 normalCoverage = texelFetch(uSource[kRSMNormal], texel, 0);
    float importance = 0.0;
    if (normalCoverage.w > 0.0) {
        vec3 position = texelFetch(uSource[kRSMPosition], texel, 0).xyz;
        vec3 normal = normalize(normalCoverage.xyz);
        vec3 flux = texelFetch(uSource[kRSMFlux], texel, 0).rgb * texelFetch(uSource[kRSMDiffuse], texel, 0).rgb;
        float fluxLuminance = luminanceRec709(flux);
        if (fluxLuminance > 0.0) {
            float sum = 0.0;
            for (int j = 0; j < uViewCount; ++j) {
                ViewSample s = samples[j];
                if (s.positionValid.w == 0.0) continue;
                sum += valImportance(fluxLuminance, position, normal, s.positionValid.xyz, s.normal.xyz, uClampDistance);
            }
            importance = sum / float(uViewCount);
        }
    }
    imageStore(uImportance, at, vec4(importance, 0.0, 0.0, 0.0));
}
