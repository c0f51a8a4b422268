// What SMCIR's selection (Algorithm 1 lines 8-19) does to the estimate over time, measured on the
// real sampler without the GPU: `vplgi smcir-selection`, scripts/smcir-experiments and the tests
// (docs/smcir.md, "Selection bias").
//
// Intro
// -----
// Eq. (5) with a receiver that sees every VPL alike (f G V = 1) is
//     Phi = (1/n) sum_i L(y_i) / p(y_i),
// an estimate of the integral of L over the surfaces the set covers (the indirectly visible ones,
// fixed for a still camera). A fresh set (line 1: candidates resampled to uniform in area, nothing
// selected yet) with accurate radiances and Poisson-unbiased densities (eq. 7, self excluded) gives
// it without bias; after the frames, the set's Phi against that value is the bias the selection
// added, as a smooth receiver in the image sees it. It splits into
//   radiance part  Phi / Phi[L_i replaced by a many-sample estimate at the same points] - 1:
//                  the VPLs kept because their radiance estimate came out high;
//   density part   Phi[accurate L] / Phi_fresh - 1: their densities (kept because r_k came out high),
//                  also with densities at 4 k (smooth: the set's real non-uniformity, not kNN noise);
//   area           (1/n) sum 1/p_i = sum pi r_k^2 / k over a fresh set's; `vplgi smcir-selection` also
//                  prints it over the scene's surface area, the area identity where the set covers
//                  every surface (the furnace's sphere, 4 pi R^2; the fresh sets' own estimate there is
//                  +0.5% above it).
// Phi is also recorded after every frame for the drift: the mean of frames [0.9 N, N) over that of
// [0.4 N, 0.5 N), minus 1 (frames counted from the first, warm-up included; conform's definition).
#pragma once

#include <cstdint>
#include <vector>

#include "core/scene/frame_snapshot.h"
#include "core/trace/ray_scene.h"
#include "core/vpl/smcir_sampler.h"

namespace vplgi {

// One set measured (luminance, Rec. 709; see the header comment for each sum).
struct SMCIRSetMeasure {
    double published = 0.0;     // Phi with the published radiances and densities
    double accurate = 0.0;      // Phi with radiances of `referenceSamples` paths, published densities
    double accurateExcluded = 0.0; // ... and densities at the rendering k, self excluded (MATH.md 2)
    double accurateWide = 0.0;  // ... and densities at 4 k, self excluded
    double area = 0.0;          // (1/n) sum 1/p_i, published densities [m^2]
    double areaExcluded = 0.0;  // the same at the rendering k, self excluded
    int count = 0;              // n
};

// Measures the sampler's current set. Radiances by SMCIRSampler::estimateRadianceAgain.
SMCIRSetMeasure measureSMCIRSet(const SMCIRSampler& sampler, int referenceSamples, std::uint32_t seed);

// One seed's run: a fresh set (initialize() without warm-up: frame 0), then `frames` steps of the
// still snapshot (the warm-up counted among them), measured after each frame in `checkpoints`.
struct SMCIRSelectionRun {
    SMCIRSetMeasure fresh;                    // frame 0
    std::vector<SMCIRSetMeasure> checkpoints; // in the order given
    std::vector<double> published;            // Phi after frames 1..frames (driftOf, core/util/metrics.h)
};
SMCIRSelectionRun runSMCIRSelection(const Scene& scene, const RayScene& rays, SMCIRParams params,
                                    const FrameSnapshot& snapshot, int frames, const std::vector<int>& checkpoints,
                                    int referenceSamples);

} // namespace vplgi
