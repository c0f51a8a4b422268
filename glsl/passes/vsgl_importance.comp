#version 450 core
// The PDF of BRSMs (VSGL section 3; MATH.md 10.1): the importance of RSM texel j is its unoccluded
// contribution to the camera, evaluated "in the same fashion as VSGLs ... by exchanging RSMs and a
// G-buffer": texel j is the receiver (its BRDF lobe about the direction to the light, from level 0
// of the RSM) and the view lights (passes/vsgl_view_rsm.comp, then vsgl_generate.comp's grid mode)
// are the emitters, so glossy texels that reflect towards what the camera sees get the importance
// a diffuse point formula would miss (the paper's Fig. 4a). Importance = luminance(incident flux x
// that sum). Layers sit side by side in the map: texel (x + layer size, y). With uPointFormula
// (`<technique>.pdf=point`) the original BRSM's point formula instead, for the paper's Fig. 4a.
#include "shared/bindings.h"
#include "shared/rsm.h"
#include "shared/sg.h"
#include "shared/tonemap.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = kUnitRSMSource) uniform sampler2DArray uSource[kRSMAttachmentCount];
layout(std430, binding = kBindingVSGLights) readonly buffer ViewLights { VSGLight viewLights[]; };
layout(std430, binding = kBindingRSMLayers) readonly buffer Layers { RSMLayerLight layers[]; };
layout(r32f, binding = kImageImportance) writeonly uniform image2D uImportance;

uniform int uSize;       // RSM edge [texels]
uniform int uLayers;     // RSM layers
uniform int uViewCount;  // view lights
uniform int uPointFormula;    // 0: VSGL radiance (the paper's PDF); 1: the original BRSM's point formula
uniform vec3 uEye;            // the camera: the view lights' "primary light" (uPointFormula 1)
uniform float uClampGeometry; // uPointFormula 1: cap on cos cos / d^2 [1/m^2] (vpl-brsm.clampGeometry); 0 none

void main()
{
    ivec2 at = ivec2(gl_GlobalInvocationID.xy);
    if (at.x >= uSize * uLayers || at.y >= uSize) return;
    ivec3 texel = ivec3(at.x % uSize, at.y, at.x / uSize);
    vec4 normal = texelFetch(uSource[kRSMNormal], texel, 0);
    vec4 flux = texelFetch(uSource[kRSMFlux], texel, 0);
    float importance = 0.0;
    if (normal.w > 0.0 && flux.r + flux.g + flux.b > 0.0) {
        vec4 position = texelFetch(uSource[kRSMPosition], texel, 0);
        vec4 diffuse = texelFetch(uSource[kRSMDiffuse], texel, 0);
        vec4 specular = texelFetch(uSource[kRSMSpecular], texel, 0);
        VSGLShadingPoint s;
        s.position = position.xyz;
        s.normal = normalize(normal.xyz);
        s.view = rsmDirectionToLight(layers[texel.z], position.xyz); // the receiver's "view" in the exchanged roles
        s.diffuse = diffuse.rgb;
        s.f0 = specular.rgb;
        s.roughness = specular.w;
        VSGLReceiver receiver = vsglReceiver(s);
        vec3 sum = vec3(0.0);
        float cancelled;
        if (uPointFormula != 0) {
            // The original BRSM (MATH.md 10.1): each view light as a point, glTF BRDFs at both ends
            // evaluated at the one direction between the points, the view light's lit from the eye.
            // A near-mirror texel gets importance only where a view point sits in its lobe: the
            // paper's Fig. 4a ("cannot produce an appropriate PDF for specular surfaces").
            for (int k = 0; k < uViewCount; ++k) {
                VSGLight v = viewLights[k];
                sum += vplRadiance(s, v, normalize(uEye - v.positionRadius2.xyz), uClampGeometry);
            }
        } else {
            // biasAlpha 0: no bias reduction, which alone reads the emitter's primary direction (here the eye's).
            for (int k = 0; k < uViewCount; ++k)
                sum += vsglRadianceReceiver(receiver, viewLights[k], vec3(0.0), 0.0, cancelled);
        }
        vec3 response = flux.rgb * sum;
        importance = max(luminanceRec709(response), 0.0);
        if (!(importance < 3.0e38)) importance = 0.0; // no NaN or Inf into the tables
    }
    imageStore(uImportance, at, vec4(importance, 0.0, 0.0, 0.0));
}
