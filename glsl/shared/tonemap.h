// Display transform shared by the GPU tone-map pass and CPU metrics (MATH.md section 8):
// exposure, Reinhard's global operator on luminance (hue kept), clamp, sRGB encoding.
#ifndef VPLGI_SHARED_TONEMAP_H
#define VPLGI_SHARED_TONEMAP_H
#include "compat.h"

VPLGI_SHARED_BEGIN

VPLGI_FUNC float luminanceRec709(vec3 c)
{
    return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

// L_d = L / (1 + L) applied to luminance after exposure; colour scaled by L_d / L.
// Numeric guard: a NaN or infinite channel makes the luminance NaN or infinite (every weight is
// positive), and Reinhard would then give NaN (inf / inf), which clamp() does not define; such a
// pixel shows black. The linear radiance output keeps the value, so `render --stats` and the soak
// still count it.
VPLGI_FUNC vec3 toneMapReinhard(vec3 radiance, float exposure)
{
    vec3 c = radiance * exposure;
    float l = luminanceRec709(c);
    if (!(l > 0.0f) || isinf(l)) return vec3(0.0f);
    return clamp(c * (1.0f / (1.0f + l)), vec3(0.0f), vec3(1.0f));
}

VPLGI_FUNC float encodeSRGB(float c)
{
    return c <= 0.0031308f ? 12.92f * c : 1.055f * pow(c, 1.0f / 2.4f) - 0.055f;
}

VPLGI_SHARED_END

#endif // VPLGI_SHARED_TONEMAP_H
