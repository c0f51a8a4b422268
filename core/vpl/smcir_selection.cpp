#include "core/vpl/smcir_selection.h"

#include <algorithm>

#include "core/util/error.h"
#include "core/util/knn.h"

namespace vplgi {

namespace {

double luminanceOf(const glm::vec3& c)
{
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

// (1/n) sum_i 1/p_i for eq. (7) with k others (self excluded) at each valid VPL; inverse[i] = 1/p_i.
std::vector<double> inverseDensitiesExcluded(const std::vector<glm::vec3>& positions, std::size_t k)
{
    const std::size_t n = positions.size();
    std::vector<double> inverse(n, 0.0);
    if (n < 2) return inverse;
    k = std::min(k, n - 1);
    const KNNIndex index(positions);
    for (std::size_t i = 0; i < n; ++i) {
        const float density = estimateKNNDensity(k, n, index.kthDistanceSquared(positions[i], k + 1));
        inverse[i] = density > 0.0f ? 1.0 / density : 0.0;
    }
    return inverse;
}

} // namespace

SMCIRSetMeasure measureSMCIRSet(const SMCIRSampler& sampler, int referenceSamples, std::uint32_t seed)
{
    const std::vector<glm::vec3> accurate = sampler.estimateRadianceAgain(referenceSamples, seed);
    const std::vector<VPL>& slots = sampler.vpls().slots;
    std::vector<glm::vec3> positions;
    std::vector<std::size_t> valid;
    for (std::size_t slot = 0; slot < slots.size(); ++slot)
        if (slots[slot].valid) {
            positions.push_back(slots[slot].position);
            valid.push_back(slot);
        }
    SMCIRSetMeasure m;
    m.count = static_cast<int>(valid.size());
    if (valid.empty()) return m;
    const SMCIRParams& params = sampler.params();
    const std::size_t k = static_cast<std::size_t>(params.knnRender > 0 ? params.knnRender
                                                                        : computeRenderingK(params.vplCount));
    const std::vector<double> excluded = inverseDensitiesExcluded(positions, k);
    const std::vector<double> wide = inverseDensitiesExcluded(positions, 4 * k);
    const double n = static_cast<double>(valid.size());
    for (std::size_t i = 0; i < valid.size(); ++i) {
        const VPL& vpl = slots[valid[i]];
        const double inverse = vpl.density > 0.0f ? 1.0 / vpl.density : 0.0;
        const double published = luminanceOf(vpl.radiance), truth = luminanceOf(accurate[valid[i]]);
        m.published += published * inverse / n;
        m.accurate += truth * inverse / n;
        m.accurateExcluded += truth * excluded[i] / n;
        m.accurateWide += truth * wide[i] / n;
        m.area += inverse / n;
        m.areaExcluded += excluded[i] / n;
    }
    return m;
}

SMCIRSelectionRun runSMCIRSelection(const Scene& scene, const RayScene& rays, SMCIRParams params,
                                    const FrameSnapshot& snapshot, int frames, const std::vector<int>& checkpoints,
                                    int referenceSamples)
{
    require(frames >= 0, "smcir selection: frames must be >= 0");
    for (int c : checkpoints)
        require(c >= 0 && c <= frames, "smcir selection: checkpoint " + std::to_string(c) + " is not in [0, frames]");
    params.warmupIterations = 0; // the warm-up is counted among the frames
    SMCIRSampler sampler(scene, rays, params);
    sampler.initialize(snapshot);
    SMCIRSelectionRun run;
    // Reference radiance seeds differ per checkpoint and from the sampler's streams.
    const std::uint32_t base = 0x5E1EC7u ^ (params.seed * 0x9E3779B9u);
    run.fresh = measureSMCIRSet(sampler, referenceSamples, base);
    run.checkpoints.resize(checkpoints.size());
    auto measureIf = [&](int frame) {
        for (std::size_t c = 0; c < checkpoints.size(); ++c)
            if (checkpoints[c] == frame)
                run.checkpoints[c] = measureSMCIRSet(sampler, referenceSamples, base + static_cast<std::uint32_t>(frame) + 1);
    };
    measureIf(0);
    for (int frame = 1; frame <= frames; ++frame) {
        sampler.step(snapshot);
        double phi = 0.0;
        const std::vector<VPL>& slots = sampler.vpls().slots;
        const double n = static_cast<double>(sampler.vpls().validCount());
        for (const VPL& vpl : slots)
            if (vpl.valid && vpl.density > 0.0f) phi += luminanceOf(vpl.radiance) / vpl.density / n;
        run.published.push_back(phi);
        measureIf(frame);
    }
    return run;
}

} // namespace vplgi
