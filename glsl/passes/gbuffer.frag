#version 450 core
// G-buffer: world position, shading normal + roughness, base colour + metallic, emission + specular,
// geometric and interpolated normals (octahedral; gl/passes/gbuffer_pass.h says which is for what).
// Material evaluation matches core/scene/surface.cpp (surfaceAt) so CPU and GPU see the same surface.
#include "../lib/frame.glsl"
#include "../shared/normals.h"
#include "../lib/geometric_normal.glsl"
#include "../lib/alpha_mask.glsl"

layout(location = 0) in vec3 vWorldPosition;
layout(location = 1) in vec3 vNormal;
layout(location = 2) in vec2 vTexcoord;
layout(location = 3) in vec4 vTangent;
layout(location = 4) in vec2 vTexcoord1;
layout(location = 5) in vec4 vColor; // COLOR_0

layout(binding = kUnitBaseColor) uniform sampler2D uBaseColorTexture;         // sRGB format
layout(binding = kUnitMetallicRoughness) uniform sampler2D uMetallicRoughnessTexture;
layout(binding = kUnitEmission) uniform sampler2D uEmissionTexture;           // sRGB format
layout(binding = kUnitNormalMap) uniform sampler2D uNormalTexture;

uniform vec4 uBaseColor;
uniform vec4 uMaterial;   // x metallic, y roughness, z specular, w normal scale
uniform vec4 uEmission;   // rgb emitted radiance
uniform ivec4 uTextures;  // x normal map present (with tangents), y double-sided

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outBaseColor;
layout(location = 3) out vec4 outEmission;
layout(location = 4) out vec4 outSurfaceNormals;

void main()
{
    vec3 n = normalize(vNormal);
    vec3 interpolated = n;
    if (uTextures.x != 0) {
        vec3 t = normalize(vTangent.xyz);
        t = normalize(t - n * dot(n, t));
        vec3 b = cross(n, t) * (vTangent.w < 0.0 ? -1.0 : 1.0);
        vec3 tn = texture(uNormalTexture, materialUV(kUnitNormalMap, vTexcoord, vTexcoord1)).xyz * 2.0 - 1.0;
        tn.xy *= uMaterial.w;
        n = normalize(t * tn.x + b * tn.y + n * tn.z);
    }
    // Double-sided materials are shaded on the side the viewer sees (core/scene/surface.cpp does the same).
    if (uTextures.y != 0 && !gl_FrontFacing) {
        n = -n;
        interpolated = -interpolated;
    }
    // The triangle's plane, on the shading normal's side; a degenerate derivative: the vertex normal.
    vec3 geometric = geometricNormal(vWorldPosition, n, interpolated);

    vec4 base = uBaseColor * vColor * texture(uBaseColorTexture, materialUV(kUnitBaseColor, vTexcoord, vTexcoord1));
    vec4 mr = texture(uMetallicRoughnessTexture, materialUV(kUnitMetallicRoughness, vTexcoord, vTexcoord1));
    float metallic = uMaterial.x * mr.b;
    float roughness = uMaterial.y * mr.g;
    vec3 emission = uEmission.rgb * texture(uEmissionTexture, materialUV(kUnitEmission, vTexcoord, vTexcoord1)).rgb;

    outPosition = vec4(vWorldPosition, 1.0);
    outNormal = vec4(n, roughness);
    outBaseColor = vec4(base.rgb, metallic);
    outEmission = vec4(emission, uMaterial.z);
    outSurfaceNormals = vec4(octEncode(geometric), octEncode(interpolated));
    discardMasked(uBaseColorTexture, vTexcoord, vTexcoord1, vColor.a);
}
