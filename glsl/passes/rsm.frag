#version 450 core
// RSM texel: world position (+ |x|^2), normal + coverage, incident flux, diffuse and specular
// reflectance, specular lobe and its integral (gl/passes/rsm_pass.h). The material is evaluated as in
// passes/gbuffer.frag (and core/scene/surface.cpp), so the RSM sees the surface the camera sees.
#include "../shared/lights.h"
#include "../shared/rsm.h"
#include "../shared/bindings.h"
#include "../shared/sg.h"
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
layout(binding = kUnitNormalMap) uniform sampler2D uNormalTexture;

uniform vec4 uBaseColor;
uniform vec4 uMaterial;   // x metallic, y roughness, z specular, w normal scale
uniform ivec4 uTextures;  // x normal map present (with tangents), y double-sided

uniform int uLightKind;          // kRSMLightSpot / kRSMLightPoint / kRSMLightArea / kRSMLightDirectional
uniform vec4 uLightPosition;     // spot, point, area: xyz position [m]
uniform vec4 uLightDirection;    // spot: axis; point, area: the cube face's axis; directional: direction light travels (unit)
uniform vec4 uEmitterAxis;       // spot: axis; area: the emitters' mean normal (cosine profile)
uniform vec4 uLightPower;        // spot, area: peak intensity, point: intensity [W/sr]; directional: irradiance [W/m^2] (rgb)
uniform vec4 uLightCone;         // spot: x cos(outer), y cos(inner)
// 4 / (P[0][0] P[1][1] W H) of the light's projection P and the RSM size W x H: the texel's solid
// angle on the axis, in [sr] (spot, MATH.md 1.5: w_n h_n / (W H z_n^2)), or its area [m^2]
// (orthographic: w_o h_o / (W H)).
uniform float uTexelFactor;

layout(location = kRSMPosition) out vec4 outPosition;
layout(location = kRSMNormal) out vec4 outNormal;
layout(location = kRSMFlux) out vec4 outFlux;
layout(location = kRSMDiffuse) out vec4 outDiffuse;
layout(location = kRSMSpecular) out vec4 outSpecular;
layout(location = kRSMLobe) out vec4 outLobe;

void main()
{
    vec3 n = normalize(vNormal);
    if (uTextures.x != 0) {
        vec3 t = normalize(vTangent.xyz);
        t = normalize(t - n * dot(n, t));
        vec3 b = cross(n, t) * (vTangent.w < 0.0 ? -1.0 : 1.0);
        vec3 tn = texture(uNormalTexture, materialUV(kUnitNormalMap, vTexcoord, vTexcoord1)).xyz * 2.0 - 1.0;
        tn.xy *= uMaterial.w;
        n = normalize(t * tn.x + b * tn.y + n * tn.z);
    }
    if (uTextures.y != 0 && !gl_FrontFacing) n = -n;
    // The triangle's plane, for the VPLs' cosines (sg.h, vplRadiance). Level 0 only: the mips
    // average its encoding.
    vec2 geometricOct = octEncode(geometricNormal(vWorldPosition, n, n));

    vec4 base = uBaseColor * vColor * texture(uBaseColorTexture, materialUV(kUnitBaseColor, vTexcoord, vTexcoord1));
    vec4 mr = texture(uMetallicRoughnessTexture, materialUV(kUnitMetallicRoughness, vTexcoord, vTexcoord1));
    float metallic = uMaterial.x * mr.b;
    float roughness = uMaterial.y * mr.g;
    vec3 diffuse = (1.0 - metallic) * base.rgb;
    vec3 f0 = mix(vec3(0.04 * uMaterial.z), base.rgb, metallic);

    // Flux through the texel (MATH.md 1.5), towards the light `toLight`.
    vec3 incident;
    vec3 toLight;
    if (uLightKind != kRSMLightDirectional) {
        // A point light's cube face is a 90-degree perspective view down the face axis: the same
        // texel solid angle as a spot's frustum, with an isotropic profile (area: cosine).
        vec3 fromLight = normalize(vWorldPosition - uLightPosition.xyz);
        int profile = uLightKind == kRSMLightSpot ? kProfileSpot : uLightKind == kRSMLightArea ? kProfileCosine
                                                                                                : kProfileIsotropic;
        PointEmitter e;
        e.positionProfile = vec4(uLightPosition.xyz, float(profile));
        e.intensity = uLightPower;
        e.axisCosOuter = vec4(uEmitterAxis.xyz, uLightCone.x);
        e.cosInner = vec4(uLightCone.y, 0.0, 0.0, 0.0);
        float cosAlpha = dot(uLightDirection.xyz, fromLight);
        // Solid angle of the texel: on-axis value times cos^3 of the ray's angle to the axis.
        float solidAngle = uTexelFactor * cosAlpha * cosAlpha * cosAlpha;
        incident = uLightPower.rgb * emitterProfile(e, fromLight) * solidAngle;
        toLight = -fromLight;
    } else {
        incident = uLightPower.rgb * uTexelFactor;
        toLight = -uLightDirection.xyz;
    }

    // Specular lobe (VSGL 3.2): the GGX reflection lobe of toLight as an SG (glsl/shared/sg.h: the NDF's
    // SG warped about n, MATH.md 4.6-4.7), stored as the Toksvig mean vector r xi, r = eta/(1+eta)
    // (4.8) so that mips average it, and its integral factor s (mean over texels, weighted by flux).
    SpecularLobe lobe = ggxReflectionLobe(n, toLight, roughness);

    outPosition = vec4(vWorldPosition, dot(vWorldPosition, vWorldPosition));
    outNormal = vec4(n, 1.0);
    outFlux = vec4(incident, geometricOct.x);
    outDiffuse = vec4(diffuse, geometricOct.y);
    outSpecular = vec4(f0, roughness);
    outLobe = vec4(toksvigEncode(lobe.axis, lobe.sharpness), lobe.integral);
    discardMasked(uBaseColorTexture, vTexcoord, vTexcoord1, vColor.a);
}
