#version 450 core
// VSGL generation (VSGL section 3.2; gl/techniques/vsgl_technique.h): one light per invocation from
// a mipmapped RSM-layout target (glsl/shared/rsm.h), written as a VSGLight (glsl/shared/sg.h).
//  uMode 0, importance draws (the RSM): draw i's texel j with per-draw probability P_j
//    (passes/importance_sample.comp) reads a mip level trilinearly: filtered position E[x],
//    E[|x|^2] -> r^2 = 2 (E|x|^2 - |E x|^2) (MATH.md 5.3), normal, diffuse and specular
//    coefficients, the Toksvig lobe (4.8). Two footprints (uFootprint, vsgl.footprint):
//    - texel, the paper's reading: level h = 1/2 log2(k / (N P_j)) (5.2), flux Phi_h / (N P_j).
//    - cell (not in the paper, our default): level h = the coarsest mip cell around j that holds
//      at most k expected draws (N P_cell <= k; the paper's criterion on the cell's own probability),
//      flux Phi_cell / (N P_cell), both read from that leaf cell itself (texelFetch).
//    Why (docs/vsgl.md): the estimator's expectation is sum_j P_j Phi_h(j) / q(j). With q = P_j it
//    is sum_j Phi_h(j), which over-counts bright texels next to dim ones (a dim texel's large
//    footprint reaches into its bright neighbours; measured over 8 seeds in docs/conformance.md,
//    "VSGL's footprints over 8 seeds"). Leaf cells are a partition (the criterion is monotone up
//    the mip chain, so every texel of a leaf finds that leaf), so with q = P_cell the expectation
//    is sum_cells P_cell Phi_cell / P_cell = Phi, exact (tests/image/test_vsgl_technique.cpp sums
//    it over every texel of a concentrated importance map). An earlier version read both bilinearly
//    at the leaf's level (smooth in the draw, but -6% to -47% where importance is concentrated:
//    issue "VSGL made exact"). Position, radius, normal and lobes stay bilinear at the leaf's level:
//    they move smoothly with the draw and carry no 1/P; with uLeafReads 2 (vsgl.leafReads = surface,
//    ours, the default) only over the neighbouring cells on the leaf's own surface (surfaceBlend),
//    and with uLeafEdges (vsgl.leafEdges) no leaf holds a geometric edge (leafHasEdge; docs/vsgl.md,
//    "Leaves stop at edges"). Leaves stop at level uMaxLeaf (vsgl.maxLeaf,
//    ours, default 2 = 4x4 texels): the cells of one level are a partition too, so the cap costs no
//    bias, and it keeps a leaf from carrying, say, a sunlit roof's flux into the room below it
//    (docs/vsgl.md, "VSGL made exact": sealed room +28% uncapped, -4% capped).
//  uMode 1, the same draws as VPLs (baseline vpl-brsm, eq. 1): level 0, no filtering, r = 0.
//  uMode 2, a grid (the view lights): every texel of level uLevel is a light, flux 4^L Phi_L.
#include "shared/bindings.h"
#define VPLGI_IMPORTANCE_TYPES_ONLY
#include "shared/importance.h"
#include "shared/rsm.h"
#include "shared/sg.h"
#include "shared/normals.h"

layout(local_size_x = 64) in;

layout(binding = kUnitRSMSource) uniform sampler2DArray uSource[kRSMAttachmentCount];
layout(binding = kUnitImportanceMips) uniform sampler2D uImportanceMips; // the draws' importance map, box mips
layout(std430, binding = kBindingImportanceSamples) readonly buffer Samples { ImportanceSample samples[]; };
layout(std430, binding = kBindingVSGLights) writeonly buffer Lights { VSGLight lights[]; };

uniform int uMode;
uniform int uCount;        // lights to write
uniform int uSize;         // level-0 edge of one layer [texels]
uniform int uLevels;       // mip levels
uniform int uMaxLeaf;      // uFootprint 1: the coarsest leaf level (vsgl.maxLeaf; >= uLevels - 1: none)
uniform int uLevel;        // uMode 2: the level whose texels are lights
uniform float uSmoothness; // k
uniform int uFootprint;    // uMode 0: 0 texel (the paper's reading), 1 cell (see the file head)
uniform int uLayers;       // uMode 0: RSM layers (side by side in the importance map)
uniform int uLeafEdges;    // uFootprint 1: 1 = a leaf holds no geometric edge (vsgl.leafEdges, see leafHasEdge)
uniform int uLeafReads;    // uFootprint 1: position, normal and lobes at the leaf's level: 0 bilinear, 1 the leaf cell's own, 2 bilinear over the leaf's surface (surfaceBlend)

const int kLeafEdgeMaxLevel = 5; // leafHasEdge scans cells of at most 32x32 texels

// The geometric normal n_g of a level-0 RSM texel (octahedral in the flux's and diffuse's w).
vec3 geometricNormal(ivec3 texel)
{
    return octDecode(vec2(texelFetch(uSource[kRSMFlux], texel, 0).w, texelFetch(uSource[kRSMDiffuse], texel, 0).w));
}

// Two neighbouring level-0 texels on different surfaces: both covered, and their geometric normals
// and positions apart by rsmSurfacesDiffer (shared/rsm.h). Not in the paper.
bool edgeBetween(ivec3 a, ivec3 b)
{
    if (!(texelFetch(uSource[kRSMNormal], a, 0).w > 0.0) || !(texelFetch(uSource[kRSMNormal], b, 0).w > 0.0)) return false;
    vec3 d = texelFetch(uSource[kRSMPosition], b, 0).xyz - texelFetch(uSource[kRSMPosition], a, 0).xyz;
    return rsmSurfacesDiffer(geometricNormal(a), geometricNormal(b), d);
}

// vsgl.leafEdges (ours, not in the paper): does the level-l cell at `cell` (in level-l texels of
// `layer`) hold two neighbouring texels on different surfaces? Every pair of neighbours inside the
// cell is tested, so a cell with an edge has parents with that edge: the property is monotone up the
// chain, as N P_cell <= k is, and the leaves stay a partition. A footprint across an edge would put
// a light between two surfaces with the spread of both (docs/vsgl.md, "Leaves stop at edges").
bool leafHasEdge(ivec2 cell, int l, int layer)
{
    // Cells above 32x32 texels count as holding an edge (monotone too): the scan of a level-l cell
    // is 4^l texels, and llvmpipe ends an invocation's loops after 65535 iterations in all
    // (gl/api/limits.h); with these, at most 1364 + 3 x 1024 (surfaceBlend's neighbours). Only
    // vsgl.maxLeaf > 5 reaches it.
    if (l > kLeafEdgeMaxLevel) return true;
    int side = 1 << l;
    ivec2 origin = cell * side;
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            ivec3 t = ivec3(origin + ivec2(x, y), layer);
            if (x + 1 < side && edgeBetween(t, t + ivec3(1, 0, 0))) return true;
            if (y + 1 < side && edgeBetween(t, t + ivec3(0, 1, 0))) return true;
        }
    return false;
}

// uFootprint 1: the leaf cell at the light's level (RSM layer texels), whose flux is read exactly;
// uLeafReads 2: the bilinear cells around the draw at that level with their weights, those on
// another surface than the leaf at weight 0.
ivec2 gLeafCell = ivec2(-1);
ivec2 gCells[4];
vec4 gWeights = vec4(0.0);

// uLeafReads 2: the bilinear blend GL's textureLod makes at `level` (clamp to edge), less the cells
// that hold no surface, hold an edge themselves (leafHasEdge), or lie on another surface than the
// leaf cell by their means (rsmSurfacesDiffer, as edgeBetween); the rest renormalised. The leaf cell keeps its weight (>= 1/4: the draw
// lies in it).
void surfaceBlend(vec2 uv, int level, int layer)
{
    int n = max(uSize >> level, 1);
    vec2 t = uv * float(n) - 0.5;
    ivec2 i0 = ivec2(floor(t));
    vec2 f = t - floor(t);
    vec4 w = vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y);
    vec3 leafPosition = texelFetch(uSource[kRSMPosition], ivec3(gLeafCell, layer), level).xyz;
    vec3 leafNormal = normalize(texelFetch(uSource[kRSMNormal], ivec3(gLeafCell, layer), level).xyz);
    for (int k = 0; k < 4; ++k) {
        gCells[k] = clamp(i0 + ivec2(k & 1, k >> 1), ivec2(0), ivec2(n - 1));
        if (gCells[k] == gLeafCell) continue;
        vec4 normal = texelFetch(uSource[kRSMNormal], ivec3(gCells[k], layer), level);
        vec3 d = texelFetch(uSource[kRSMPosition], ivec3(gCells[k], layer), level).xyz - leafPosition;
        bool same = normal.w > 0.0 && dot(normal.xyz, normal.xyz) > 0.0 &&
                    !rsmSurfacesDiffer(leafNormal, normalize(normal.xyz), d) &&
                    !leafHasEdge(gCells[k], level, layer); // a cell holding part of another surface is not one
        if (!same) w[k] = 0.0;
    }
    gWeights = w / (w.x + w.y + w.z + w.w);
}

vec4 fetch(int a, vec3 uvLayer, float level, bool filtered, ivec3 texel)
{
    if (uLeafReads == 1 && gLeafCell.x >= 0) return texelFetch(uSource[a], ivec3(gLeafCell, texel.z), int(level));
    if (uLeafReads == 2 && gLeafCell.x >= 0) {
        vec4 sum = vec4(0.0);
        for (int k = 0; k < 4; ++k)
            if (gWeights[k] > 0.0) sum += gWeights[k] * texelFetch(uSource[a], ivec3(gCells[k], texel.z), int(level));
        return sum;
    }
    return filtered ? textureLod(uSource[a], uvLayer, level) : texelFetch(uSource[a], texel, int(level));
}

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uCount) return;
    VSGLight light;
    light.positionRadius2 = vec4(0.0);
    light.normalValid = vec4(0.0);
    light.flux = vec4(0.0);
    light.diffuse = vec4(0.0);
    light.specular = vec4(0.0);
    light.lobe = vec4(0.0, 0.0, 1.0, 0.0);
    light.geometric = vec4(0.0);

    ivec3 texel;
    float level = 0.0;
    float fluxScale;
    bool filtered = false;
    if (uMode == 2) {
        int edge = max(uSize >> uLevel, 1);
        texel = ivec3(i % edge, i / edge, 0);
        level = float(uLevel);
        fluxScale = exp2(2.0 * float(uLevel)); // level-L texels are means over 4^L level-0 texels
    } else {
        ImportanceSample s = samples[i];
        if (s.x < 0 || !(s.probability > 0.0)) {
            lights[i] = light;
            return;
        }
        texel = ivec3(s.x % uSize, s.y, s.x / uSize); // the importance map holds the layers side by side
        fluxScale = 1.0 / (float(uCount) * s.probability); // Phi / (N P_j): unbiased for Phi_j, not for a footprint
        if (uMode == 0) {
            filtered = true;
            if (uFootprint == 0) {
                level = vsglMipLevel(float(uCount), s.probability, uSmoothness, uLevels); // MATH.md 5.2
            } else {
                // The leaf: P_cell = 4^l x the mean importance at level l / the total (I_j / P_j).
                float toProbability = s.probability / s.importance;
                int leaf = 0;
                for (int l = 1; l < min(uLevels, uMaxLeaf + 1); ++l) {
                    float cell = texelFetch(uImportanceMips, ivec2(s.x, s.y) >> l, l).r * toProbability * exp2(2.0 * float(l));
                    if (!(float(uCount) * cell <= uSmoothness)) break;
                    if (uLeafEdges != 0 && leafHasEdge(ivec2(texel.xy) >> l, l, texel.z)) break;
                    leaf = l;
                }
                level = float(leaf);
                ivec2 importanceCell = ivec2(s.x, s.y) >> leaf;
                // The leaf's probability and flux are the cell's box means times 4^leaf: the
                // factors cancel in Phi_cell / (N P_cell).
                float probability = texelFetch(uImportanceMips, importanceCell, leaf).r * toProbability;
                if (probability > 0.0) fluxScale = 1.0 / (float(uCount) * probability);
                gLeafCell = ivec2(texel.xy) >> leaf; // the same cell in the RSM layer
            }
        }
    }
    vec3 uvLayer = vec3((vec2(texel.xy) + 0.5) / float(uSize), float(texel.z));
    if (uLeafReads == 2 && gLeafCell.x >= 0) surfaceBlend(uvLayer.xy, int(level), texel.z);
    vec4 position = fetch(kRSMPosition, uvLayer, level, filtered, texel);
    vec4 normal = fetch(kRSMNormal, uvLayer, level, filtered, texel);
    vec4 flux = gLeafCell.x >= 0 ? texelFetch(uSource[kRSMFlux], ivec3(gLeafCell, texel.z), int(level))
                                : fetch(kRSMFlux, uvLayer, level, filtered, texel);
    if (!(normal.w > 0.0) || !(flux.r + flux.g + flux.b > 0.0) || dot(normal.xyz, normal.xyz) == 0.0) {
        lights[i] = light;
        return;
    }
    vec4 diffuse = fetch(kRSMDiffuse, uvLayer, level, filtered, texel);
    vec4 specular = fetch(kRSMSpecular, uvLayer, level, filtered, texel);
    vec4 lobe = fetch(kRSMLobe, uvLayer, level, filtered, texel);
    // The filtered values are means weighted by flux over the covered texels (rsm_pass.h); the
    // radius from the positional variance (5.3), 0 for a point light (uMode 1).
    float variance = max(position.w - dot(position.xyz, position.xyz), 0.0);
    vec3 axis;
    float sharpness;
    toksvigDecode(lobe.xyz, axis, sharpness);
    light.positionRadius2 = vec4(position.xyz, uMode == 1 ? 0.0 : 2.0 * variance);
    // The footprint's diffuse emission towards w is sum_k Phi_k rho_k/pi cos(n_k, w) = Phi rho/pi
    // (n_mean . w): the mean normal keeps its length (|n_mean| < 1 where normals spread: normal maps,
    // corners), which the unit normal of eq. (3)'s cosine drops, so the diffuse coefficient takes it
    // (not in the paper; an earlier version without it was biased high in the normal-mapped glossy
    // room; docs/vsgl.md). The specular lobe carries its own exit cosine (sg.h ggxReflectionLobe),
    // so |n_mean| is on the diffuse lobe only.
    float normalLength = min(length(normal.xyz), 1.0);
    light.normalValid = vec4(normal.xyz / length(normal.xyz), 1.0);
    light.flux = vec4(flux.rgb * fluxScale, float(texel.z)); // w: the layer (RSMLayerLight)
    // Numeric guard: a draw of (nearly) zero probability makes 1 / (N P_j) overflow, and an RSM texel
    // can hold an overflowed flux (half floats end at 65504); such a light would be infinitely
    // strong, and inf * 0 poisons every pixel it reaches with NaN. It is dropped (left invalid).
    if (any(isnan(light.flux.rgb)) || any(isinf(light.flux.rgb)) || any(isnan(light.positionRadius2)) ||
        any(isinf(light.positionRadius2))) {
        lights[i] = VSGLight(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0, 0.0, 1.0, 0.0), vec4(0.0));
        return;
    }
    light.diffuse = vec4(diffuse.rgb * normalLength, specular.w);
    light.specular = vec4(specular.rgb, lobe.w);
    light.lobe = vec4(axis, sharpness);
    // A VPL (level 0) carries its triangle's normal from the RSM (flux.w, diffuse.w); a filtered
    // footprint has no single triangle: its mean normal.
    light.geometric = vec4(uMode == 1 ? octDecode(vec2(flux.w, diffuse.w)) : light.normalValid.xyz, 0.0);
    lights[i] = light;
}
