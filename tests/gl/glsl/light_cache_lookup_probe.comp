#version 450 core
// Runs glsl/shared/light_cache_lookup.h on the GPU for the queries the test gives
// (tests/gl/test_light_cache_lookup_gpu.cpp compares with the same function compiled as C++).
// One word buffer holds everything (runComputeProbe binds one input), laid out by the test:
//   words[0..3]   grid origin xyz, cell size (float bits)
//   words[4..7]   the hash table's slot mask, its max probe, unused, k
//   words[8..12]  offsets (in words) of: caches (8 words each: position xyz, pad, normal xyz, pad),
//                 slots (4 words each), cacheIndices, queries (8 words each: x xyz, pad, n xyz, pad), reach records
//                 (4 words per cache; offset 0: no reach test)
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Words { uint words[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
uniform int uCount;

float wordFloat(int i) { return uintBitsToFloat(words[i]); }
vec3 wordVec3(int i) { return vec3(wordFloat(i), wordFloat(i + 1), wordFloat(i + 2)); }

uvec4 lightCacheSlot(int slot)
{
    int at = int(words[9]) + 4 * slot;
    return uvec4(words[at], words[at + 1], words[at + 2], words[at + 3]);
}
uint lightCacheIndex(int i) { return words[int(words[10]) + i]; }
vec3 lightCachePosition(int cache) { return wordVec3(int(words[8]) + 8 * cache); }
vec3 lightCacheNormal(int cache) { return wordVec3(int(words[8]) + 8 * cache + 4); }
uvec4 lightCacheReach(int cache)
{
    int at = int(words[12]) + 4 * cache;
    return uvec4(words[at], words[at + 1], words[at + 2], words[at + 3]);
}

#include "shared/light_cache_lookup.h"

const int kResultsPerCase = 9; // count, 4 x 4 indices (as floats: exact below 2^24), 4 x 4 squared distances

void main()
{
    int q = int(gl_GlobalInvocationID.x);
    if (q >= uCount) return;
    int query = int(words[11]) + 8 * q;
    LightCacheNeighbours found;
    findNearestLightCaches(wordVec3(0), wordFloat(3), words[4], int(words[5]), wordVec3(query), wordVec3(query + 4),
                           int(words[7]), words[12] != 0u, found);
    int base = q * kResultsPerCase;
    results[base] = vec4(float(found.count), 0.0f, 0.0f, 0.0f);
    for (int i = 0; i < 4; ++i) {
        vec4 indices = vec4(-1.0f);
        vec4 distances = vec4(-1.0f);
        for (int j = 0; j < 4; ++j) {
            int slot = 4 * i + j;
            if (slot < found.count) {
                indices[j] = float(found.index[slot]);
                distances[j] = found.distance2[slot];
            }
        }
        results[base + 1 + i] = indices;
        results[base + 5 + i] = distances;
    }
}
