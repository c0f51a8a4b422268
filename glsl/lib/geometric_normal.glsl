// Fragment shaders only: the plane of the triangle being rasterised, for the G-buffer
// (passes/gbuffer.frag) and the RSMs (passes/rsm.frag).
// The unit normal of the triangle's plane from the screen-space derivatives of the world position
// (one triangle per 2x2 quad: helper invocations extend the same plane), turned to the side of
// `shading` as core/scene/surface.cpp keeps Embree's; a degenerate derivative falls back to `fallback`.
vec3 geometricNormal(vec3 worldPosition, vec3 shading, vec3 fallback)
{
    vec3 geometric = cross(dFdx(worldPosition), dFdy(worldPosition));
    float length2 = dot(geometric, geometric);
    geometric = length2 > 0.0 ? geometric * inversesqrt(length2) : fallback;
    return dot(geometric, shading) < 0.0 ? -geometric : geometric;
}
