// smcir-rt (SMCIR's sampler + the all-VPL ray-traced gather, SMCIR Fig. 8) against closed forms
// and the path tracer.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "core/scene/builtin_scenes.h"
#include "core/util/metrics.h"
#include "core/trace/path_tracer.h"
#include "core/trace/ray_scene.h"
#include "core/vpl/smcir_sampler.h"
#include "core/vpl/vpl_gather.h"
#include "measured.h"

using namespace vplgi;

namespace {

double meanLuminance(const ImageRGBA32F& image)
{
    double sum = 0.0;
    for (std::size_t p = 0; p < static_cast<std::size_t>(image.width) * image.height; ++p)
        sum += 0.2126 * image.pixels[p * 4] + 0.7152 * image.pixels[p * 4 + 1] + 0.0722 * image.pixels[p * 4 + 2];
    return sum / (static_cast<double>(image.width) * image.height);
}

} // namespace

TEST_CASE("smcir-rt on the furnace converges to rho * L_all as I grows (no clamping)", "[smcir][furnace][numbers]")
{
    // SMCIR is consistent, not unbiased: at finite I the kNN density of its blue-noise VPL set
    // (k from eq. 8) overestimates 1/p, and ranking VPLs by their frozen radiance estimates keeps the
    // high ones (see core/vpl/smcir_sampler.h). Both shrink as I (and with it k) grows.
    FurnaceParams furnace;
    Scene scene = makeFurnace(furnace);
    RayScene rays(scene);
    const double expected = furnace.albedo * furnaceRadianceAll(furnace); // indirect = rho * L_all
    auto relativeError = [&](int vplCount) {
        SMCIRParams params;
        params.vplCount = vplCount;
        params.radiosityBounces = 40; // the furnace's series: 0.5^40 is negligible
        params.radiositySamples = 64;
        params.warmupIterations = 10;
        // Eq. (7) self excluded (MATH.md 2): after 10 frames the set is still mostly fresh, where the
        // default smcir.knnCountsSelf is -1/k by construction (it pays off on evolved sets:
        // tests/cpu/test_smcir_selection.cpp).
        params.knnCountsSelf = false;
        SMCIRSampler sampler(scene, rays, params);
        sampler.initialize(scene.cameras[0]);
        const ImageRGBA32F image =
            renderVPLGather(scene, rays, scene.cameras[0], 12, 8, sampler.vpls(), VPLGatherParams{});
        return meanLuminance(image) / expected - 1.0;
    };
    const double small = relativeError(256);
    const double large = relativeError(4096);
    MEASURED("smcir-rt furnace, relative error of the indirect radiance: I = 256: " << small << ", I = 4096: " << large);
    CHECK(std::abs(large) < std::abs(small));
    // Measured +42% at I = 256 and +3.5% at I = 4096 (k = 1 candidates, eq. 8 rendering k); 8% is
    // about 2.3x the large-I bias.
    CHECK(std::abs(large) < 0.08);
}

TEST_CASE("smcir-rt on cornell approaches the path tracer's clamped indirect image as I grows", "[smcir][cornell][numbers]")
{
    Scene scene = makeBuiltinScene("cornell");
    RayScene rays(scene);
    const Camera& camera = scene.cameras[0];
    const int width = 24, height = 24;
    const float clampDistance = 0.05f * rays.sceneScale(); // the same clamping on both sides
    const float gMax = 1.0f / (clampDistance * clampDistance);

    PathTracerParams reference;
    reference.mode = PathTracerParams::Mode::Clamped;
    reference.clampGeometry = gMax;
    reference.maxDepth = 4; // reflection at the primary hit + the sampler's 3 radiosity bounces
    reference.spp = 2048;
    reference.jitterPixels = false;
    const ImageRGBA32F truth = renderReference(scene, rays, camera, width, height, reference).image;

    auto errorWith = [&](int vplCount, bool gridDensity = false) {
        SMCIRParams params;
        params.vplCount = vplCount;
        params.candidateDensityGrid = gridDensity;
        params.warmupIterations = 10;
        params.knnCountsSelf = false; // as above: a mostly fresh set
        SMCIRSampler sampler(scene, rays, params);
        sampler.initialize(camera);
        VPLGatherParams gather;
        gather.clampGeometry = gMax;
        const ImageRGBA32F image = renderVPLGather(scene, rays, camera, width, height, sampler.vpls(), gather);
        return compareImages(image, truth, 4.0);
    };
    const ImageErrors small = errorWith(512);
    const ImageErrors large = errorWith(8192);
    // The grid-count density option (not in the paper) must not make the distribution worse.
    const ImageErrors grid = errorWith(512, true);
    MEASURED("smcir-rt cornell vs clamped reference: I = 512: rmse " << small.rmse << " |E| " << small.meanAbsToneMapped
             << " bias " << small.meanRelativeLuminance << "; I = 8192: rmse " << large.rmse << " |E| "
             << large.meanAbsToneMapped << " bias " << large.meanRelativeLuminance
             << "; I = 512 with grid density: rmse " << grid.rmse << " |E| " << grid.meanAbsToneMapped);
    CHECK(grid.rmse < 1.5 * small.rmse);
    CHECK(large.rmse < small.rmse);
    CHECK(large.meanAbsToneMapped < small.meanAbsToneMapped);
    // Measured bias +1.1% at I = 8192 (+23% at I = 512); 3% is about 2.7x it.
    CHECK(std::abs(large.meanRelativeLuminance) < 0.03);
}

TEST_CASE("screened candidates: VPLs still carry full radiance estimates", "[smcir][furnace][numbers]")
{
    // With candidateRadianceSamples = 1 the candidates are ranked by one-path estimates, but a
    // candidate that becomes a VPL is re-estimated with radiositySamples (line 18): the published
    // radiances must be as accurate as without screening.
    FurnaceParams furnace;
    Scene scene = makeFurnace(furnace);
    RayScene rays(scene);
    const double expected = furnaceRadianceBounce(furnace, 1) + furnaceRadianceBounce(furnace, 2) +
                            furnaceRadianceBounce(furnace, 3); // radiosityBounces = 3
    auto worstDeviation = [&](int screeningSamples) {
        SMCIRParams params;
        params.vplCount = 256;
        params.radiositySamples = 64;
        params.candidateRadianceSamples = screeningSamples;
        params.warmupIterations = 3;
        SMCIRSampler sampler(scene, rays, params);
        sampler.initialize(scene.cameras[0]);
        double worst = 0.0;
        for (const VPL& v : sampler.vpls().slots)
            if (v.valid) worst = std::max(worst, std::abs(v.radiance.g / expected - 1.0));
        return worst;
    };
    const double full = worstDeviation(0);
    const double screened = worstDeviation(1);
    MEASURED("screened candidates, worst VPL radiance deviation: paper " << full << ", screened with 1 sample " << screened);
    CHECK(screened < 0.1);
    CHECK(screened < 2.0 * full + 0.02);
}
