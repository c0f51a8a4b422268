#version 450 core
// Colours of glsl/passes/vpl_debug.vert's drawings: the scene in grey by height (brighter is
// higher; everything above uCutHeight is cut away), VPLs
// in their intensity scaled by uColorScale, the frustum in yellow.
#include "../shared/bindings.h"
#include "../lib/alpha_mask.glsl"

uniform int uMode;
uniform float uCutHeight;
uniform vec2 uHeightRange; // world y shown darkest .. brightest
uniform float uColorScale;

in vec3 vWorld;
in vec2 vTexcoord;
in vec2 vTexcoord1;
in float vAlpha;

layout(binding = kUnitBaseColor) uniform sampler2D uBaseColorTexture;
flat in vec3 vColor;

layout(location = 0) out vec4 outColor;

void main()
{
    if (uMode == 0) {
        if (vWorld.y > uCutHeight) discard;
        float t = clamp((vWorld.y - uHeightRange.x) / max(uHeightRange.y - uHeightRange.x, 1e-6), 0.0, 1.0);
        outColor = vec4(vec3(0.05 + 0.35 * t), 1.0);
        discardMasked(uBaseColorTexture, vTexcoord, vTexcoord1, vAlpha);
    } else if (uMode == 1) {
        outColor = vec4(vColor * uColorScale, 1.0);
    } else {
        outColor = vec4(vColor, 1.0);
    }
}
