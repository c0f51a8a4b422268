#version 450 core
// Resamples the three hemisphere-cube faces of a batch of VPLs into their paraboloid maps
// (gl/passes/vpl_shadow_maps.h, MATH.md 6.4). Invocation (x, y, i): texel (x, y) of the map of
// batch item i. The texel's direction in the VPL's light frame (paraboloid inverse, rim-clamped)
// -> world -> cube frame -> the face it leaves through -> that face's nearest texel -> distance.
#include "../shared/bindings.h"
#include "../shared/light_view.h"
#include "../shared/shadow_atlas.h"
#include "../shared/vpl.h"

layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

layout(binding = kUnitShadowAtlas) uniform sampler2DArray uFaces;
layout(binding = kImageVPLShadowMaps, r32f) writeonly uniform image2DArray uMaps;

layout(std430, binding = kBindingVPLBatch) readonly buffer Batch {
    VPLBatchItem batch[];
};

uniform int uMapSize;
uniform int uMapTilesPerRow;
uniform int uFaceSize;
uniform int uFaceTilesPerRow;
uniform float uZNear;
uniform float uZFar;

void main()
{
    ivec3 id = ivec3(gl_GlobalInvocationID);
    if (id.x >= uMapSize || id.y >= uMapSize || id.z >= batch.length()) return;
    VPLBatchItem item = batch[id.z];
    vec3 n = item.normal.xyz;
    vec3 directionLight = vplParaboloidTexelDirection(id.xy, uMapSize);
    vec3 direction = lightViewBasis(n) * directionLight;
    vec3 directionCube = transpose(lightViewHemisphereBasis(n)) * direction;
    int face = lightViewHemisphereFace(directionCube);
    vec2 faceUV = lightViewHemisphereFaceUV(directionCube, face);
    ivec2 faceTexel = clamp(ivec2(floor(faceUV * float(uFaceSize))), ivec2(0), ivec2(uFaceSize - 1));
    ivec3 faceTile = shadowAtlasTile(item.slot.y, face, 3, uFaceTilesPerRow);
    float depth = texelFetch(uFaces, ivec3(faceTile.xy * uFaceSize + faceTexel, faceTile.z), 0).r;
    float distance = vplFaceDistance(depth, directionCube, face, uZNear, uZFar);
    ivec3 mapTile = shadowAtlasTileFromIndex(item.slot.x, uMapTilesPerRow);
    imageStore(uMaps, ivec3(mapTile.xy * uMapSize + id.xy, mapTile.z), vec4(distance));
}
