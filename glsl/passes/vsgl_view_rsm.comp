#version 450 core
// VSGL's "mipmapped G-buffer acting as the light" (VSGL section 3: the PDF of BRSMs is computed "in
// the same fashion as VSGLs without visibility tests by exchanging RSMs and a G-buffer"): the
// camera's G-buffer, point-sampled on a uSize x uSize grid, written in the RSM layout
// (glsl/shared/rsm.h) so that the RSM mip kernel filters it and the VSGL generation kernel turns
// its texels into lights. The roles swap: a pixel "emits" importance (one unit per covered grid
// texel, in the flux channel), reflected by its BRDF about the direction towards the eye (the
// lobe channel), and RSM texels receive it (passes/vsgl_importance.comp).
#include "shared/bindings.h"
#include "shared/rsm.h"
#include "shared/sg.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = kUnitGBufferPosition) uniform sampler2D uPosition;
layout(binding = kUnitGBufferNormal) uniform sampler2D uNormal;
layout(binding = kUnitGBufferBaseColor) uniform sampler2D uBaseColor;
layout(binding = kUnitGBufferEmission) uniform sampler2D uEmission;
layout(rgba32f, binding = kImageRSMTarget) writeonly uniform image2DArray uTarget[kRSMAttachmentCount];

uniform int uSize;          // grid edge [texels], a power of two
uniform vec3 uEye;          // camera position [m]

void main()
{
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (texel.x >= uSize || texel.y >= uSize) return;
    ivec2 gsize = textureSize(uPosition, 0);
    // The G-buffer pixel at the grid texel's centre (nearest: a G-buffer is not filterable).
    ivec2 pixel = min(ivec2((vec2(texel) + 0.5) / float(uSize) * vec2(gsize)), gsize - 1);
    vec4 position = texelFetch(uPosition, pixel, 0);
    ivec3 at = ivec3(texel, 0);
    if (position.w == 0.0) {
        for (int a = 0; a < kRSMAttachmentCount; ++a) imageStore(uTarget[a], at, vec4(0.0));
        return;
    }
    vec4 normalRoughness = texelFetch(uNormal, pixel, 0);
    vec4 baseMetallic = texelFetch(uBaseColor, pixel, 0);
    float specularFactor = texelFetch(uEmission, pixel, 0).a;
    vec3 n = normalize(normalRoughness.xyz);
    vec3 toEye = normalize(uEye - position.xyz);
    vec3 diffuse = (1.0 - baseMetallic.a) * baseMetallic.rgb;
    vec3 f0 = mix(vec3(0.04 * specularFactor), baseMetallic.rgb, baseMetallic.a);
    SpecularLobe lobe = ggxReflectionLobe(n, toEye, normalRoughness.w);
    imageStore(uTarget[kRSMPosition], at, vec4(position.xyz, dot(position.xyz, position.xyz)));
    imageStore(uTarget[kRSMNormal], at, vec4(n, 1.0));
    imageStore(uTarget[kRSMFlux], at, vec4(1.0, 1.0, 1.0, 0.0)); // one unit of importance per covered texel
    imageStore(uTarget[kRSMDiffuse], at, vec4(diffuse, 0.0));
    imageStore(uTarget[kRSMSpecular], at, vec4(f0, normalRoughness.w));
    imageStore(uTarget[kRSMLobe], at, vec4(toksvigEncode(lobe.axis, lobe.sharpness), lobe.integral));
}
