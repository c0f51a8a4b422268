// Light-view maths, defined once for GLSL and C++: how a light (or a VPL) looks at the scene.
//
// Intro
// -----
// Every pass that renders from a light or reads what was rendered there needs the same matrices
// and maps: the six cube faces of a point light's shadow cube, SMCIR's rotated hemisphere cube
// (three faces that together see exactly the hemisphere around a VPL's normal), the paraboloid
// map that stores a hemisphere in one square texture, and the orthographic view of a directional
// light fitted to the scene. ShadowPass uses the cube faces and the directional fit; the shadow
// atlas, RSM and SMCIR/IR passes use the rest.
//
// Conventions (GL and glm's defaults): views are right-handed and look down -z; clip space maps
// to NDC x, y, z in [-1, 1]; matrices are named for the spaces they map between (clipFromWorld).
// The "light frame" of a surface point has z = its normal n and x, y = tangents (lightViewBasis).
//
// Overview
// --------
//  lightViewFromAxes                   a view matrix from an eye and its axes
//  lightViewLookAt / Frustum / Ortho   glm::lookAt / frustum / ortho (RH, NO) with the same
//                                      arithmetic, so C++ results are bit-identical to glm's
//  lightViewCubeFace*                  GL cube-map faces (+X, -X, +Y, -Y, +Z, -Z), 90 degrees each
//  lightViewHemisphere*                SMCIR Sec. 4: three faces of a cube rotated so that
//                                      (1,1,1)/sqrt(3) is n, eye at the VPL (MATH.md 6.2, 6.3)
//  paraboloid*                         Brabec et al. 2002 (MATH.md 6.1): map, inverse, solid angles
//  lightViewDirectional*               orthographic view of the bounding sphere of a box
//
// Details
// -------
//  Hemisphere cube. The cube spans [-h, h]^3 in its own frame, whose axes (the columns of
//  lightViewHemisphereBasis(n)) are rotated so that (1,1,1)/sqrt(3) is n; the eye (the VPL) sits at
//  (h/3)(1,1,1). The plane through the eye orthogonal to n then passes through the cube corners
//  (-h,h,h), (h,-h,h), (h,h,-h), so every direction w with w.n >= 0 leaves the cube through +x, +y
//  or +z, each of which it covers on one side of a diagonal. All three faces are 2h/3 from the eye,
//  so a direction leaves through the face of its largest cube-frame component (ties: the lowest
//  face index, lightViewHemisphereFace). Face k looks along cube axis k with the generalized
//  perspective projection of Kooima 2008 (screen = the face, eye = the VPL): right = axis k+2,
//  up = axis k+1 (indices mod 3; the cyclic permutation of MATH.md 6.3's face +x), and the
//  asymmetric frustum l = b = -2 zNear, r = t = zNear (the face spans [-4h/3, 2h/3] around the
//  eye's foot point at distance 2h/3). The face's corners map to NDC (+-1, +-1).
//  zNear and zFar clip the depth along the face's axis, not the distance: a point of the
//  hemisphere at distance d has axial depth between d/sqrt(6) (a direction on the rim, halfway
//  between two axes) and d. So everything within zFar of the VPL is kept, and nothing closer than
//  zNear; between zNear and sqrt(6) zNear it depends on the direction.
//
//  Paraboloid. In the light frame, a direction v with v.z >= 0 maps to (s, t) = v.xy / (1 + v.z)
//  in the unit disk and to map coordinates uv = (s, t)/2 + 1/2 in [0,1]^2; the inverse is
//  v = (2s, 2t, 1 - s^2 - t^2) / (1 + s^2 + t^2), and dw = 4 / (1 + s^2 + t^2)^2 ds dt
//  = 16 / (1 + s^2 + t^2)^2 du dv: a texel at the centre holds 4x the solid angle of one at the rim.
//  Depth is the distance from the light, scaled to [0, 1] between zNear and zFar. Texels whose
//  centre is outside the disk hold no direction of the hemisphere.
//
// References
// ----------
//  R. Kooima: Generalized Perspective Projection, 2008 (MATH.md 6.2).
//  SMCIR (papers/000) Sec. 4: the rotated hemisphere cube; MATH.md 6.3 derives its placement.
//  S. Brabec, T. Annen, H.-P. Seidel: Shadow Mapping for Hemispherical and Omnidirectional Light
//    Sources, 2002 (MATH.md 6.1).
//  T. Duff et al.: Building an Orthonormal Basis, Revisited, JCGT 6(1), 2017.
//  OpenGL 4.5 core specification, Table 8.19 (cube-map face selection and orientation).
#ifndef VPLGI_SHARED_LIGHT_VIEW_H
#define VPLGI_SHARED_LIGHT_VIEW_H
#include "compat.h"

VPLGI_SHARED_BEGIN

// --- Look-at and projections (glm's right-handed, NDC z in [-1, 1] forms) ----------------------

// viewFromWorld of an eye at `eye` with orthonormal view axes right (view +x), up (+y) and back
// (+z, from the scene towards the eye): the rows of the rotation, then the translation.
VPLGI_FUNC mat4 lightViewFromAxes(vec3 right, vec3 up, vec3 back, vec3 eye)
{
    mat4 m = mat4(1.0f);
    m[0][0] = right.x;
    m[1][0] = right.y;
    m[2][0] = right.z;
    m[0][1] = up.x;
    m[1][1] = up.y;
    m[2][1] = up.z;
    m[0][2] = back.x;
    m[1][2] = back.y;
    m[2][2] = back.z;
    m[3][0] = -dot(right, eye);
    m[3][1] = -dot(up, eye);
    m[3][2] = -dot(back, eye);
    return m;
}

// View matrix of an eye at `eye` looking at `center`: glm::lookAt's arithmetic step for step, so
// that the C++ result is bit for bit glm's (ShadowPass's images did not change when it moved
// here). Negation is exact, so back = -f and -dot(back, eye) are glm's -f and dot(f, eye).
VPLGI_FUNC mat4 lightViewLookAt(vec3 eye, vec3 center, vec3 up)
{
    vec3 f = normalize(center - eye);
    vec3 s = normalize(cross(f, up));
    vec3 u = cross(s, f);
    return lightViewFromAxes(s, u, -f, eye);
}

// Perspective projection of the view-space window [left, right] x [bottom, top] on the plane
// z = -zNear (glm::frustum).
VPLGI_FUNC mat4 lightViewFrustum(float left, float right, float bottom, float top, float zNear, float zFar)
{
    mat4 m = mat4(0.0f);
    m[0][0] = (2.0f * zNear) / (right - left);
    m[1][1] = (2.0f * zNear) / (top - bottom);
    m[2][0] = (right + left) / (right - left);
    m[2][1] = (top + bottom) / (top - bottom);
    m[2][2] = -(zFar + zNear) / (zFar - zNear);
    m[2][3] = -1.0f;
    m[3][2] = -(2.0f * zFar * zNear) / (zFar - zNear);
    return m;
}

// Orthographic projection of the view-space box [left, right] x [bottom, top] x [-zFar, -zNear]
// (glm::ortho).
VPLGI_FUNC mat4 lightViewOrtho(float left, float right, float bottom, float top, float zNear, float zFar)
{
    mat4 m = mat4(1.0f);
    m[0][0] = 2.0f / (right - left);
    m[1][1] = 2.0f / (top - bottom);
    m[2][2] = -2.0f / (zFar - zNear);
    m[3][0] = -(right + left) / (right - left);
    m[3][1] = -(top + bottom) / (top - bottom);
    m[3][2] = -(zFar + zNear) / (zFar - zNear);
    return m;
}

// Orthonormal frame around the unit normal n: columns x (tangent), y (bitangent), z = n,
// right-handed (Duff et al. 2017). The light frame of the paraboloid map.
VPLGI_FUNC mat3 lightViewBasis(vec3 n)
{
    float sgn = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sgn + n.z);
    float c = n.x * n.y * a;
    vec3 t = vec3(1.0f + sgn * n.x * n.x * a, sgn * c, -sgn * n.x);
    vec3 b = vec3(c, sgn + n.y * n.y * a, -n.y);
    return mat3(t, b, n);
}

// --- Cube faces (point lights) ------------------------------------------------------------------

VPLGI_CONST int kLightViewCubeFaceCount = 6;

// Direction the face looks along, in GL's face order +X, -X, +Y, -Y, +Z, -Z (layer = face).
VPLGI_FUNC vec3 lightViewCubeFaceDirection(int face)
{
    int axis = face / 2;
    float sgn = face % 2 == 0 ? 1.0f : -1.0f;
    return vec3(axis == 0 ? sgn : 0.0f, axis == 1 ? sgn : 0.0f, axis == 2 ? sgn : 0.0f);
}

// The face's "up" (view +y) such that the rendered face is laid out as GL samples a cube map:
// Table 8.19's (s, t) for the face equal the view's NDC (x, y) mapped to [0, 1].
VPLGI_FUNC vec3 lightViewCubeFaceUp(int face)
{
    if (face == 2) return vec3(0.0f, 0.0f, 1.0f);
    if (face == 3) return vec3(0.0f, 0.0f, -1.0f);
    return vec3(0.0f, -1.0f, 0.0f);
}

// viewFromWorld of face `face` of a cube around `position` (look-at from the centre along the face).
VPLGI_FUNC mat4 lightViewCubeFaceViewFromWorld(vec3 position, int face)
{
    return lightViewLookAt(position, position + lightViewCubeFaceDirection(face), lightViewCubeFaceUp(face));
}

// 90 degree square frustum (glm::perspective(radians(90), 1, zNear, zFar): tan(45 degrees) is 1
// exactly in float, so the entries are equal too).
VPLGI_FUNC mat4 lightViewCubeFaceClipFromView(float zNear, float zFar)
{
    mat4 m = mat4(0.0f);
    m[0][0] = 1.0f;
    m[1][1] = 1.0f;
    m[2][2] = -(zFar + zNear) / (zFar - zNear);
    m[2][3] = -1.0f;
    m[3][2] = -(2.0f * zFar * zNear) / (zFar - zNear);
    return m;
}

VPLGI_FUNC mat4 lightViewCubeFaceClipFromWorld(vec3 position, int face, float zNear, float zFar)
{
    return lightViewCubeFaceClipFromView(zNear, zFar) * lightViewCubeFaceViewFromWorld(position, face);
}

// The face a direction (from the cube's centre) leaves through: its major axis and that
// component's sign. Ties (a direction on an edge, which lies on both faces' borders) go to the
// lower axis; GL's own choice on ties is implementation-dependent.
VPLGI_FUNC int lightViewCubeFace(vec3 direction)
{
    vec3 a = abs(direction);
    if (a.x >= a.y && a.x >= a.z) return direction.x >= 0.0f ? 0 : 1;
    if (a.y >= a.z) return direction.y >= 0.0f ? 2 : 3;
    return direction.z >= 0.0f ? 4 : 5;
}

// --- Hemisphere cube (SMCIR Sec. 4; MATH.md 6.2, 6.3) -------------------------------------------

VPLGI_CONST int kLightViewHemisphereFaceCount = 3;

// Columns: the cube's x, y, z axes in world space, rotated so that (1,1,1)/sqrt(3) in cube
// coordinates is the unit normal n. In the light frame (t, b, n) of lightViewBasis the axes are
// (1/sqrt2, 1/sqrt6, 1/sqrt3), (-1/sqrt2, 1/sqrt6, 1/sqrt3), (0, -2/sqrt6, 1/sqrt3): orthonormal,
// right-handed, each 54.7 degrees from n. The rotation about n is that of lightViewBasis.
VPLGI_FUNC mat3 lightViewHemisphereBasis(vec3 n)
{
    mat3 frame = lightViewBasis(n);
    vec3 t = frame[0];
    vec3 b = frame[1];
    float invSqrt2 = 0.70710678118655f;
    float invSqrt6 = 0.40824829046386f;
    float invSqrt3 = 0.57735026918963f;
    vec3 x = invSqrt2 * t + invSqrt6 * b + invSqrt3 * n;
    vec3 y = -invSqrt2 * t + invSqrt6 * b + invSqrt3 * n;
    vec3 z = -2.0f * invSqrt6 * b + invSqrt3 * n;
    return mat3(x, y, z);
}

// The face (0 = +x, 1 = +y, 2 = +z of the cube frame) a direction given in cube coordinates
// (transpose(lightViewHemisphereBasis(n)) * w) leaves through: its largest component. A direction
// on the edge shared by two faces (equal largest components; n itself is on all three) lies on
// the border of both faces' frusta; it is given to the lower face index.
VPLGI_FUNC int lightViewHemisphereFace(vec3 directionCube)
{
    if (directionCube.x >= directionCube.y && directionCube.x >= directionCube.z) return 0;
    if (directionCube.y >= directionCube.z) return 1;
    return 2;
}

// Face `face`'s viewFromWorld for a VPL at `position` with cube axes `cubeBasis`: Kooima's
// M^T T(-p_e) with right = axis face+2, up = axis face+1, back (towards the eye) = -axis face.
VPLGI_FUNC mat4 lightViewHemisphereFaceViewFromWorld(vec3 position, mat3 cubeBasis, int face)
{
    return lightViewFromAxes(cubeBasis[(face + 2) % 3], cubeBasis[(face + 1) % 3], -cubeBasis[face], position);
}

// The asymmetric frustum of every hemisphere face: l = b = -2 zNear, r = t = zNear (MATH.md 6.3).
VPLGI_FUNC mat4 lightViewHemisphereFaceClipFromView(float zNear, float zFar)
{
    return lightViewFrustum(-2.0f * zNear, zNear, -2.0f * zNear, zNear, zNear, zFar);
}

VPLGI_FUNC mat4 lightViewHemisphereFaceClipFromWorld(vec3 position, mat3 cubeBasis, int face, float zNear, float zFar)
{
    return lightViewHemisphereFaceClipFromView(zNear, zFar) *
           lightViewHemisphereFaceViewFromWorld(position, cubeBasis, face);
}

// Texture coordinates in [0,1]^2 on face `face` of a direction given in cube coordinates, as the
// face's clipFromWorld projects it (u along the face's right axis, v along its up axis): each
// coordinate is (ratio + 2) / 3 with ratio = that axis' component over the face axis' component,
// in [-2, 1] on the face. For resampling the faces (e.g. into a paraboloid map, MATH.md 6.4).
VPLGI_FUNC vec2 lightViewHemisphereFaceUV(vec3 directionCube, int face)
{
    float axial = directionCube[face];
    float right = directionCube[(face + 2) % 3];
    float up = directionCube[(face + 1) % 3];
    return (vec2(right, up) / axial + vec2(2.0f)) / 3.0f;
}

// --- Paraboloid map (Brabec et al. 2002; MATH.md 6.1) -------------------------------------------

// Map coordinates uv in [0,1]^2 of a unit direction in the light frame with z >= 0.
VPLGI_FUNC vec2 paraboloidMapFromDirection(vec3 directionLight)
{
    vec2 st = vec2(directionLight.x, directionLight.y) / (1.0f + directionLight.z);
    return 0.5f * st + vec2(0.5f);
}

// (u, v, depth) of a point given relative to the light in its frame (z >= 0): the map coordinates
// of its direction and its distance mapped linearly from [zNear, zFar] to [0, 1].
VPLGI_FUNC vec3 paraboloidMapFromPoint(vec3 pointLight, float zNear, float zFar)
{
    float radial = length(pointLight);
    vec2 uv = paraboloidMapFromDirection(pointLight / radial);
    return vec3(uv, (radial - zNear) / (zFar - zNear));
}

// Unit direction in the light frame of map coordinates uv; z >= 0 inside the disk
// (2u-1)^2 + (2v-1)^2 <= 1 (outside it, the formula continues onto the lower hemisphere).
VPLGI_FUNC vec3 paraboloidDirectionFromMap(vec2 uv)
{
    vec2 st = 2.0f * uv - vec2(1.0f);
    float r2 = dot(st, st);
    return vec3(2.0f * st.x, 2.0f * st.y, 1.0f - r2) / (1.0f + r2);
}

// Solid angle per unit map area at uv: dw / (du dv) = 16 / (1 + s^2 + t^2)^2 [sr], (s, t) = 2uv - 1.
VPLGI_FUNC float paraboloidSolidAngleDensity(vec2 uv)
{
    vec2 st = 2.0f * uv - vec2(1.0f);
    float q = 1.0f + dot(st, st);
    return 16.0f / (q * q);
}

// Integral over t' in [0, t] of 4 / (1 + s^2 + t'^2)^2: exact (with a^2 = 1 + s^2,
// 2 [t / (a^2 (a^2 + t^2)) + atan(t / a) / a^3]).
VPLGI_FUNC float paraboloidSolidAngleStrip(float s, float t)
{
    float a2 = 1.0f + s * s;
    float a = sqrt(a2);
    return 2.0f * (t / (a2 * (a2 + t * t)) + atan(t / a) / (a2 * a));
}

// One column (at s) of the part of the strip t0 <= t <= t1 inside the unit disk.
VPLGI_FUNC float paraboloidSolidAngleColumn(float s, float t0, float t1)
{
    float rim = sqrt(max(1.0f - s * s, 0.0f));
    float lo = max(t0, -rim);
    float hi = min(t1, rim);
    return hi > lo ? paraboloidSolidAngleStrip(s, hi) - paraboloidSolidAngleStrip(s, lo) : 0.0f;
}

// The columns from s = a to s = b by 4-point Gauss-Legendre (nodes +-0.33998104, +-0.86113631,
// weights 0.65214515, 0.34785485 on [-1, 1]); 0 when a = b.
VPLGI_FUNC float paraboloidSolidAngleSpan(float a, float b, float t0, float t1)
{
    float mid = 0.5f * (a + b);
    float halfWidth = 0.5f * (b - a);
    float sum = 0.34785484513745f * paraboloidSolidAngleColumn(mid - 0.86113631159405f * halfWidth, t0, t1) +
                0.65214515486255f * paraboloidSolidAngleColumn(mid - 0.33998104358486f * halfWidth, t0, t1) +
                0.65214515486255f * paraboloidSolidAngleColumn(mid + 0.33998104358486f * halfWidth, t0, t1) +
                0.34785484513745f * paraboloidSolidAngleColumn(mid + 0.86113631159405f * halfWidth, t0, t1);
    return sum * halfWidth;
}

// Solid angle [sr] of the hemisphere directions that texel `texel` of a resolution^2 paraboloid
// map holds: the density integrated over the texel's part of the unit disk, exactly along t and by
// Gauss-Legendre along s. The clipped column length has kinks where the rim crosses the texel's
// rows t0 and t1, at s = +-sqrt(1 - t^2); the s range is split there so that each piece is smooth
// (five pieces, empty ones cost nothing but evaluations). What is left is the sqrt-shaped rim at
// s = +-1 in the texels of the outermost columns. tests/cpu/test_light_view.cpp measures the sum
// over the map against 2 pi and single texels against brute force.
VPLGI_FUNC float paraboloidTexelSolidAngle(ivec2 texel, int resolution)
{
    float h = 2.0f / float(resolution);
    float s0 = -1.0f + h * float(texel.x);
    float s1 = s0 + h;
    float t0 = -1.0f + h * float(texel.y);
    float t1 = t0 + h;
    float k0 = sqrt(max(1.0f - t0 * t0, 0.0f));
    float k1 = sqrt(max(1.0f - t1 * t1, 0.0f));
    float kLo = min(k0, k1);
    float kHi = max(k0, k1);
    float c1 = clamp(-kHi, s0, s1);
    float c2 = clamp(-kLo, s0, s1);
    float c3 = clamp(kLo, s0, s1);
    float c4 = clamp(kHi, s0, s1);
    return paraboloidSolidAngleSpan(s0, c1, t0, t1) + paraboloidSolidAngleSpan(c1, c2, t0, t1) +
           paraboloidSolidAngleSpan(c2, c3, t0, t1) + paraboloidSolidAngleSpan(c3, c4, t0, t1) +
           paraboloidSolidAngleSpan(c4, s1, t0, t1);
}

// --- Spot lights (RSM) ---------------------------------------------------------------------------

// viewFromWorld of a spot light at `position` emitting along the unit `axis`: looks down the axis,
// with the same choice of "up" as the directional view.
VPLGI_FUNC mat4 lightViewSpotViewFromWorld(vec3 position, vec3 axis)
{
    vec3 up = abs(axis.y) < 0.99f ? vec3(0.0f, 1.0f, 0.0f) : vec3(1.0f, 0.0f, 0.0f);
    return lightViewLookAt(position, position + axis, up);
}

// Square symmetric frustum whose half-angle across x and y is `halfAngle` [rad] (< pi/2): the cone
// of that half-angle is inscribed in it, so a spot's whole cone is seen when halfAngle is its
// outer angle. The near-plane window is +-zNear tan(halfAngle).
VPLGI_FUNC mat4 lightViewSpotClipFromView(float halfAngle, float zNear, float zFar)
{
    float extent = zNear * tan(halfAngle);
    return lightViewFrustum(-extent, extent, -extent, extent, zNear, zFar);
}

// --- Directional lights --------------------------------------------------------------------------

// viewFromWorld of a directional light travelling along `direction`, seen from 2 * radius before
// `center` (the centre of a sphere of `radius` to be covered).
VPLGI_FUNC mat4 lightViewDirectionalViewFromWorld(vec3 direction, vec3 center, float radius)
{
    vec3 dir = normalize(direction);
    vec3 up = abs(dir.y) < 0.99f ? vec3(0.0f, 1.0f, 0.0f) : vec3(1.0f, 0.0f, 0.0f);
    return lightViewLookAt(center - dir * (2.0f * radius), center, up);
}

// Orthographic box around that sphere: +-radius across, depth [0.5, 3.5] radius (the sphere spans
// [1, 3] radius, with half a radius to spare on each side).
VPLGI_FUNC mat4 lightViewDirectionalClipFromView(float radius)
{
    return lightViewOrtho(-radius, radius, -radius, radius, radius * 0.5f, radius * 3.5f);
}

// clipFromWorld of a directional light fitted to the box [boundsLower, boundsUpper] (not empty):
// the bounding sphere of the box with 1% margin; the diagonal is taken as at least 1e-3.
VPLGI_FUNC mat4 lightViewDirectionalFit(vec3 direction, vec3 boundsLower, vec3 boundsUpper)
{
    float diagonal = max(1e-3f, length(boundsUpper - boundsLower));
    vec3 center = 0.5f * (boundsLower + boundsUpper);
    float radius = 0.5f * diagonal * 1.01f;
    return lightViewDirectionalClipFromView(radius) * lightViewDirectionalViewFromWorld(direction, center, radius);
}

VPLGI_SHARED_END

#endif // VPLGI_SHARED_LIGHT_VIEW_H
