// Unit normals packed into two components (octahedral map, Cigolle et al. 2014, "A Survey of
// Efficient Representations for Independent Unit Vectors", JCGT 3(2)): the G-buffer's geometric and
// interpolated normals share one RGBA16F attachment (gl/passes/gbuffer_pass.h). Round trip through
// float16 is within 1.1e-3 rad (measured over 200000 directions: tests/cpu/test_normals.cpp).
#ifndef VPLGI_SHARED_NORMALS_H
#define VPLGI_SHARED_NORMALS_H
#include "compat.h"

VPLGI_SHARED_BEGIN

// +1 for x >= 0, else -1 (GLSL's sign(0) is 0, which would fold the seams onto the axes).
VPLGI_FUNC vec2 octSignNotZero(vec2 v)
{
    return vec2(v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f);
}

// Unit n -> [-1, 1]^2: the octahedron |x| + |y| + |z| = 1, its lower half folded over the diagonals.
VPLGI_FUNC vec2 octEncode(vec3 n)
{
    vec2 p = vec2(n.x, n.y) * (1.0f / (abs(n.x) + abs(n.y) + abs(n.z)));
    if (n.z < 0.0f) p = (vec2(1.0f) - abs(vec2(p.y, p.x))) * octSignNotZero(p);
    return p;
}

// [-1, 1]^2 -> unit n (the inverse of octEncode).
VPLGI_FUNC vec3 octDecode(vec2 e)
{
    vec3 n = vec3(e.x, e.y, 1.0f - abs(e.x) - abs(e.y));
    if (n.z < 0.0f) {
        vec2 folded = (vec2(1.0f) - abs(vec2(n.y, n.x))) * octSignNotZero(vec2(n.x, n.y));
        n = vec3(folded.x, folded.y, n.z);
    }
    return normalize(n);
}

VPLGI_SHARED_END

#endif
