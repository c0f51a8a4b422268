// Direct-light emitters as the GPU shades them and the CPU evaluates them (one definition).
// Every point, spot or emissive-triangle sample is a PointEmitter; directional lights are
// DirectionalEmitters. std430 layout, vec4 members only.
#ifndef VPLGI_SHARED_LIGHTS_H
#define VPLGI_SHARED_LIGHTS_H
#include "compat.h"

VPLGI_SHARED_BEGIN

VPLGI_CONST int kProfileIsotropic = 0; // point light: I(w) = intensity
VPLGI_CONST int kProfileSpot = 1;      // glTF spot: intensity * smooth cone falloff
VPLGI_CONST int kProfileCosine = 2;    // sample of an emissive surface: intensity * max(cos, 0)

struct PointEmitter {
    vec4 positionProfile; // xyz position [m], w = profile (as float)
    vec4 intensity;       // rgb peak radiant intensity [W/sr], w = shadow map layer (as float, -1 = none)
    vec4 axisCosOuter;    // xyz axis (direction of emission), w = cos(outer cone angle)
    vec4 cosInner;        // x = cos(inner cone angle), yzw unused
};

struct DirectionalEmitter {
    vec4 direction;  // xyz direction light travels (unit), w = shadow map index (as float, -1 = none)
    vec4 irradiance; // rgb irradiance on a surface facing the light [W/m^2]
};

// Fraction of the peak intensity emitted towards `dirFromLight` (unit, pointing away from the light).
VPLGI_FUNC float emitterProfile(PointEmitter e, vec3 dirFromLight)
{
    int profile = int(e.positionProfile.w + 0.5f);
    float c = dot(vec3(e.axisCosOuter), dirFromLight);
    if (profile == kProfileSpot) {
        float cosOuter = e.axisCosOuter.w;
        float cosInner = e.cosInner.x;
        float t = clamp((c - cosOuter) / max(cosInner - cosOuter, 1e-4f), 0.0f, 1.0f);
        return t * t;
    }
    if (profile == kProfileCosine) return max(c, 0.0f);
    return 1.0f;
}

VPLGI_SHARED_END

#endif // VPLGI_SHARED_LIGHTS_H
