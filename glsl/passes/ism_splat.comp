#version 450 core
// Imperfect shadow maps (gl/passes/imperfect_shadow_maps.h): splats each light's run of scene
// points into its paraboloid map, nearest distance wins: the texel of the point's direction, and with
// uSplatRadius > 0 every texel whose centre lies in the image of the point's disk (the footprint
// splat of glsl/shared/ism.h, ours); with uPlanes a second dispatch (uPass 1) writes the normal of
// the point that won each texel (glsl/shared/ism.h, planes). Invocation (j, light):
// points k = j * ISM_POINTS_PER_INVOCATION ... of the light's run, point (start + k) mod P of the point
// set, start = light * uPointsPerMap mod P (several points per invocation share the light's frame:
// 25% faster on llvmpipe than one each). The distance is
// positive, so its float bits order like the floats and imageAtomicMin on them is a depth test whose
// result does not depend on the order the invocations run in.
#include "../shared/bindings.h"
#include "../shared/ism.h"
#include "../shared/normals.h"

#ifndef ISM_POINTS_PER_INVOCATION
#define ISM_POINTS_PER_INVOCATION 8
#endif
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(binding = kImageISMMaps, r32ui) uniform uimage2DArray uMaps;
layout(binding = kImageISMNormals, r32ui) uniform uimage2DArray uNormals; // uPass 1: the winners' packed normals

struct ISMPoint {
    vec3 position;        // world [m]
    uint normalSnorm2x16; // unit geometric normal, octEncode'd and packSnorm2x16'd
    uint reach;           // glsl/shared/ism.h, ismWithinReach (kISMReachFull without the reach)
};

// Per point uPointStride uvec4s: (the position's bits, the packed normal), then, only with the reach
// (stride 2), (the reach profile, -, -, -): 16 bytes a point without it.
layout(std430, binding = kBindingISMPoints) readonly buffer Points {
    uvec4 pointWords[];
};
uniform int uPointStride;

ISMPoint loadPoint(uint index)
{
    uvec4 head = pointWords[index * uint(uPointStride)];
    ISMPoint point;
    point.position = uintBitsToFloat(head.xyz);
    point.normalSnorm2x16 = head.w;
    point.reach = uPointStride > 1 ? pointWords[index * uint(uPointStride) + 1u].x : kISMReachFull;
    return point;
}

layout(std430, binding = kBindingISMLights) readonly buffer Lights {
    vec4 lightRecords[]; // per light uStride vec4s: (position, -), (unit normal, -), ...; w of vec4 uValidVec4: valid
};

uniform int uCount;
uniform int uStride;
uniform int uValidVec4; // the record's vec4 whose w is 0 for an empty record
uniform int uPointsPerMap;
uniform int uPointCount;
uniform int uMapSize;
uniform int uTilesPerRow;
uniform float uSplatRadius;    // world radius of each point's disk [m]; 0: one-texel points
uniform float uSplatMaxExtent;
uniform int uRadius2Vec4;      // the record's vec4 whose w is the light's radius^2 [m^2]; -1: point lights
uniform float uOwnRadius;      // points within this x the light's radius are not splatted
uniform int uOwnSurfaceOnly;   // 1: of the points within the own radius, only those of the light's own surface are left out
uniform int uPlanes;           // 1: the centre texel holds the distance to the point's plane (glsl/shared/ism.h, planes)
uniform int uPass;             // 0: distances (nearest wins); 1: normals where the point's distance won the texel
uniform float uReachMargin;    // [m] the reach's margin (ismWithinReach)

// Pass 0: the nearest distance wins. Pass 1 (planes): where this point's distance is the texel's,
// its packed normal, the smallest winning.
void splatTexel(ivec3 texel, float distance, uint packedNormal)
{
    if (uPass == 0)
        imageAtomicMin(uMaps, texel, floatBitsToUint(distance));
    else if (imageLoad(uMaps, texel).r == floatBitsToUint(distance))
        imageAtomicMin(uNormals, texel, packedNormal);
}

layout(std430, binding = kBindingISMNearIndices) readonly buffer NearIndices {
    uint nearIndices[]; // the points' indices, slot by slot
};
layout(std430, binding = kBindingISMNearSlots) readonly buffer NearSlots {
    uint nearSlots[]; // slot s's indices: nearSlots[s] .. nearSlots[s + 1] - 1
};
uniform int uRunInvocations; // invocations x < this splat the light's run; the next 27 its near field's cells
uniform int uNearSlots;      // hash slots; 0: no near field
uniform float uNearRadius;   // [m]
uniform float uNearSplatRadius;
uniform vec3 uNearOrigin;
uniform float uNearInverseEdge; // 1 / the grid cells' edge, a hair over uNearRadius (ismNearCell)

// One point into the light's map: its own texel, and with radius > 0 its disk's texels.
void splatPoint(ISMPoint record, int light, vec3 lightPosition, mat3 frame, float ownRadius, ivec2 tileOrigin,
                float radius)
{
    vec3 point = record.position;
    ivec3 texel = ismSplatTexel(light, lightPosition, frame, point, uMapSize, uTilesPerRow);
    if (texel.x < 0) return;
    float pointDistance = length(point - lightPosition);
    vec3 worldNormal = octDecode(unpackSnorm2x16(record.normalSnorm2x16));
    if (pointDistance < ownRadius &&
        (uOwnSurfaceOnly == 0 || ismOwnSurface(point - lightPosition, worldNormal, frame[2], ownRadius)))
        return;
    vec3 toPoint = transpose(frame) * (point - lightPosition);
    float toPointLength = length(toPoint);
    vec3 normal = transpose(frame) * worldNormal;
    uint packedNormal = uPlanes != 0 ? ismPackNormal(worldNormal, point - lightPosition) : kISMNoNormal;
    float centreDistance = uPlanes != 0 ? ismPlaneSplatDistance(toPoint, normal, kVPLNoOccluder,
                                                                texel.xy - tileOrigin, uMapSize)
                                        : pointDistance;
    if (ismValid(centreDistance)) splatTexel(texel, centreDistance, packedNormal);
    if (!(radius > 0.0)) return;
    // The reach: only a point whose disk is cut somewhere tests its texels (glsl/shared/ism.h).
    bool cut = uPlanes != 0 && record.reach != kISMReachFull; // without the reach every record is whole
    vec3 reachAxis0 = vec3(0.0), reachAxis1 = vec3(0.0);
    if (cut) ismReachAxes(worldNormal, frame, reachAxis0, reachAxis1);
    vec2 centre = ismMapPosition(toPoint / toPointLength, uMapSize);
    mat2 ellipse = ismSplatEllipse(toPoint, normal, radius, uMapSize);
    vec2 extent = ismSplatExtent(ellipse, uSplatMaxExtent);
    ivec2 lo = ismSplatFirstTexel(centre, extent), hi = ismSplatLastTexel(centre, extent, uMapSize);
    for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
            float distance = ismSplatDistance(toPoint, toPointLength, normal, radius, centre, ellipse, ivec2(x, y), uMapSize);
            if (uPlanes != 0 && ismValid(distance)) {
                distance = ismPlaneSplatDistance(toPoint, normal, radius, ivec2(x, y), uMapSize);
                // The meeting point's offset from the point (light frame) against the reach.
                if (cut && ismValid(distance) &&
                    !ismWithinReach(record.reach, distance * vplParaboloidTexelDirection(ivec2(x, y), uMapSize) - toPoint,
                                    reachAxis0, reachAxis1, uSplatRadius, uReachMargin))
                    distance = kVPLNoOccluder;
            }
            if (ismValid(distance)) splatTexel(ivec3(tileOrigin + ivec2(x, y), texel.z), distance, packedNormal);
        }
}

void main()
{
    int invocation = int(gl_GlobalInvocationID.x);
    int light = int(gl_GlobalInvocationID.y);
    if (light >= uCount || invocation >= uRunInvocations + (uNearSlots > 0 ? 27 : 0)) return;
    if (lightRecords[light * uStride + uValidVec4].w == 0.0) return;
    vec4 positionValid = lightRecords[light * uStride];
    // A light with extent (a VSGL) is not shadowed by its own footprint, the surface it stands for.
    float ownRadius = uRadius2Vec4 >= 0 ? uOwnRadius * sqrt(max(lightRecords[light * uStride + uRadius2Vec4].w, 0.0)) : 0.0;
    mat3 frame = lightViewBasis(lightRecords[light * uStride + 1].xyz);
    ivec2 tileOrigin = shadowAtlasTileFromIndex(light, uTilesPerRow).xy * uMapSize;
    if (invocation >= uRunInvocations) {
        // Near field: the points of cell (light's cell + offset) within uNearRadius of the light.
        int c = invocation - uRunInvocations;
        ivec3 cell = ismNearCell(positionValid.xyz, uNearOrigin, uNearInverseEdge) + ivec3(c % 3, (c / 3) % 3, c / 9) - ivec3(1);
        uint slot = ismNearSlot(cell, uint(uNearSlots));
        for (uint k = nearSlots[slot]; k < nearSlots[slot + 1u]; ++k) {
            ISMPoint record = loadPoint(nearIndices[k]);
            if (!(length(record.position - positionValid.xyz) < uNearRadius)) continue;
            if (ismNearCell(record.position, uNearOrigin, uNearInverseEdge) != cell) continue; // another cell of the slot
            splatPoint(record, light, positionValid.xyz, frame, ownRadius, tileOrigin, uNearSplatRadius);
        }
        return;
    }
    int first = invocation * ISM_POINTS_PER_INVOCATION;
    if (first >= uPointsPerMap) return;
    // The C++ side keeps lights * pointsPerMap below 2^32.
    uint start = (uint(light) * uint(uPointsPerMap)) % uint(uPointCount);
    int last = min(first + ISM_POINTS_PER_INVOCATION, uPointsPerMap);
    for (int k = first; k < last; ++k)
        splatPoint(loadPoint((start + uint(k)) % uint(uPointCount)), light, positionValid.xyz, frame, ownRadius,
                   tileOrigin, uSplatRadius);
}
