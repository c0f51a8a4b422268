// What SMCIR's selection (Algorithm 1 lines 8-19) adds to the estimate over the frames of a still
// camera (core/vpl/smcir_selection.h; docs/smcir.md "Selection bias"): the radiance part, the
// density part and the area identity on the real sampler, for the default selection and the
// paper's. One seed each: the per-seed spread of these numbers is measured over 8 seeds by
// `vplgi smcir-selection` (docs/smcir.md), and each tolerance below says how it relates to it.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "core/scene/builtin_scenes.h"
#include "core/trace/ray_scene.h"
#include "core/vpl/smcir_selection.h"
#include "measured.h"

using namespace vplgi;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The paper's selection: rank by the values rendered with (one estimate per VPL), eq. (7) self excluded.
SMCIRParams paperSelection(SMCIRParams params)
{
    params.independentRadiance = false;
    params.rankRadiance = kRankByRenderedRadiance;
    params.knnCountsSelf = false;
    return params;
}

} // namespace

TEST_CASE("smcir selection, furnace: the area identity holds after 100 and 300 frames and stops growing",
          "[smcir][numbers]")
{
    // In the furnace L is the same everywhere, so eq. (5) of a uniform receiver is L times the area
    // identity (1/n) sum 1/p_i = sum pi r_k^2 / k, which must equal the sphere's area 4 pi R^2.
    FurnaceParams furnace;
    const Scene scene = makeFurnace(furnace);
    const RayScene rays(scene);
    const double area = 4.0 * kPi * furnace.radius * furnace.radius;
    const FrameSnapshot snapshot = FrameSnapshot::of(scene, scene.cameras[0], 16.0f / 9.0f);
    // The radiance is not looked at here: 1 reference sample and radiance paths of one bounce (L is
    // uniform either way, so the selection sees the same intensities up to noise) keep the run cheap.
    SMCIRParams params;
    params.radiosityBounces = 1;
    const SMCIRSelectionRun ours = runSMCIRSelection(scene, rays, params, snapshot, 300, {100, 300}, 1);
    const SMCIRSelectionRun paper = runSMCIRSelection(scene, rays, paperSelection(params), snapshot, 100, {100}, 1);
    const double at100 = ours.checkpoints[0].area / area - 1.0, at300 = ours.checkpoints[1].area / area - 1.0;
    const double paper100 = paper.checkpoints[0].area / area - 1.0;
    MEASURED("smcir furnace area identity (I = 2048, seed 1), sum pi r_k^2 / k over 4 pi R^2 - 1: default "
             << at100 << " after 100 frames, " << at300 << " after 300; the paper's selection " << paper100
             << " after 100");
    // The acceptance of "SMCIR without drift": within 4% after 100 and 300 frames. The sampler is
    // deterministic for a seed, so these are values, not samples (measured -3.1%, -1.8% with seed 1;
    // over 8 seeds -3.5% [-3.8, -3.2] and -1.8% [-2.0, -1.5] against the sphere's area, as here, and
    // -4.0%, -2.3% against the fresh sets' own estimate, which is +0.5% above it; docs/smcir.md). The
    // issue's second goal, growing by under 1 point from 100 to 300 frames, is
    // not met (1.2 points here, 1.8 between the 8-seed means); the bound is 2x this seed's growth,
    // below the paper's selection's 2.6 points (8-seed means).
    CHECK(std::abs(at100) < 0.04);
    CHECK(std::abs(at300) < 0.04);
    CHECK(std::abs(at300 - at100) < 0.025);
    // The paper's selection over-estimates the area (a repulsive set under a Poisson estimator; the
    // survivors are those whose r_k came out large): measured +10.2% with seed 1; +9.1% [+8.9, +9.4]
    // over 8 seeds against the fresh sets (docs/smcir.md).
    CHECK(paper100 > 0.05);
}

TEST_CASE("smcir selection, Cornell: the rendered radiances are not the selected ones (radiance part)",
          "[smcir][numbers]")
{
    // The radiance part: eq. (5) of a uniform receiver with the published radiances over the same
    // with 256-sample estimates at the same points. Ranking VPLs by the very estimate they render
    // with keeps the ones that came out high; the default ranks by the candidate's estimate.
    const Scene scene = makeBuiltinScene("cornell");
    const RayScene rays(scene);
    const FrameSnapshot snapshot = FrameSnapshot::of(scene, scene.cameras[0], 16.0f / 9.0f);
    const SMCIRSelectionRun ours = runSMCIRSelection(scene, rays, SMCIRParams{}, snapshot, 300, {100, 300}, 256);
    const SMCIRSelectionRun paper = runSMCIRSelection(scene, rays, paperSelection(SMCIRParams{}), snapshot, 100, {100}, 256);
    auto radiancePart = [](const SMCIRSetMeasure& m) { return m.published / m.accurate - 1.0; };
    auto densityPart = [&](const SMCIRSetMeasure& m, const SMCIRSelectionRun& run) {
        return m.accurate / run.fresh.accurateExcluded - 1.0;
    };
    const double ours100 = radiancePart(ours.checkpoints[0]), ours300 = radiancePart(ours.checkpoints[1]);
    const double paper100 = radiancePart(paper.checkpoints[0]);
    MEASURED("smcir Cornell (I = 2048, seed 1) radiance part: default " << ours100 << " after 100 frames, " << ours300
             << " after 300, the paper's selection " << paper100 << " after 100; density part (against this seed's "
             << "fresh set): default " << densityPart(ours.checkpoints[0], ours) << ", "
             << densityPart(ours.checkpoints[1], ours) << ", the paper's " << densityPart(paper.checkpoints[0], paper));
    // Over 8 seeds the default's radiance part is within about 1 point of 0 (docs/smcir.md); the
    // 256-sample reference adds about 0.3% per seed. 3 points is 3x that.
    CHECK(std::abs(ours100) < 0.03);
    CHECK(std::abs(ours300) < 0.03);
    // The paper's: +16.3% [+15.8, +16.7] after 100 frames over 8 seeds.
    CHECK(paper100 > 0.10);
}

TEST_CASE("smcir selection, Cornell: at equal generations the density bias falls as I grows", "[smcir][numbers]")
{
    // #23 part 2, consistency: with M_max = I/128 every budget replaces the same share of its set in
    // 100 frames, so the sets are equally evolved. The density part at 4k (densities of the 4k
    // nearest: the set's real non-uniformity, not kNN noise) must fall as I grows if the selection
    // is consistent. One seed per budget (the sampler is deterministic for a seed: these are values).
    const Scene scene = makeBuiltinScene("cornell");
    const RayScene rays(scene);
    const FrameSnapshot snapshot = FrameSnapshot::of(scene, scene.cameras[0], 16.0f / 9.0f);
    double wide[3] = {}, bias[3] = {};
    const int budgets[3] = {256, 512, 1024};
    for (int b = 0; b < 3; ++b) {
        SMCIRParams params;
        params.vplCount = budgets[b];
        params.maxMoves = budgets[b] / 128;
        const SMCIRSelectionRun run = runSMCIRSelection(scene, rays, params, snapshot, 100, {100}, 128);
        wide[b] = run.checkpoints[0].accurateWide / run.fresh.accurateWide - 1.0;
        bias[b] = run.checkpoints[0].published / run.fresh.accurateExcluded - 1.0;
    }
    MEASURED("smcir Cornell at equal generations (M_max = I/128, 100 frames, seed 1), I = 256 / 512 / 1024: density part "
             << "at 4k " << wide[0] << " / " << wide[1] << " / " << wide[2] << "; bias " << bias[0] << " / " << bias[1]
             << " / " << bias[2]);
    // Over 8 seeds (`vplgi smcir-selection --scene cornell --frames 100 --set smcir.vplCount=I --set
    // smcir.maxMoves=I/128`): +28.2% [+26.6, +29.9], +23.7% [+23.0, +24.3], +17.3% [+17.1, +17.6]
    // (and +13.0% at 2048), normalised by the mean fresh set; this seed against its own fresh set:
    // +34.4%, +27.0%, +15.5%. The bias itself is not monotone for the default (+11.9%, -2.8%, -4.2%,
    // +0.3% over 8 seeds: F2's -1/k offset against a density part that shrinks), docs/smcir.md.
    CHECK(wide[1] < wide[0]);
    CHECK(wide[2] < wide[1]);
    CHECK(wide[2] > 0.0); // what is left at 1024 is a bias, not noise (the interval is far from 0)
}
