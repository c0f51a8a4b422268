// LightSkin's virtual area light (VAL) at one RSM texel, as the proxy pass sums it and the finalize
// pass reads a cache's own light (glsl/passes/lightskin_proxy.comp, lightskin_proxy_finalize.comp).
// The includer declares, before including this file:
//   uniform sampler2DArray uSource[kRSMAttachmentCount];      (binding kUnitRSMSource)
//   buffer Views { RSMLayerView views[]; };                    (binding kBindingRSMLayerViews)
//   buffer Layers { RSMLayerLight layerLights[]; };            (binding kBindingRSMLayers)
// and includes ../shared/lightskin.h, ../shared/lightskin_gpu.h, ../shared/normals.h, ../shared/rsm.h.

struct LightSkinVAL {
    bool valid;        // a covered texel that reflects light towards its own side
    vec3 position;     // x_l [m]
    vec3 normal;       // the texel's geometric normal n_g (the footprint's exit cosine and tilt)
    vec3 flux;         // reflected flux [W]: incident flux x (1 - metallic) baseColor x cos_s / cos_g
    float area;        // eq. (1)'s area [m^2]
    float areaTilted;  // the footprint on the surface, MATH.md 9.1 [m^2]
};

LightSkinVAL readLightSkinVAL(ivec3 texel)
{
    LightSkinVAL val;
    val.valid = false;
    vec4 normalCoverage = texelFetch(uSource[kRSMNormal], texel, 0);
    if (normalCoverage.w == 0.0) return val;
    vec4 fluxTexel = texelFetch(uSource[kRSMFlux], texel, 0);
    vec4 diffuseTexel = texelFetch(uSource[kRSMDiffuse], texel, 0);
    val.flux = fluxTexel.rgb * diffuseTexel.rgb;
    if (val.flux == vec3(0.0)) return val;
    val.position = texelFetch(uSource[kRSMPosition], texel, 0).xyz;
    // The VAL's cosines as the one-bounce path tracer has them (not in the paper; issue "Every
    // light type in the RSM techniques", part 2; glsl/shared/sg.h, vplRadiance, derives them):
    // the RSM's flux crossed the texel's triangle, of geometric normal n_g (level 0: flux.w,
    // diffuse.w), so the surface's irradiance takes cos_s(in) / cos_g(in) of it, n_s the shading
    // normal; the footprint's exit cosine and tilt are n_g's. Without normal maps n_s = n_g.
    vec3 ns = normalize(normalCoverage.xyz);
    val.normal = octDecode(vec2(fluxTexel.w, diffuseTexel.w));
    RSMLayerView layer = views[texel.z];
    bool orthographic = layer.info.y != 0.0;
    vec4 light = layerLights[texel.z].positionKind;
    vec3 ray = orthographic ? normalize(light.xyz) : normalize(val.position - light.xyz);
    float cosGeometricIn = dot(val.normal, -ray);
    if (!(cosGeometricIn > 1e-3)) return val;
    val.flux *= max(dot(ns, -ray), 0.0) / cosGeometricIn;
    if (val.flux == vec3(0.0)) return val;
    float depth = dot(layer.depthRow, vec4(val.position, 1.0));
    val.area = lightskinValArea(depth, layer.info.x, orthographic);
    // MATH.md 9.1: the texel's ray from the light, its cosine to the view axis and to the surface.
    float cosAxis = orthographic ? 1.0 : depth / max(distance(val.position, light.xyz), 1e-6);
    val.areaTilted = lightskinValAreaTilted(val.area, cosAxis, cosGeometricIn);
    val.valid = val.area > 0.0;
    return val;
}
