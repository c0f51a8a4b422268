// Scenes vplgi generates itself (no external assets): canyon, caustics, cornell, cutout, furnace, glossy, maze,
// sealed (sealed-emissive, sealed-point, sealed-spot: the same rooms, one light type each), street.
#pragma once

#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace vplgi {

std::vector<std::string> builtinSceneNames();
bool isBuiltinScene(const std::string& name);
// Throws Error for an unknown name.
Scene makeBuiltinScene(const std::string& name);

// The furnace: the inside of a closed sphere of radius R with Lambertian albedo rho, an isotropic
// point light of intensity I0 at the centre (MATH.md section 3). Closed forms below.
struct FurnaceParams {
    float radius = 1.0f;            // R [m]
    float albedo = 0.5f;            // rho, grey
    float intensity = 3.14159265f;  // I0 [W/sr]; with rho = 0.5, R = 1: L_all = 1 (pbrt's test)
    int rings = 96;                 // latitude segments of the tessellation
    int segments = 192;             // longitude segments
};
Scene makeFurnace(const FurnaceParams& params);
// Radiance after exactly n reflections, L_n = rho^n I0 / (pi R^2).
double furnaceRadianceBounce(const FurnaceParams& params, int n);
// All bounces, L_all = rho I0 / (pi R^2 (1 - rho)).
double furnaceRadianceAll(const FurnaceParams& params);

// The caustics scene (VSGL Fig. 4): a near-mirror ring section (200 degrees of the inside of a
// vertical cylinder, open towards the light) on a light grey Lambertian floor, lit from above at an
// angle by the spot light "spot"; the ring focuses the light into a bright cardioid-like curve on
// the floor inside it. Cameras "default" (oblique) and "top" (straight down, image up = -z).
struct CausticsParams {
    float ringRadius = 1.0f;    // inner radius [m], centred on the origin; the whole layout scales with it
    float ringHeight = 0.6f;    // [m]
    float ringRoughness = 0.1f; // perceptual, metallic 1: alpha = 0.01 (VSGL's Phong exponent 65535 is
                                // alpha = sqrt(2 / 65537) = 0.0055); larger values blur the caustic
    int ringSegments = 48;      // along the arc
};
Scene makeCaustics(const CausticsParams& params);

} // namespace vplgi
