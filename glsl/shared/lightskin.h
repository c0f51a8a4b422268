// The maths of LightSkin + bidirectional RSMs, defined once for the GPU (GLSL) and the CPU (C++:
// tests/cpu/test_lightskin_math.cpp checks every formula against closed forms, quadrature or Monte
// Carlo; tests/gl/test_lightskin_math_gpu.cpp checks that GLSL and C++ agree).
//
// Paper: LightSkin + BRSMs for open-world GI (papers/004), sections 3 and 4; the formulas are those
// of ../shared/MATH.md 9, tagged below. docs/lightskin.md ("Maths") lists the readings taken here
// and the numbers the tests print.
//
// Overview
// --------
//  lightskinValArea                 eq. (1): a VAL's disk area from its RSM texel           MATH 9.1
//  lightskinValAreaTilted           the exact footprint on the tilted surface (option)      MATH 9.1
//  valGeometryTerm, diskFormFactor  cos+ cos+ / (A + pi d^2), and A times it                MATH 9.2
//  phongExponentFromRoughness       GGX alpha -> the Phong exponent k of eq. (4), (6), (15)
//  phongBRDF                        rho_g (k+2)/(2 pi) cos+^k theta_e                        MATH 9.2
//  valDiffuseRadiance               one VAL's term of eq. (3) / (14)                         MATH 9.2, 9.9
//  valGlossyRadiance                one VAL's term of eq. (4) / (15)                         MATH 9.2, 9.9
//  valSelectionExpectation          P_VAL = N_sVAL p (the reading of eq. 13-15)              MATH 9.9
//  proxyWeightDiffuse / Glossy      eq. (6)                                                  MATH 9.3
//  proxyFluxFromRadiance            eq. (7), and pointLightRadiance, its inverse             MATH 9.4
//  interpolationWeight              eq. (8) (normalised over the caches by eq. 9)            MATH 9.5
//  valImportance                    eq. (10)'s summand with eq. (11)'s clamp                 MATH 9.6
//  halton, haltonViewPixel          the view samples of eq. (10)                             MATH 9.8
//  proxySphereRadius ... occlusionFromOverlap   occlusion by double projection (section 3)   MATH 9.3, 9.10
//
// Details
// -------
//  Eq. (1) for our RSMs. RSMView::texelFactor (gl/passes/rsm_pass.h) is 4/(P00 P11 W H), P the
//  light's clipFromView. A perspective frustum has P00 = 2 z_near/w_near and P11 = 2 z_near/h_near,
//  so texelFactor = 4 w_near h_near / (4 z_near^2 W H) and eq. (1) is exactly z^2 texelFactor, z the
//  texel's view-space depth (the reading of MATH 9.1: depth along the light axis, not distance). An
//  orthographic RSM of w_o x h_o has P00 = 2/w_o, P11 = 2/h_o: texelFactor = w_o h_o/(W H) is the
//  texel's area at every depth (MATH 9.1), so lightskinValArea returns it as is. Both are the
//  footprint on a plane perpendicular to the light axis, the paper's A_disk; the footprint on the
//  real surface, A cos(alpha)/cos(theta_s), is lightskinValAreaTilted (not the default).
//
//  Radiance (eq. 3, 4). Phi/A is the VAL's exitance and A cos cos/(A + pi d^2) the disk-to-point
//  form factor (exact on axis, approximate off axis: MATH 9.2), so one VAL's term is
//  f_r Phi F/A = f_r Phi cos+ cos+ / (A + pi d^2), which tends to the VPL term of a diffuse emitter
//  (intensity Phi cos/pi) as A -> 0. It is evaluated as the geometry term G_A = cos+ cos+ / (A + pi d^2)
//  so that A = 0 is not 0/0. The glossy BRDF is the normalised Phong lobe about the mirror direction:
//  theta_e is the angle between the view direction and the incident direction mirrored at the
//  receiver normal.
//
//  Selection (eq. 13-15). P_VAL is the expected number of times a VAL is drawn, N_sVAL p with p the
//  per-draw probability of glsl/shared/importance.h (MATH 9.9's reading; each draw counts, duplicates
//  included); with every VAL used once (lightskin-full), P_VAL = 1. A VAL with P_VAL <= 0 cannot have
//  been drawn and contributes 0.
//
//  Occlusion (section 3, "Occlusion"; MATH 9.3, 9.10). Everything a receiving cache c sees is
//  projected onto the unit disk about its normal (Nusselt's analogue): a direction w goes to its
//  tangent-plane coordinates (w.t, w.b), and a shape of form factor F covers an area pi F there. The
//  proxy light is a sphere: the paper's box (2 sigma_x, 2 sigma_y, 2 sigma_z) of the weighted VAL
//  positions, turned into a sphere whose radius is the box's largest dimension, 2 sigma_max. We read
//  the box extent as the full width (2 sigma), not the half width (sigma): for VALs uniform on a disk
//  of radius R, sigma per in-plane axis is R/2, so 2 sigma = R gives the sphere the disk's own radius,
//  where sigma would give a quarter of its area. The occluders are the other caches' disks (their
//  Voronoi areas). Both become axis-aligned squares of the same area about the projected centres;
//  the overlap of two squares is the product of the overlaps of their intervals, and
//  occlusion = min(1, sum of the occluders' overlaps with the proxy's square / the proxy's square).
//  Overlapping occluders are counted twice (the paper's "amount of cache quads overlapping"); the
//  min(1, ...) keeps the result a fraction.
//
//  Degenerate inputs give finite results (zero distance, zero area, zero normals, zero probability
//  give 0 or the limits stated per function).
#ifndef VPLGI_SHARED_LIGHTSKIN_H
#define VPLGI_SHARED_LIGHTSKIN_H
#include "brdf.h"
#include "compat.h"
#include "light_view.h"

VPLGI_SHARED_BEGIN

// --- Virtual area lights (eq. 1; MATH 9.1) --------------------------------------------------------

// Eq. (1): A_disk = z^2 w_near h_near / (z_near^2 W H) = viewDepth^2 texelFactor for a perspective
// RSM (the algebra is in the file head), texelFactor itself for an orthographic one [m^2].
// viewDepth: the texel's depth along the light axis (-z in the light's view space) [m];
// texelFactor: RSMView::texelFactor, 4/(P00 P11 W H).
VPLGI_FUNC float lightskinValArea(float viewDepth, float texelFactor, bool orthographic)
{
    return orthographic ? texelFactor : viewDepth * viewDepth * texelFactor;
}

// Below this cosine between the light's ray and the surface normal, the tilted footprint is held
// (a grazing texel would otherwise stretch without bound; 0.05 allows a stretch of 20).
VPLGI_CONST float kValMinSurfaceCosine = 0.05f;

// The exact footprint of the texel on the real surface (MATH 9.1): A_disk cos(alpha) / cos(theta_s),
// alpha the angle of the texel's ray to the light axis (cosAxis = 1 for an orthographic RSM),
// theta_s the angle of the ray to the surface normal. Not the paper's form (which is
// lightskinValArea); an option for the passes.
VPLGI_FUNC float lightskinValAreaTilted(float area, float cosAxis, float cosSurface)
{
    return area * cosAxis / max(abs(cosSurface), kValMinSurfaceCosine);
}

// --- Disk form factor and one VAL's radiance (eq. 3, 4, 14, 15; MATH 9.2, 9.9) --------------------

// G_A = cos+(theta_l) cos+(theta_x) / (A + pi d^2) [1/m^2], eq. (3)'s geometry (no 1/pi). cosLight:
// VAL normal . (x - x_l)/d; cosReceiver: receiver normal . (x_l - x)/d. 0 when A + pi d^2 is 0.
VPLGI_FUNC float valGeometryTerm(float area, float cosLight, float cosReceiver, float distance2)
{
    float denominator = area + kPi * distance2;
    if (!(denominator > 0.0f)) return 0.0f;
    return max(cosLight, 0.0f) * max(cosReceiver, 0.0f) / denominator;
}

// The disk-to-point form factor A cos+ cos+ / (A + pi d^2) (MATH 9.2: a^2/(d^2 + a^2) on axis for a
// disk of radius a, exact; approximate off axis, see docs/lightskin.md for the measured error).
VPLGI_FUNC float diskFormFactor(float area, float cosLight, float cosReceiver, float distance2)
{
    return area * valGeometryTerm(area, cosLight, cosReceiver, distance2);
}

// The mirror image of the unit direction w at the normal n: 2 (n.w) n - w (points away from the
// surface when w does). Eq. (4)'s reflection vector and eq. (8)'s r_x, r_c.
VPLGI_FUNC vec3 mirrorDirection(vec3 w, vec3 n)
{
    return 2.0f * dot(n, w) * n - w;
}

// GGX alpha (glTF roughness^2) -> Phong exponent k about the mirror direction. sg.h's NDF sharpness
// n = 2/alpha^2 - 2 describes a lobe in the half vector; the mirror direction moves twice as fast
// as the half vector (theta_e ~= 2 theta_h at normal view), so cos^k(theta_e) ~= exp(-2 k theta_h^2)
// matches exp(-n theta_h^2 / 2) at k = n/4. Chosen by measured error against the exact GGX lobe
// D V (F = 1) times cos over alpha 0.05..1 and views 0, 30, 60 degrees: n/4 has the smallest summed
// shape error of n/4, n/(4 cos theta_v) and n (tests/cpu/test_lightskin_math.cpp "GGX to Phong",
// table in docs/lightskin.md). k = 0 at alpha = 1; alpha is held at brdf.h's kMinAlpha (k = 125000)
// as the BRDF holds it, so a mirror gets a finite exponent.
VPLGI_FUNC float phongExponentFromRoughness(float alpha)
{
    float a = max(alpha, kMinAlpha);
    return max(0.5f / (a * a) - 0.5f, 0.0f);
}

// cos+^k: 0 for cosine <= 0 (also at k = 0, where the lobe is the hemisphere's constant).
VPLGI_FUNC float phongLobe(float cosine, float exponent)
{
    return cosine > 0.0f ? pow(min(cosine, 1.0f), exponent) : 0.0f;
}

// Eq. (4)'s glossy BRDF rho_g (k+2)/(2 pi) cos+^k(theta_e) [1/sr]; the normalisation makes
// int (k+2)/(2 pi) cos^k(theta_e) cos(theta) dw = 1 at normal incidence (MATH 9.2).
VPLGI_FUNC vec3 phongBRDF(vec3 glossy, float cosMirror, float exponent)
{
    return glossy * ((exponent + 2.0f) / (2.0f * kPi) * phongLobe(cosMirror, exponent));
}

// P_VAL of eq. (13)-(15): the expected number of draws of a VAL, drawCount times its per-draw
// probability (MATH 9.9); 1 for lightskin-full (every VAL once).
VPLGI_FUNC float valSelectionExpectation(float drawCount, float probability)
{
    return drawCount * probability;
}

// One VAL's term of eq. (3), divided by P_VAL as in eq. (14) [W/(m^2 sr)]:
//   Phi_l rho_d/pi cos+(theta_l) cos+(theta_x) / (A_l + pi |x_l - x|^2) / P_VAL.
// valFlux: the VAL's reflected flux Phi_l (RSM flux times the VAL's albedo) [W]; valArea from
// lightskinValArea; diffuse: the receiver's rho_d; selectionExpectation: P_VAL (1: eq. 3 itself).
// 0 for P_VAL <= 0 and for x = x_l.
VPLGI_FUNC vec3 valDiffuseRadiance(vec3 valFlux, vec3 valPosition, vec3 valNormal, float valArea, vec3 receiverPosition,
                                   vec3 receiverNormal, vec3 diffuse, float selectionExpectation)
{
    vec3 toVal = valPosition - receiverPosition;
    float distance2 = dot(toVal, toVal);
    if (!(selectionExpectation > 0.0f) || !(distance2 > 0.0f)) return vec3(0.0f);
    vec3 w = toVal * inversesqrt(distance2);
    float geometry = valGeometryTerm(valArea, -dot(valNormal, w), dot(receiverNormal, w), distance2);
    return valFlux * diffuse * (kInvPi * geometry / selectionExpectation);
}

// One VAL's term of eq. (4), divided by P_VAL as in eq. (15) [W/(m^2 sr)]:
//   Phi_l rho_g (k+2)/(2 pi) cos+^k(theta_e) cos+(theta_l) cos+(theta_x) / (A_l + pi |x_l - x|^2) / P_VAL,
// theta_e the angle between `view` (unit, from x towards the eye) and the incident direction
// (x_l - x)/d mirrored at receiverNormal. Arguments as valDiffuseRadiance; glossy: rho_g;
// phongExponent: k (phongExponentFromRoughness).
VPLGI_FUNC vec3 valGlossyRadiance(vec3 valFlux, vec3 valPosition, vec3 valNormal, float valArea, vec3 receiverPosition,
                                  vec3 receiverNormal, vec3 view, vec3 glossy, float phongExponent,
                                  float selectionExpectation)
{
    vec3 toVal = valPosition - receiverPosition;
    float distance2 = dot(toVal, toVal);
    if (!(selectionExpectation > 0.0f) || !(distance2 > 0.0f)) return vec3(0.0f);
    vec3 w = toVal * inversesqrt(distance2);
    float geometry = valGeometryTerm(valArea, -dot(valNormal, w), dot(receiverNormal, w), distance2);
    float cosMirror = dot(view, mirrorDirection(w, receiverNormal));
    return valFlux * phongBRDF(glossy, cosMirror, phongExponent) * (geometry / selectionExpectation);
}

// --- Proxy lights (eq. 5-7, 13; MATH 9.3, 9.4) ----------------------------------------------------

// eq. (6)'s epsilon_p: only keeps eq. (5)'s denominator away from 0. It must stay far below the
// form factors that matter: a 1 cm^2 VAL 10 m away has F ~ 1e-4 / (pi 100) ~ 3e-7, so 1e-12 is
// negligible against every VAL that contributes visibly (and a normal float).
VPLGI_CONST float kProxyWeightEpsilon = 1.0e-12f;

// Eq. (6), diffuse: w_d = epsilon_p + F(c <- l, disk) (formFactor from diskFormFactor at the cache).
// As printed the weight carries no flux (MATH 9.3, "Ambiguity"); a pass that wants flux weighting
// multiplies by the VAL's flux luminance.
VPLGI_FUNC float proxyWeightDiffuse(float formFactor, float epsilon)
{
    return epsilon + formFactor;
}

// Eq. (6), glossy: w_g = epsilon_p + cos+^k(theta_e) F(c <- l, disk).
VPLGI_FUNC float proxyWeightGlossy(float formFactor, float cosMirror, float phongExponent, float epsilon)
{
    return epsilon + phongLobe(cosMirror, phongExponent) * formFactor;
}

// Below this cosine (or BRDF value) eq. (7) gives no flux: the division would turn float noise into
// an unbounded flux. 1e-6 is below any cosine a visible contribution comes from.
VPLGI_CONST float kProxyMinDenominator = 1.0e-6f;

// Eq. (7), per colour channel (MATH 9.4): Phi_p = 4 pi L |x_p - c|^2 / (f_r(c, w, w_i) cos+(n_c.w_i)),
// w_i = (x_p - c)/|x_p - c|; radiance: eq. (3)/(14) (diffuse proxy) or (4)/(15) (glossy proxy) at c;
// brdf: the cache's f_r towards w_i (rho_d/pi, or phongBRDF). A channel whose brdf, or a cosine, is
// below kProxyMinDenominator gets 0. The isotropic point light Phi_p/(4 pi) at x_p then reproduces
// `radiance` at c exactly (pointLightRadiance).
// The cache's reflectance cancels (MATH 9.4): evaluating eq. (3)/(4) with rho = 1 and passing
// brdf = 1/pi (or phongBRDF(vec3(1), ...)) gives the same flux, and keeps the light a cache passes
// on to pixels in a channel where the cache's own colour is 0 (which would otherwise give 0 there).
VPLGI_FUNC vec3 proxyFluxFromRadiance(vec3 radiance, float distance2, vec3 brdf, float cosCache)
{
    if (!(cosCache > kProxyMinDenominator)) return vec3(0.0f);
    vec3 flux;
    float scale = 4.0f * kPi * distance2 / cosCache;
    flux.x = brdf.x > kProxyMinDenominator ? scale * radiance.x / brdf.x : 0.0f;
    flux.y = brdf.y > kProxyMinDenominator ? scale * radiance.y / brdf.y : 0.0f;
    flux.z = brdf.z > kProxyMinDenominator ? scale * radiance.z / brdf.z : 0.0f;
    return flux;
}

// The radiance an isotropic point light of flux Phi (intensity Phi/(4 pi)) at squared distance d^2
// reflects: f_r Phi/(4 pi) cos+(theta) / d^2 (MATH 9.5, shading with the interpolated proxies;
// without occlusion). 0 at d = 0.
VPLGI_FUNC vec3 pointLightRadiance(vec3 flux, float distance2, vec3 brdf, float cosReceiver)
{
    if (!(distance2 > 0.0f)) return vec3(0.0f);
    return brdf * flux * (max(cosReceiver, 0.0f) / (4.0f * kPi * distance2));
}

// --- Interpolation (eq. 8, 9; MATH 9.5) -----------------------------------------------------------

// The default exponent p of eq. (8): linear falloff (the paper gives no value; MATH 9.5's reading).
VPLGI_CONST float kInterpolationExponent = 1.0f;

// Eq. (8): w' = (1 - |x - c| / d_c,max)^p cos+, with cosNormals = n_x.n_c (diffuse) or r_x.r_c
// (glossy, mirrorDirection of the incident direction at x and at c). maxDistance: the distance to the
// farthest of the point's caches, which therefore gets weight 0. maxDistance <= 0 (all caches at x)
// gives cos+. Eq. (9) divides by the sum over the caches.
VPLGI_FUNC float interpolationWeight(float distance, float maxDistance, float exponent, float cosNormals)
{
    float falloff = maxDistance > 0.0f ? max(1.0f - distance / maxDistance, 0.0f) : 1.0f;
    float shaped = falloff > 0.0f ? pow(falloff, exponent) : 0.0f;
    return shaped * max(cosNormals, 0.0f);
}

// --- Bidirectional importance (eq. 10, 11; MATH 9.6) ---------------------------------------------

// The default clamp distance of eq. (11) [m]: the paper clamps |l|^2 below at 1 (scene units).
VPLGI_CONST float kImportanceClampDistance = 1.0f;

// One view sample's summand of eq. (10): Phi_l cos+(n_l.d) cos+(n_vs.(-d)) / D(l), l = x_vs - x_l,
// d = l/|l|, with D(l) = max(clamp^2, |l|^2), which generalises eq. (11) (clamp = 1) to any clamp
// distance. fluxLuminance: the VAL's flux luminance. The importance ignores occlusion. The pass
// averages the summands over its N_VS view samples (the 1/N_VS of eq. 10). 0 when x_vs = x_l.
VPLGI_FUNC float valImportance(float fluxLuminance, vec3 valPosition, vec3 valNormal, vec3 viewSamplePosition,
                               vec3 viewSampleNormal, float clampDistance)
{
    vec3 l = viewSamplePosition - valPosition;
    float distance2 = dot(l, l);
    if (!(distance2 > 0.0f)) return 0.0f;
    vec3 d = l * inversesqrt(distance2);
    float cosines = max(dot(valNormal, d), 0.0f) * max(-dot(viewSampleNormal, d), 0.0f);
    return fluxLuminance * cosines / max(clampDistance * clampDistance, distance2);
}

// --- Halton view samples (MATH 9.8) ---------------------------------------------------------------

// The radical inverse phi_b(index) (digits of index in base b mirrored after the point):
// phi_2(1, 2, 3) = 1/2, 1/4, 3/4; phi_3(1, 2, 3) = 1/3, 2/3, 1/9. A base below 2 gives 0 (the loop
// would never end).
VPLGI_FUNC float halton(uint index, uint base)
{
    if (base < 2u) return 0.0f;
    float inverseBase = 1.0f / float(base);
    float scale = inverseBase;
    float result = 0.0f;
    uint i = index;
    while (i > 0u) {
        result += scale * float(i % base);
        i /= base;
        scale *= inverseBase;
    }
    return result;
}

// View sample `sampleIndex` (1..N_VS; index 0 would be the corner (0, 0)) of a width x height view
// buffer: pixel (floor(phi_2(i) W), floor(phi_3(i) H)) (MATH 9.8).
VPLGI_FUNC ivec2 haltonViewPixel(uint sampleIndex, int width, int height)
{
    int x = int(halton(sampleIndex, 2u) * float(width));
    int y = int(halton(sampleIndex, 3u) * float(height));
    return ivec2(min(x, width - 1), min(y, height - 1));
}

// --- Occlusion by double projection (section 3; MATH 9.3, 9.10) ----------------------------------

// The proxy light's bounding-sphere radius from eq. (5)'s weighted VAL positions: sigma per axis from
// the weighted first and second moments of the offsets x_l - o from any reference point o (the pass
// should use the cache position: offsets keep the variance free of the cancellation that absolute
// open-world coordinates of 1 km would cause in float), the box (2 sigma_x, 2 sigma_y, 2 sigma_z),
// radius = its largest dimension 2 sigma_max (the full-width reading, file head). 0 without weight.
VPLGI_FUNC float proxySphereRadius(float weightSum, vec3 weightedOffsetSum, vec3 weightedSquaredOffsetSum)
{
    if (!(weightSum > 0.0f)) return 0.0f;
    vec3 mean = weightedOffsetSum / weightSum;
    vec3 variance = max(weightedSquaredOffsetSum / weightSum - mean * mean, vec3(0.0f));
    return 2.0f * sqrt(max(variance.x, max(variance.y, variance.z)));
}

// The frame of a receiving cache's unit disk: columns t, b (the disk's axes) and n.
VPLGI_FUNC mat3 occlusionFrame(vec3 cacheNormal)
{
    return lightViewBasis(cacheNormal);
}

// The sphere (centre at toCentre from the cache, radius r) on the cache's unit disk: xy the
// tangent-plane coordinates of the direction to the centre, z the covered area pi F with the sphere's
// form factor F = (r/d)^2 cos+(theta) (MATH 9.10, exact while the sphere is above the horizon; near
// the horizon it is the approximation the paper's method takes), at most pi. A cache inside the
// sphere (d <= r) is covered entirely: (0, 0, pi).
VPLGI_FUNC vec3 projectSphereToUnitDisk(vec3 toCentre, float radius, mat3 frame)
{
    float distance2 = dot(toCentre, toCentre);
    if (!(distance2 > radius * radius)) return vec3(0.0f, 0.0f, kPi);
    vec3 w = toCentre * inversesqrt(distance2);
    float formFactor = radius * radius / distance2 * max(dot(w, frame[2]), 0.0f);
    return vec3(dot(w, frame[0]), dot(w, frame[1]), min(kPi * formFactor, kPi));
}

// An occluding cache's disk (centre at toCentre from the receiving cache, unit normal, area) on the
// receiving cache's unit disk: xy as projectSphereToUnitDisk, z = pi F with diskFormFactor. The disk
// blocks light whichever side faces the receiver, so its cosine enters as |cos|. (0, 0, 0) at d = 0.
VPLGI_FUNC vec3 projectDiskToUnitDisk(vec3 toCentre, vec3 diskNormal, float diskArea, mat3 frame)
{
    float distance2 = dot(toCentre, toCentre);
    if (!(distance2 > 0.0f)) return vec3(0.0f);
    vec3 w = toCentre * inversesqrt(distance2);
    float formFactor = diskFormFactor(diskArea, abs(dot(diskNormal, w)), dot(w, frame[2]), distance2);
    return vec3(dot(w, frame[0]), dot(w, frame[1]), min(kPi * formFactor, kPi));
}

// The overlap area of the axis-aligned squares of equal area about two projected shapes (xy centre,
// z area): the product of the overlaps of their x and y intervals (half side sqrt(area)/2).
VPLGI_FUNC float squareOverlap(vec3 a, vec3 b)
{
    float halfA = 0.5f * sqrt(max(a.z, 0.0f));
    float halfB = 0.5f * sqrt(max(b.z, 0.0f));
    float overlapX = min(a.x + halfA, b.x + halfB) - max(a.x - halfA, b.x - halfB);
    float overlapY = min(a.y + halfA, b.y + halfB) - max(a.y - halfA, b.y - halfB);
    return max(overlapX, 0.0f) * max(overlapY, 0.0f);
}

// The occlusion cells (not in the paper; issue "LightSkin's indirect shadows", part 1). One sphere per
// proxy cannot stand for VALs spread over a broad floor: their weighted mean lies near the cache,
// the sphere (2 sigma) contains the cache, and nothing between them can occlude it (on the `board`
// scene occlusion changed nothing, docs/lightskin.md). So the VALs are also summed per cell of the
// receiving cache's unit disk (Nusselt's projection, the one the double projection uses): a
// central disk of radius 1/sqrt(5) and four quadrants around it, each 1/5 of the disk, i.e. of the
// cosine-weighted hemisphere (tests/cpu/test_lightskin_math.cpp checks the fifths). A cell's light
// goes to the unit disk directly, not through a sphere: its square is centred on the weighted mean
// of its VALs' disk coordinates with the area pi (2 sigma_max)^2 of their spread there (the proxy
// sphere's full-width reading, on the disk), an occluder blocks the part of the cell's light that
// lies behind it (occlusionBehind, from the mean and spread of the VALs' distances: a cell's VALs
// can span metres to tens of metres along its directions, and a sphere's near side would then be
// the cache itself), and the occluder-plane test takes the weighted mean position of the cell's
// VALs. The proxy's visibility is the radiance-weighted mean of its cells' visibilities.
// Measured against each cache's visibility traced with Embree (lightskin.tracedOcclusion,
// docs/lightskin.md "Occlusion"): the image mean within 1% of the traced one on the canyon at
// d_eps 2-4 m, 4-14% darker on the board scene; a hard near side (mean - 2 sigma, at least half the
// mean) left the board +25 points above the traced visibility and the canyon +19.
VPLGI_CONST float kOcclusionCentreRadius2 = 0.2f; // (1/sqrt 5)^2: the centre cell's radius squared

// The cell of unit direction w (from the cache) on the unit disk of `frame` (occlusionFrame): 0 the
// centre, 1-4 the quadrants around +t, +b, -t, -b. Directions below the horizon go to the quadrant of
// their projection too (their form factor is 0, so they only carry eq. (6)'s epsilon).
VPLGI_FUNC int occlusionCell(vec3 w, mat3 frame)
{
    float u = dot(w, frame[0]);
    float v = dot(w, frame[1]);
    if (u * u + v * v < kOcclusionCentreRadius2) return 0;
    if (abs(u) >= abs(v)) return u >= 0.0f ? 1 : 3;
    return v >= 0.0f ? 2 : 4;
}

// A cell's square on the unit disk from its VALs' weighted moments of the disk coordinates (u, v)
// (weightedSum: sum w (u, v); weightedSquaredSum: sum w (u^2, v^2)): xy the mean, z the area
// pi (2 sigma_max)^2, at most pi (VALs uniform on a disk of radius R on the unit disk have sigma R/2
// per axis, so the area is the disk's). (0, 0, 0) without weight.
VPLGI_FUNC vec3 occlusionCellSquare(float weightSum, vec2 weightedSum, vec2 weightedSquaredSum)
{
    if (!(weightSum > 0.0f)) return vec3(0.0f);
    vec2 mean = weightedSum / weightSum;
    vec2 variance = max(weightedSquaredSum / weightSum - mean * mean, vec2(0.0f));
    return vec3(mean, min(4.0f * kPi * max(variance.x, variance.y), kPi));
}

// The fraction of a light that lies behind an occluder at `distance` from the cache, the light's
// distance having mean depth.x and spread depth.y [m]: a logistic step (the normal distribution's
// CDF within 0.01), a hard step at depth.x when the spread is 0 (the paper's sphere: its near side).
VPLGI_FUNC float occlusionBehind(float distance, vec2 depth)
{
    if (!(depth.y > 0.0f)) return distance < depth.x ? 1.0f : 0.0f;
    return 1.0f / (1.0f + exp(1.702f * (distance - depth.x) / depth.y));
}

// The occluder-plane test's margin, relative to the distance from the cache to the occluder (1 mm at
// 1 m: far above float noise at open-world coordinates of 1 km, 1e-4 m).
VPLGI_CONST float kOccluderPlaneMargin = 1.0e-3f;

// A cell's depth for occlusionBehind from its VALs' weighted distances (weightedDistanceSum:
// sum w |v|, weightedDistance2Sum: sum w |v|^2): the mean and the standard deviation, held at 1e-3
// of the mean at least (one VAL: a step just at its distance). (0, 0) without weight.
VPLGI_FUNC vec2 occlusionCellDepth(float weightSum, float weightedDistanceSum, float weightedDistance2Sum)
{
    if (!(weightSum > 0.0f)) return vec2(0.0f);
    float mean = weightedDistanceSum / weightSum;
    float sigma = sqrt(max(weightedDistance2Sum / weightSum - mean * mean, 0.0f));
    return vec2(mean, max(sigma, 1e-3f * mean));
}

// Which caches can occlude the proxy light of the receiving cache: not the cache itself, in its
// upper hemisphere (n_c.(o - c) > 0) and closer to it than the proxy light (|o - c|^2 < proxyDistance2,
// the squared distance from the cache to the proxy light's position).
VPLGI_FUNC bool isOccluderCandidate(int cacheIndex, vec3 cachePosition, vec3 cacheNormal, int occluderIndex,
                                    vec3 occluderPosition, float proxyDistance2)
{
    vec3 toOccluder = occluderPosition - cachePosition;
    return occluderIndex != cacheIndex && dot(cacheNormal, toOccluder) > 0.0f &&
           dot(toOccluder, toOccluder) < proxyDistance2;
}

// occlusion = min(1, sum of squareOverlap(proxy, occluder) / the proxy's projected area); 0 when the
// proxy covers nothing (below the horizon). The proxy light's contribution is multiplied by
// 1 - occlusion.
VPLGI_FUNC float occlusionFromOverlap(float overlapSum, float proxyProjectedArea)
{
    if (!(proxyProjectedArea > 0.0f)) return 0.0f;
    return min(overlapSum / proxyProjectedArea, 1.0f);
}

// --- View culling (ours, not in the paper; issue "LightSkin's indirect shadows", part 4) -------------
// A pixel interpolates only caches closer than the search radius d_eps to its surface point
// (glsl/shared/light_cache_lookup.h), and that point lies in the camera's frustum; so a cache whose
// ball of radius d_eps misses the frustum serves no pixel, and its proxies (the proxy pass, the
// heaviest: every VAL for every cache) and its occlusion need not be made. It stays an occluder of
// the others. The frustum's six planes from clipFromWorld's rows (w +- x, w +- y, w +- z: clip
// space's -w <= x, y, z <= w), each normalised; the ball is kept when no plane has it wholly
// outside. kLightCacheCullMargin widens the ball: a surface point within a rounding of a plane must
// not cull its cache (the exact test is images bit-identical with and without culling).
VPLGI_CONST float kLightCacheCullMargin = 1.01f;
VPLGI_FUNC bool lightCacheInView(mat4 clipFromWorld, vec3 position, float radius)
{
    vec4 rowX = vec4(clipFromWorld[0][0], clipFromWorld[1][0], clipFromWorld[2][0], clipFromWorld[3][0]);
    vec4 rowY = vec4(clipFromWorld[0][1], clipFromWorld[1][1], clipFromWorld[2][1], clipFromWorld[3][1]);
    vec4 rowZ = vec4(clipFromWorld[0][2], clipFromWorld[1][2], clipFromWorld[2][2], clipFromWorld[3][2]);
    vec4 rowW = vec4(clipFromWorld[0][3], clipFromWorld[1][3], clipFromWorld[2][3], clipFromWorld[3][3]);
    vec4 p = vec4(position, 1.0f);
    float r = kLightCacheCullMargin * radius;
    bool inside = true;
    for (int i = 0; i < 6; ++i) {
        vec4 axis = i < 2 ? rowX : (i < 4 ? rowY : rowZ);
        vec4 plane = (i % 2 == 0) ? rowW + axis : rowW - axis;
        float length2 = dot(vec3(plane), vec3(plane));
        // Outside: the signed distance below -r, i.e. dot(plane, p) < -r |plane.xyz|.
        float distance = dot(plane, p);
        if (length2 > 0.0f && distance < 0.0f && distance * distance > r * r * length2) inside = false;
    }
    return inside;
}

VPLGI_SHARED_END

#endif // VPLGI_SHARED_LIGHTSKIN_H
