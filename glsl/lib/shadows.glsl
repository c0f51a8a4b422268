// Shadow lookups shared by the passes that shade with the direct emitters.
#include "frame.glsl"

layout(binding = kUnitPointShadows) uniform samplerCubeArray uPointShadows;
layout(binding = kUnitDirectionalShadows) uniform sampler2DArray uDirectionalShadows;

layout(std430, binding = kBindingShadowMatrices) readonly buffer ShadowMatricesLookup {
    mat4 shadowClipFromWorld[];
};

// 1 = lit, 0 = shadowed. `p` is offset along the normal by about one shadow texel at its distance.
float pointShadow(int cube, vec3 lightPosition, vec3 p, vec3 n)
{
    vec3 toPoint = p - lightPosition;
    float d = length(toPoint);
    float texel = 2.0 * d / float(textureSize(uPointShadows, 0).x);
    vec3 q = p + n * (frame.shadow.y * texel);
    vec3 dir = q - lightPosition;
    float stored = texture(uPointShadows, vec4(dir, float(cube))).r * frame.shadow.x;
    return length(dir) - frame.shadow.z <= stored ? 1.0 : 0.0;
}

// Percentage-closer filtering over (2r+1)^2 texels of a directional shadow map layer.
float directionalShadow(int layer, vec3 p, vec3 n)
{
    ivec3 size = textureSize(uDirectionalShadows, 0);
    mat4 clipFromWorld = shadowClipFromWorld[layer];
    // World size of one texel: the orthographic extent over the resolution.
    float texelWorld = 2.0 / (length(clipFromWorld[0].xyz) * float(size.x));
    vec4 clip = clipFromWorld * vec4(p + n * (frame.shadow.y * texelWorld), 1.0);
    vec3 ndc = clip.xyz / clip.w;
    vec2 uv = ndc.xy * 0.5 + 0.5;
    float depth = ndc.z * 0.5 + 0.5;
    if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || depth > 1.0) return 1.0;
    int r = int(frame.shadow.w);
    float lit = 0.0;
    for (int y = -r; y <= r; ++y)
        for (int x = -r; x <= r; ++x) {
            float stored = texture(uDirectionalShadows, vec3(uv + vec2(x, y) / vec2(size.xy), float(layer))).r;
            lit += depth <= stored + 1e-5 ? 1.0 : 0.0;
        }
    return lit / float((2 * r + 1) * (2 * r + 1));
}
