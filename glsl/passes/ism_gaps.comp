#version 450 core
// Imperfect shadow maps with planes, gap filling (gl/passes/imperfect_shadow_maps.h, glsl/shared/ism.h,
// ismGapCrossing): reads the splatted level 0 (distances and packed normals) and writes every texel
// into the copies, either as it was or, where two opposite neighbours saw a plane that its ray crosses
// before its own hit, that plane's distance along its direction and the nearer neighbour's normal.
// Invocation (t, light): texel t (row-major) of the light's tile.
#include "../shared/bindings.h"
#include "../shared/ism.h"
#include "../shared/normals.h"

layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(binding = kImageISMMaps, r32ui) readonly uniform uimage2DArray uMaps;
layout(binding = kImageISMNormals, r32ui) readonly uniform uimage2DArray uNormals;
layout(binding = kImageISMGapDistances, r32ui) writeonly uniform uimage2DArray uOutMaps;
layout(binding = kImageISMGapNormals, r32ui) writeonly uniform uimage2DArray uOutNormals;

layout(std430, binding = kBindingISMLights) readonly buffer Lights {
    vec4 lightRecords[]; // per light uStride vec4s: (position, -), (unit normal, -), ...
};

uniform int uCount;
uniform int uStride;
uniform int uMapSize;
uniform int uTilesPerRow;
uniform int uReach; // k = 1 .. uReach texels
uniform float uLift;

void main()
{
    int t = int(gl_GlobalInvocationID.x);
    int light = int(gl_GlobalInvocationID.y);
    if (t >= uMapSize * uMapSize || light >= uCount) return;
    ivec3 tile = shadowAtlasTileFromIndex(light, uTilesPerRow);
    ivec2 texel = ivec2(t % uMapSize, t / uMapSize);
    ivec3 address = ivec3(tile.xy * uMapSize + texel, tile.z);
    uint ownBits = imageLoad(uMaps, address).x;
    uint ownNormal = imageLoad(uNormals, address).x;
    mat3 frame = lightViewBasis(lightRecords[light * uStride + 1].xyz);
    vec3 dJ = frame * vplParaboloidTexelDirection(texel, uMapSize);
    float tJ = uintBitsToFloat(ownBits);
    float angle = ismPlaneTexelAngle(uMapSize);
    float best = kVPLNoOccluder;
    uint bestNormal = kISMNoNormal;
    for (int k = 1; k <= uReach; ++k)
        for (int pair = 0; pair < 4; ++pair) {
            ivec2 a = texel - ismGapOffset(pair, k), b = texel + ismGapOffset(pair, k);
            bool rimA = ismBeyondRim(a, uMapSize), rimB = ismBeyondRim(b, uMapSize);
            if (rimA != rimB) {
                // One side beyond the rim: the other alone (ismGapCrossingAtRim).
                ivec2 inside = rimA ? b : a;
                ivec3 addressIn = ivec3(tile.xy * uMapSize + inside, tile.z);
                uint wordIn = imageLoad(uNormals, addressIn).x;
                if (wordIn == kISMNoNormal) continue;
                float tIn = uintBitsToFloat(imageLoad(uMaps, addressIn).x);
                vec3 dIn = frame * vplParaboloidTexelDirection(inside, uMapSize);
                float s = ismGapCrossingAtRim(dJ, tJ, dIn, tIn, octDecode(unpackSnorm2x16(wordIn)), angle, float(k), uLift);
                if (s < best) {
                    best = s;
                    bestNormal = wordIn;
                }
                continue;
            }
            if (rimA || min(min(a.x, a.y), min(b.x, b.y)) < 0 || max(max(a.x, a.y), max(b.x, b.y)) >= uMapSize) continue;
            ivec3 addressA = ivec3(tile.xy * uMapSize + a, tile.z), addressB = ivec3(tile.xy * uMapSize + b, tile.z);
            uint wordA = imageLoad(uNormals, addressA).x, wordB = imageLoad(uNormals, addressB).x;
            if (wordA == kISMNoNormal || wordB == kISMNoNormal) continue;
            float tA = uintBitsToFloat(imageLoad(uMaps, addressA).x), tB = uintBitsToFloat(imageLoad(uMaps, addressB).x);
            vec3 nA = octDecode(unpackSnorm2x16(wordA)), nB = octDecode(unpackSnorm2x16(wordB));
            vec3 dA = frame * vplParaboloidTexelDirection(a, uMapSize), dB = frame * vplParaboloidTexelDirection(b, uMapSize);
            float s = ismGapCrossing(dJ, tJ, dA, tA, nA, dB, tB, nB, angle, float(k), uLift);
            if (s < best) {
                best = s;
                bestNormal = tA <= tB ? wordA : wordB;
            }
        }
    bool filled = ismValid(best);
    imageStore(uOutMaps, address, uvec4(filled ? floatBitsToUint(best) : ownBits));
    imageStore(uOutNormals, address, uvec4(filled ? bestNormal : ownNormal));
}
