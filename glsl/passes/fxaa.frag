#version 450 core
// FXAA (T. Lottes, "FXAA", NVIDIA white paper, 2009; the "quality" variant): renderer.antialias on
// the display image, after tone mapping (it works on the sRGB-encoded bytes, as FXAA is meant to).
// Not in any of the three papers; the measured radiance (EXR, metrics) never passes through it.
//  1. Local contrast: the luma range over the pixel and its 4 neighbours. Below the threshold the
//     pixel is written unchanged, so interiors keep their exact bytes.
//  2. Edge orientation from second differences over the 3x3 neighbourhood; the side of the edge
//     with the steeper gradient.
//  3. Search along the edge, half a pixel towards that side, in both directions, until the luma
//     leaves the edge's mean by a quarter of its gradient: the pixel's position along the edge
//     gives how far to move the lookup across it (the nearer end decides).
//  4. A sub-pixel term for single-pixel features (the 3x3 mean against the centre).
//  5. One bilinear lookup moved across the edge by the larger of the two offsets.
#include "../shared/bindings.h"

layout(binding = kUnitAntialiasInput) uniform sampler2D uInput; // the tone-mapped display (bilinear, clamped)

layout(location = 0) out vec4 outDisplay;

const float kEdgeThreshold = 0.125;     // the white paper's "high quality" contrast threshold (1/8)
const float kEdgeThresholdMin = 0.0625; // and its floor for dark regions (1/16)
const float kSubpixelQuality = 0.75;    // its default sub-pixel amount
const int kSearchSteps = 12;
// Step lengths of the search, in pixels, growing as the edge gets longer.
const float kSearchStep[kSearchSteps] = float[](1.0, 1.0, 1.0, 1.0, 1.0, 1.5, 2.0, 2.0, 2.0, 2.0, 4.0, 8.0);

float luma(vec3 c)
{
    return dot(c, vec3(0.299, 0.587, 0.114));
}

float lumaAt(ivec2 p)
{
    return luma(texelFetch(uInput, clamp(p, ivec2(0), textureSize(uInput, 0) - 1), 0).rgb);
}

float lumaAt(vec2 uv)
{
    return luma(textureLod(uInput, uv, 0.0).rgb);
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 texel = 1.0 / vec2(textureSize(uInput, 0));
    vec2 uv = (vec2(p) + 0.5) * texel;
    vec4 centre = texelFetch(uInput, p, 0);

    // 1. Local contrast.
    float c = luma(centre.rgb);
    float n = lumaAt(p + ivec2(0, 1)), s = lumaAt(p + ivec2(0, -1));
    float e = lumaAt(p + ivec2(1, 0)), w = lumaAt(p + ivec2(-1, 0));
    float lowest = min(c, min(min(n, s), min(e, w)));
    float highest = max(c, max(max(n, s), max(e, w)));
    float range = highest - lowest;
    if (range < max(kEdgeThresholdMin, highest * kEdgeThreshold)) {
        outDisplay = centre;
        return;
    }

    // 2. Orientation: an edge along x (horizontal) changes across y.
    float ne = lumaAt(p + ivec2(1, 1)), nw = lumaAt(p + ivec2(-1, 1));
    float se = lumaAt(p + ivec2(1, -1)), sw = lumaAt(p + ivec2(-1, -1));
    float acrossY = 2.0 * abs(n + s - 2.0 * c) + abs(ne + se - 2.0 * e) + abs(nw + sw - 2.0 * w);
    float acrossX = 2.0 * abs(e + w - 2.0 * c) + abs(ne + nw - 2.0 * n) + abs(se + sw - 2.0 * s);
    bool horizontal = acrossY >= acrossX;
    float before = horizontal ? s : w; // the neighbours across the edge
    float after = horizontal ? n : e;
    float gradientBefore = abs(before - c), gradientAfter = abs(after - c);
    bool towardsBefore = gradientBefore >= gradientAfter;
    float across = horizontal ? texel.y : texel.x; // one pixel across the edge, signed towards its side
    if (towardsBefore) across = -across;
    float edgeMean = 0.5 * (c + (towardsBefore ? before : after));
    float threshold = 0.25 * max(gradientBefore, gradientAfter);

    // 3. Search along the edge, half a pixel towards its side.
    vec2 onEdge = uv + (horizontal ? vec2(0.0, 0.5 * across) : vec2(0.5 * across, 0.0));
    vec2 along = horizontal ? vec2(texel.x, 0.0) : vec2(0.0, texel.y);
    vec2 end1 = onEdge - along, end2 = onEdge + along;
    float delta1 = lumaAt(end1) - edgeMean, delta2 = lumaAt(end2) - edgeMean;
    bool done1 = abs(delta1) >= threshold, done2 = abs(delta2) >= threshold;
    for (int i = 1; i < kSearchSteps && !(done1 && done2); ++i) {
        if (!done1) {
            end1 -= along * kSearchStep[i];
            delta1 = lumaAt(end1) - edgeMean;
            done1 = abs(delta1) >= threshold;
        }
        if (!done2) {
            end2 += along * kSearchStep[i];
            delta2 = lumaAt(end2) - edgeMean;
            done2 = abs(delta2) >= threshold;
        }
    }
    float distance1 = horizontal ? uv.x - end1.x : uv.y - end1.y;
    float distance2 = horizontal ? end2.x - uv.x : end2.y - uv.y;
    bool nearer1 = distance1 < distance2;
    float edgeOffset = 0.5 - min(distance1, distance2) / (distance1 + distance2);
    // Only when the luma at the nearer end moves away from the centre's side of the mean (else the
    // pixel is at the far end of a step and stays).
    bool centreBelow = c < edgeMean;
    bool moves = ((nearer1 ? delta1 : delta2) < 0.0) != centreBelow;
    float offset = moves ? edgeOffset : 0.0;

    // 4. Sub-pixel aliasing.
    float mean3x3 = (2.0 * (n + s + e + w) + ne + nw + se + sw) / 12.0;
    float subpixel = clamp(abs(mean3x3 - c) / range, 0.0, 1.0);
    float eased = (3.0 - 2.0 * subpixel) * subpixel * subpixel;
    offset = max(offset, eased * eased * kSubpixelQuality);

    // 5. One lookup moved across the edge.
    outDisplay = textureLod(uInput, uv + (horizontal ? vec2(0.0, offset * across) : vec2(offset * across, 0.0)), 0.0);
}
