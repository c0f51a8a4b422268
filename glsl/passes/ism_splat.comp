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
    vec3 position;       // world [m]
    uint normalSnorm2x16; // unit geometric normal, octEncode'd and packSnorm2x16'd
};

layout(std430, binding = kBindingISMPoints) readonly buffer Points {
    ISMPoint points[];
};

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

// Pass 0: the nearest distance wins. Pass 1 (planes): where this point's distance is the texel's,
// its packed normal, the smallest winning.
void splatTexel(ivec3 texel, float distance, uint packedNormal)
{
    if (uPass == 0)
        imageAtomicMin(uMaps, texel, floatBitsToUint(distance));
    else if (imageLoad(uMaps, texel).r == floatBitsToUint(distance))
        imageAtomicMin(uNormals, texel, packedNormal);
}

void main()
{
    int first = int(gl_GlobalInvocationID.x) * ISM_POINTS_PER_INVOCATION;
    int light = int(gl_GlobalInvocationID.y);
    if (first >= uPointsPerMap || light >= uCount) return;
    if (lightRecords[light * uStride + uValidVec4].w == 0.0) return;
    vec4 positionValid = lightRecords[light * uStride];
    // A light with extent (a VSGL) is not shadowed by its own footprint, the surface it stands for.
    float ownRadius = uRadius2Vec4 >= 0 ? uOwnRadius * sqrt(max(lightRecords[light * uStride + uRadius2Vec4].w, 0.0)) : 0.0;
    mat3 frame = lightViewBasis(lightRecords[light * uStride + 1].xyz);
    // The C++ side keeps lights * pointsPerMap below 2^32.
    uint start = (uint(light) * uint(uPointsPerMap)) % uint(uPointCount);
    int last = min(first + ISM_POINTS_PER_INVOCATION, uPointsPerMap);
    ivec2 tileOrigin = shadowAtlasTileFromIndex(light, uTilesPerRow).xy * uMapSize;
    for (int k = first; k < last; ++k) {
        ISMPoint record = points[(start + uint(k)) % uint(uPointCount)];
        vec3 point = record.position;
        ivec3 texel = ismSplatTexel(light, positionValid.xyz, frame, point, uMapSize, uTilesPerRow);
        if (texel.x < 0) continue;
        float pointDistance = length(point - positionValid.xyz);
        vec3 worldNormal = octDecode(unpackSnorm2x16(record.normalSnorm2x16));
        if (pointDistance < ownRadius &&
            (uOwnSurfaceOnly == 0 || ismOwnSurface(point - positionValid.xyz, worldNormal, frame[2], ownRadius)))
            continue;
        vec3 toPoint = transpose(frame) * (point - positionValid.xyz);
        float toPointLength = length(toPoint);
        vec3 normal = transpose(frame) * worldNormal;
        uint packedNormal = uPlanes != 0 ? ismPackNormal(worldNormal, point - positionValid.xyz) : kISMNoNormal;
        float centreDistance = uPlanes != 0 ? ismPlaneSplatDistance(toPoint, normal, kVPLNoOccluder,
                                                                    texel.xy - tileOrigin, uMapSize)
                                            : pointDistance;
        if (ismValid(centreDistance)) splatTexel(texel, centreDistance, packedNormal);
        if (!(uSplatRadius > 0.0)) continue;
        vec2 centre = ismMapPosition(toPoint / toPointLength, uMapSize);
        mat2 ellipse = ismSplatEllipse(toPoint, normal, uSplatRadius, uMapSize);
        vec2 extent = ismSplatExtent(ellipse, uSplatMaxExtent);
        ivec2 lo = ismSplatFirstTexel(centre, extent), hi = ismSplatLastTexel(centre, extent, uMapSize);
        for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x) {
                float distance = ismSplatDistance(toPoint, toPointLength, normal, uSplatRadius, centre, ellipse, ivec2(x, y), uMapSize);
                if (uPlanes != 0 && ismValid(distance))
                    distance = ismPlaneSplatDistance(toPoint, normal, uSplatRadius, ivec2(x, y), uMapSize);
                if (ismValid(distance)) splatTexel(ivec3(tileOrigin + ivec2(x, y), texel.z), distance, packedNormal);
            }
    }
}
