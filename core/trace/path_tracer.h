// The ground-truth reference: an Embree path tracer over core::Scene with the shared material.
//
// Intro
// -----
// Every GI technique in vplgi is judged against this renderer. It solves the rendering equation for
// the scene exactly as the GPU sees it (same surfaces through surfaceAt, same BRDF through
// shared::evaluateBRDF, same punctual emitters through buildDirectLights and evaluateDirectLight,
// same camera rays), with nothing clamped or filtered except what a mode asks for. It is slow and
// simple on purpose: a unidirectional path tracer with next-event estimation and multiple
// importance sampling, as pbrt-v4's PathIntegrator.
//
// Overview
// --------
//  renderReference()            passes of 1, 2, 4, ... samples per pixel until `spp` or the time
//   |                           budget; after each pass the main thread reports progress
//   +- tbb::parallel_for tiles  every pixel sums its samples in sample-index order
//       +- radiance(pixel, s)   one camera path; its random numbers come only from
//                               hash(seed, pixel index, sample index)
//
// Details
// -------
//  Units are those of core/scene/scene.h: point/spot intensity [W/sr], directional irradiance [W/m^2],
//  emission radiance [W/(m^2 sr)]; the image holds radiance [W/(m^2 sr)] per pixel (linear RGB,
//  rows top to bottom, alpha 1).
//
//  Camera: pixel (x, y), y down, sample jitter (u, v) in [0,1)^2 (a box filter over the pixel):
//  NDC = ((x+u)/W*2-1, 1-(y+v)/H*2); the ray leaves camera.position through
//  inverse(clipFromView(W/H) * viewFromWorld()) of the NDC point on the far plane, and is clipped to
//  the near and far planes as the rasterizer clips (t from the near-plane point to the far one).
//
//  Vertices and depth: vertex 0 is the primary hit, vertex k the hit after k bounces. Light that
//  reaches the camera after n reflections is emission seen at vertex n, or a light sample at vertex
//  n-1. `maxDepth` is the largest n kept: emission is added at vertices 0..maxDepth and next-event
//  estimation runs at vertices 0..maxDepth-1. maxDepth = 0 is emission only, 1 is direct light
//  only, 2 adds one-bounce indirect (the furnace's L_2), and so on.
//
//  Surfaces: the back-face rule (scene.h Material::doubleSided, ray_scene.h Looker): whoever looks
//  along a segment does not see the backs of single-sided surfaces (front: counter-clockwise,
//  clockwise under a mirroring instance), as the rasterizer culls them in the camera's and every
//  light's view. Camera rays pass through backs; a shadow ray towards a light or an emitting
//  triangle passes through a surface whose back faces that emitter; a bounce stops on either side,
//  and a back ends the path (it reflects nothing: the vertex behind it looks, and sees its front).
//  Double-sided materials are shaded on the side the ray arrives from (surfaceAt).
//
//  Next-event estimation at every vertex (pbrt-v4 SampleLd):
//   - point, spot and directional lights (delta lights): each of them, every time, with one shadow
//     ray; evaluateDirectLight does it, so the Direct mode agrees with the CPU direct evaluation of
//     the GPU's direct pass for punctual lights.
//   - emissive triangles (area lights): one triangle chosen with probability proportional to its
//     power (luminance(emission) * area), a uniform point on it, a shadow ray, and the power
//     heuristic (beta = 2) against the BRDF density. Emission found by BRDF sampling gets the
//     complementary weight. (buildDirectLights' cosine point samples of emitters are not used.)
//  BRDF sampling (sampleBRDF): a mixture of the cosine-weighted diffuse lobe and the GGX lobe,
//  sampled through its distribution of visible normals (Heitz 2018); the lobe is chosen with a
//  probability from the Fresnel reflectance at the view angle against the diffuse albedo. The pdf
//  (pdfBRDF) is the exact mixture density. Directions below the geometric horizon end the path.
//  Ray offsets: 1e-4 * RayScene::sceneScale() along the geometric normal.
//
//  Russian roulette: before the path goes on to vertex k with k >= rrStartDepth, it survives with
//  probability q = min(0.95, max component of the throughput) and the throughput is divided by q.
//
//  Modes (SMCIR Fig. 8 and Sec. 5.4):
//   Full      everything.
//   Direct    emission seen at the primary hit plus one reflection of light at the primary hit
//             (light samples at vertex 0 and emission found at vertex 1); this is Full with
//             maxDepth = min(maxDepth, 1).
//   Indirect  Full minus Direct: only light that was reflected at least once after the primary hit
//             (light samples at vertices >= 1, emission at vertices >= 2). This is what VPL methods
//             estimate.
//   Clamped   Indirect, with the geometry term of the segment x0 -> x1 leaving the primary hit
//             clamped as VPL methods clamp G between VPLs and primary hits (MATH.md 1.2 (a)):
//             everything carried by that segment is scaled by min(1, G_max / G(x0, x1)),
//             G = cos(n0, x1-x0) cos(n1, x0-x1) / |x1-x0|^2 with shading normals. SMCIR Sec. 5.4
//             "clamp[s] the geometry term of all light transport path segments that originate from
//             the primary hits, except for those that directly connect to a light source": light
//             samples at x0 (direct light) are not clamped, and are not in Indirect anyway.
//   OneBounce Indirect with the paths cut after vertex 2: light that was reflected exactly once
//             between the light and the primary hit (light -> x1 -> x0 -> eye): light samples at
//             vertex 1 and emission found at vertex 2; this is Indirect with
//             maxDepth = min(maxDepth, 2). It is what RSM-based techniques (VSGL, LightSkin) estimate;
//             on the furnace it is L_2 = rho^2 I0 / (pi R^2) (MATH.md 3).
//  Whatever the mode, every vertex draws the same random numbers, so with the same seed and no
//  Russian roulette in play the modes follow identical paths: Full = Direct + Indirect per sample
//  up to rounding (a test checks this).
//
//  Reflected radiance at a given point (ReflectedRadianceEstimator, SMCIR 3.2.3): the same
//  integrator, but the path starts at a surface point y instead of a camera ray. Vertex 0 is y with
//  its material reduced to the diffuse lobe ((1 - metallic) * baseColor / pi, SMCIR 3.1's Lambert
//  assumption) and wo = n; y's own emission is left out (the renderer draws emitters directly).
//  The result is the diffuse exitant radiance L(y) = (rho_d/pi) * irradiance, with light reflected
//  at most `maxBounces` times counting the reflection at y (1 = direct light at y only). A VPL
//  carries it as its radiance (core/vpl/vpl.h).
//
//  Work skipped because it cannot change the result (both exact, bit for bit):
//   - Without emissive triangles, the intersection of a vertex past maxDepth is not cast: such a
//     vertex could only add emission (the last ray of every path that reaches maxDepth).
//   - ReflectedRadianceEstimator: every path from y starts at the same vertex 0, and the punctual
//     lights' term there (evaluateDirectLight: one shadow ray per light, no random numbers) is the
//     same in every path. The first path that needs it computes it; the others reuse that value,
//     which is the one they would have computed, so each path's sum and the mean are unchanged. The
//     random numbers each path draws are unchanged too. Its shadow rays are cast (and counted in
//     `rays`) once per estimate instead of once per sample: about a third of the rays of SMCIR's
//     radiance paths in the maze (8 point lights).
//
//  Determinism: sample s of pixel p uses its own PCG32 stream seeded from hash(seed, p, s); pixels
//  sum their samples in sample order. The image is bit-identical for a given seed and sample count
//  whatever the thread count and scheduling. With a time budget, the sample count reached depends
//  on the machine (ReferenceResult::spp reports it).
//
// References
// ----------
//  M. Pharr, W. Jakob, G. Humphreys: Physically Based Rendering, 4th ed., 2023 (PathIntegrator,
//    Russian roulette, power heuristic; the furnace test).
//  E. Veach: Robust Monte Carlo Methods for Light Transport Simulation, 1997, ch. 9 (MIS).
//  E. Heitz: Sampling the GGX Distribution of Visible Normals, JCGT 7(4), 2018.
//  T. Duff et al.: Building an Orthonormal Basis, Revisited, JCGT 6(1), 2017.
//  M. O'Neill: PCG: A Family of Simple Fast Space-Efficient Statistically Good Algorithms for
//    Random Number Generation, 2014.
//  SMCIR (papers/000): Sec. 5.4 and Fig. 8, path tracing with simulated clamping.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "glsl/shared/brdf.h"
#include "core/util/image_io.h"
#include "core/trace/ray_scene.h"
#include "core/scene/scene.h"
#include "core/scene/surface.h"

namespace vplgi {

class ParamVisitor;
struct SurfacePoint;

// Camera rays through pixel positions (x, y in pixels, rows top to bottom; x + 0.5 is a pixel
// centre), as the rasterizer projects: from the eye through the NDC point, clipped to the near and
// far planes (the prose above). Double precision.
class CameraRays {
public:
    CameraRays(const Camera& camera, int width, int height);
    Ray at(double x, double y) const;

private:
    glm::dvec3 unproject(double x, double y, double z) const;
    int mWidth, mHeight;
    glm::dvec3 mEye;
    glm::dmat4 mWorldFromClip;
};

struct PathTracerParams {
    enum class Mode { Full = 0, Direct = 1, Indirect = 2, Clamped = 3, OneBounce = 4 };

    int spp = 64;                 // samples per pixel [1, 2^24]
    int maxDepth = 8;             // most reflections a light path may undergo [0, 1024] (see header)
    int rrStartDepth = 3;         // first vertex reached only through Russian roulette [1, 1025]
    Mode mode = Mode::Full;       // which part of the light transport to render
    float clampGeometry = 10.0f;  // G_max [1/m^2] of the Clamped mode [0, 1e9]
    std::uint32_t seed = 1;       // random stream seed: the same seed gives the same image
    double timeBudgetSeconds = 0; // wall-clock budget [s], 0 = none: no pass starts after it, and a
                                  // pass is shortened to what the measured time per sample says fits
    bool progress = false;        // print a line per pass to stderr
    bool jitterPixels = true;     // false: every sample through the pixel centre, as a rasterizer
                                  // without MSAA samples (for GPU-vs-reference checks at edges)
    bool untexturedBounces = false; // vertices after the primary hit use UntexturedMaterials (mean
                                    // albedos, no normal maps): SMCIR 5's reference for its VPLs
    int diffuseVertices = 0;        // vertices after the primary hit that reflect with their diffuse lobe
                                    // only ((1 - metallic) baseColor / pi), as VPLs do: 0 none, 1 the
                                    // first (SMCIR: the VPL's Lambert assumption, its radiance paths
                                    // keep the BRDF), 2 every one (IR: light paths of diffuse bounces)

    // Keys "reference.<field>": spp, maxDepth, rrStartDepth, mode (0 full, 1 direct, 2 indirect,
    // 3 clamped, 4 onebounce), clampGeometry, seed, timeBudgetSeconds [0, 1e7] (visited as a float), progress,
    // jitterPixels, untexturedBounces, diffuseVertices.
    void visitParams(ParamVisitor& visitor);
};

// The version of the integrator's output. Bump it whenever the same scene, camera and parameters
// would give a different image (sampling, MIS, Russian roulette, random streams, camera rays, the
// shared BRDF...): cached references carry it in their key, so an older integrator's images are
// not served for the new one's.
constexpr int kPathTracerVersion = 1;

// Text identifying the image `params` ask for, for cache keys: kPathTracerVersion and every field
// visitParams visits, exact values (floats in hex), except reference.progress and
// reference.timeBudgetSeconds (they change when the render stops, not what a complete render
// gives). A field added to visitParams later is in the key without anyone remembering it.
std::string pathTracerImageKey(const PathTracerParams& params);

struct ReferenceResult {
    ImageRGBA32F image; // radiance [W/(m^2 sr)], linear RGB, rows top to bottom, alpha 1
    int spp = 0;        // samples per pixel actually taken (< requested when the budget ran out)
    double seconds = 0; // wall-clock time of the render [s]
};

// Called on the calling thread between passes with the fraction of samples done, in (0, 1].
using ProgressCallback = std::function<void(double fraction)>;

// Renders `camera`'s view of `scene` (which `rays` was built from) at width x height pixels.
// Throws Error for bad sizes or parameters.
ReferenceResult renderReference(const Scene& scene, const RayScene& rays, const Camera& camera, int width, int height,
                                const PathTracerParams& params, ProgressCallback progress = {});

// The same estimate as renderReference, but only at the given pixels (SMCIR 5.2: "ground truth
// values for these pixels", the tracked pixels of the temporal metrics): pixel (x, y) of a
// width x height image uses the same sample streams and sums its samples in the same order, so each
// value is bit-identical to that pixel of renderReference's image for the same parameters.
// params.timeBudgetSeconds is ignored (every pixel gets params.spp samples). Throws Error for
// pixels outside the image or bad parameters.
struct PixelReferenceResult {
    std::vector<glm::vec3> radiance; // per requested pixel [W/(m^2 sr)], linear RGB
    int spp = 0;
    double seconds = 0; // wall-clock time [s]
};
PixelReferenceResult renderReferencePixels(const Scene& scene, const RayScene& rays, const Camera& camera, int width,
                                           int height, const std::vector<glm::ivec2>& pixels,
                                           const PathTracerParams& params, ProgressCallback progress = {});

// --- Reflected radiance at a surface point (the radiance of a VPL, SMCIR 3.2.3) ------------------

// Holds the scene's lights as the path tracer sees them (build it again after lights change) and
// estimates the diffuse exitant radiance L(y) [W/(m^2 sr)] at surface points: (rho_d/pi) times the
// irradiance at y, rho_d = (1 - metallic) * baseColor, with next-event estimation and MIS as
// renderReference, light reflected at most maxBounces times including at y, no emission of y.
// Thread-safe: estimate() may run concurrently. The scene must outlive the estimator; its geometry
// and materials must not change while it lives (its lights may, when a snapshot was given).
class ReflectedRadianceEstimator {
public:
    // maxBounces in [1, 1024]: 1 = direct light at y, 3 = SMCIR's default. Throws Error otherwise.
    // Reads scene.lights now (on the calling thread).
    ReflectedRadianceEstimator(const Scene& scene, const RayScene& rays, int maxBounces);
    // With a snapshot of the lights instead of scene.lights (the scene's light list is never read,
    // so another thread may animate it meanwhile), and with `untextured` (not null; it must outlive
    // the estimator) the paths' vertices after y use that table (SMCIR 5).
    ReflectedRadianceEstimator(const Scene& scene, const RayScene& rays, const std::vector<Light>& lights,
                               int maxBounces, const UntexturedMaterials* untextured);
    ~ReflectedRadianceEstimator();
    ReflectedRadianceEstimator(const ReflectedRadianceEstimator&) = delete;
    ReflectedRadianceEstimator& operator=(const ReflectedRadianceEstimator&) = delete;

    // Mean of `samples` paths from y (samples >= 1). Sample s draws its random numbers from
    // hash(seed, s) only, so the same (y, seed) gives the same value. When `rays` is not null, the
    // Embree rays cast (intersect and occluded) are added to *rays.
    glm::vec3 estimate(const SurfacePoint& y, int samples, std::uint32_t seed, std::uint64_t* rays = nullptr) const;

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

// One-off convenience: builds a ReflectedRadianceEstimator and calls estimate() once.
glm::vec3 estimateReflectedRadiance(const Scene& scene, const RayScene& rays, const SurfacePoint& y, int samples,
                                    int maxBounces, std::uint32_t seed, std::uint64_t* rayCount = nullptr);

// --- BRDF sampling of the shared material (glsl/shared/brdf.h), exposed for tests ---------------

struct BRDFSample {
    glm::vec3 wi{0.0f};     // sampled direction, unit, away from the surface
    glm::vec3 weight{0.0f}; // f_r(wo, wi) cos(n, wi) / pdf
    float pdf = 0.0f;       // solid-angle density of wi [1/sr] (the whole mixture's)
};

// Draws wi for unit `wo` (away from the surface) about the unit shading normal `n` from three
// uniform numbers in [0,1). Empty when the draw lands below the shading horizon, wo is below it, or
// the material reflects nothing; the density of the non-empty draws is still pdfBRDF.
std::optional<BRDFSample> sampleBRDF(const shared::SurfaceMaterial& material, const glm::vec3& n, const glm::vec3& wo,
                                     const glm::vec3& u);
// Solid-angle density [1/sr] with which sampleBRDF draws wi; 0 below either horizon.
float pdfBRDF(const shared::SurfaceMaterial& material, const glm::vec3& n, const glm::vec3& wo, const glm::vec3& wi);

} // namespace vplgi
