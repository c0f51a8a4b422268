// The material model of vplgi, defined once for the GPU (GLSL) and the CPU (C++: the path tracer
// and the CPU reference evaluations). glTF 2.0 metallic-roughness:
//   f_r = (1 - metallic) * baseColor / pi                               (Lambert)
//       + D_GGX(h) * V_SmithGGXCorrelated * F_Schlick(F0, v.h)           (microfacet, Filament's form)
//   F0  = mix(0.04 * specular, baseColor, metallic), alpha = roughness^2 (clamped to 0.002)
// `specular` = 0 with metallic = 0 gives an exactly Lambertian surface (Cornell box, furnace).
#ifndef VPLGI_SHARED_BRDF_H
#define VPLGI_SHARED_BRDF_H
#include "compat.h"

VPLGI_SHARED_BEGIN

VPLGI_CONST float kPi = 3.14159265358979f;
VPLGI_CONST float kInvPi = 0.31830988618379f;
VPLGI_CONST float kMinAlpha = 0.002f;

struct SurfaceMaterial {
    vec3 baseColor;  // linear albedo / F0 tint
    float metallic;  // [0,1]
    float roughness; // perceptual [0,1]
    float specular;  // dielectric F0 scale (0.04 * specular)
};

VPLGI_FUNC float distributionGGX(float NoH, float alpha)
{
    float a2 = alpha * alpha;
    float d = NoH * NoH * (a2 - 1.0f) + 1.0f;
    return a2 / (kPi * d * d);
}

// Height-correlated Smith visibility term V = G / (4 NoL NoV) (Heitz 2014).
VPLGI_FUNC float visibilitySmithGGX(float NoV, float NoL, float alpha)
{
    float a2 = alpha * alpha;
    float gv = NoL * sqrt(NoV * NoV * (1.0f - a2) + a2);
    float gl = NoV * sqrt(NoL * NoL * (1.0f - a2) + a2);
    return 0.5f / max(gv + gl, 1e-8f);
}

VPLGI_FUNC vec3 fresnelSchlick(vec3 f0, float VoH)
{
    float m = clamp(1.0f - VoH, 0.0f, 1.0f);
    float m2 = m * m;
    return f0 + (vec3(1.0f) - f0) * (m2 * m2 * m);
}

// BRDF value [1/sr] of the glTF model given by its coefficients: diffuse reflectance rho_d (the
// Lambert lobe is rho_d / pi), F0 and perceptual roughness; v and l point away from the surface.
// Zero below the horizon. The VSGL lights carry these coefficients (glsl/shared/sg.h), not a material.
VPLGI_FUNC vec3 evaluateBRDFCoefficients(vec3 diffuse, vec3 f0, float roughness, vec3 n, vec3 v, vec3 l)
{
    float NoL = dot(n, l);
    float NoV = dot(n, v);
    if (NoL <= 0.0f || NoV <= 0.0f) return vec3(0.0f);
    vec3 lambert = diffuse * kInvPi;
    if (f0.x + f0.y + f0.z <= 0.0f) return lambert;
    vec3 h = normalize(v + l);
    float alpha = max(roughness * roughness, kMinAlpha);
    float D = distributionGGX(clamp(dot(n, h), 0.0f, 1.0f), alpha);
    float V = visibilitySmithGGX(NoV, NoL, alpha);
    vec3 F = fresnelSchlick(f0, clamp(dot(v, h), 0.0f, 1.0f));
    return lambert + D * V * F;
}

// BRDF value f_r(n, v, l) [1/sr] of a material; v and l point away from the surface. Zero below the horizon.
VPLGI_FUNC vec3 evaluateBRDF(SurfaceMaterial m, vec3 n, vec3 v, vec3 l)
{
    vec3 f0 = mix(vec3(0.04f * m.specular), m.baseColor, m.metallic);
    return evaluateBRDFCoefficients((1.0f - m.metallic) * m.baseColor, f0, m.roughness, n, v, l);
}

VPLGI_SHARED_END

#endif // VPLGI_SHARED_BRDF_H
