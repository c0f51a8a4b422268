// The UVs of a material's textures (core/scene/scene.h, TextureRef; core/scene/surface.cpp samples
// the same on the CPU): per texture unit kUnitBaseColor, kUnitMetallicRoughness, kUnitEmission,
// kUnitNormalMap (0-3), the UV set it reads (TEXCOORD_0 or _1) and its KHR_texture_transform matrix.
// GpuScene sets both for every draw that binds material textures.
uniform mat3 uTextureTransform[4];
uniform ivec4 uTextureSet;

vec2 materialUV(int unit, vec2 uv0, vec2 uv1)
{
    return (uTextureTransform[unit] * vec3(uTextureSet[unit] == 0 ? uv0 : uv1, 1.0)).xy;
}

