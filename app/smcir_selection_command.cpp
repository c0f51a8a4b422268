// `vplgi smcir-selection`: what SMCIR's selection (Algorithm 1 lines 8-19) adds to the estimate
// over the frames of a still camera, per option set, over seeds; CPU only (Embree), no GL.
// core/vpl/smcir_selection.h defines every column; docs/smcir.md, "Selection bias", has the runs.
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "commands.h"
#include "core/scene/scene_loader.h"
#include "core/util/error.h"
#include "core/util/metrics.h"
#include "core/util/params.h"
#include "core/util/progress.h"
#include "core/vpl/smcir_selection.h"

namespace vplgi {

namespace {

struct Variant {
    std::string label; // its settings as given ("defaults" for none)
    Settings settings;
};

std::vector<int> parseIntList(const std::string& text, const std::string& option)
{
    std::vector<int> values;
    std::stringstream s(text);
    for (std::string item; std::getline(s, item, ',');) {
        try {
            std::size_t used = 0;
            values.push_back(std::stoi(item, &used));
            require(used == item.size(), "");
        } catch (const std::exception&) {
            throw Error("--" + option + " must be a comma-separated list of integers (got \"" + text + "\")");
        }
    }
    return values;
}

} // namespace

int runSMCIRSelection(const std::vector<std::string>& args)
{
    OptionParser parser(
        "vplgi smcir-selection",
        "Runs SMCIR's sampler (CPU, no GL) on a still camera and measures what its selection adds to the\n"
        "eq. (5) estimate of a receiver that sees every VPL alike: the bias against a fresh set, split\n"
        "into a radiance part and a density part, the area identity, and the drift over the frames;\n"
        "mean and 95% interval over the seeds, per option set (--variant).");
    parser.value("scene", "NAME|FILE", "built-in scene or scene file (its smcir.* settings apply)", "cornell");
    parser.value("variant", "KEY=VALUE;...", "an option set to measure (repeatable; none: the defaults)", "", true);
    parser.value("set", "KEY=VALUE", "an smcir.* setting for every variant (repeatable)", "", true);
    parser.value("seeds", "N", "seeds per variant (smcir.seed = 1..N)", "8");
    parser.value("frames", "N", "frames per seed, the 100 warm-up frames of the paper counted among them", "300");
    parser.value("checkpoints", "A,B,...", "frames after which the set is measured (default: 100 and --frames)");
    parser.value("reference-samples", "N", "paths of the accurate radiance estimates", "512");
    parser.value("aspect", "W/H", "the view's aspect ratio (camera rays)", "1.7777778");
    parser.value("json", "FILE", "also write the results as JSON");
    if (!parser.parse(args)) return 0;

    const int seeds = parser.getInt("seeds", 1, 1000);
    const int frames = parser.getInt("frames", 10, 1000000);
    const int referenceSamples = parser.getInt("reference-samples", 1, 1 << 20);
    const float aspect = parser.getFloat("aspect", 0.01f, 100.0f);
    std::vector<int> checkpoints = parser.has("checkpoints") ? parseIntList(parser.get("checkpoints"), "checkpoints")
                                                             : std::vector<int>{std::min(100, frames), frames};
    for (int c : checkpoints)
        require(c >= 0 && c <= frames, "--checkpoints must lie in [0, --frames] (got " + std::to_string(c) + ")");

    SceneDescription description = loadSceneSpec(parser.get("scene"));
    const Scene& scene = description.scene;
    require(!scene.cameras.empty(), "the scene has no camera");
    // The scene file's settings of the sampler (the technique's own, smcir.visibility and the like, do
    // not apply here).
    ParamDumper known;
    SMCIRParams{}.visitParams(known);
    Settings common;
    for (const auto& s : description.settings)
        if (known.values().count(s.first)) common.push_back(s);
    for (const std::string& s : parser.getAll("set"))
        common.push_back(parseSetting(s));
    std::vector<Variant> variants;
    for (const std::string& text : parser.getAll("variant")) {
        Variant v{text.empty() ? "defaults" : text, {}};
        std::stringstream s(text);
        for (std::string item; std::getline(s, item, ';');)
            if (!item.empty()) v.settings.push_back(parseSetting(item));
        variants.push_back(v);
    }
    if (variants.empty()) variants.push_back(Variant{"defaults", {}});

    // Every option set is checked before anything runs or prints: a bad key is one error line.
    std::vector<SMCIRParams> variantParams;
    for (const Variant& variant : variants) {
        SMCIRParams params;
        Settings settings = common;
        settings.insert(settings.end(), variant.settings.begin(), variant.settings.end());
        ParamSetter setter(settings);
        params.visitParams(setter);
        setter.finish();
        variantParams.push_back(params);
    }

    const RayScene rays(scene);
    const FrameSnapshot snapshot = FrameSnapshot::of(scene, scene.cameras[0], aspect);
    const ProgressSink progress = terminalProgressBar();
    nlohmann::ordered_json json = {{"scene", parser.get("scene")}, {"seeds", seeds}, {"frames", frames},
                                   {"referenceSamples", referenceSamples}, {"variants", nlohmann::ordered_json::array()}};
    // The area identity against the scene's surfaces themselves: the set's area estimate is over the
    // surfaces it covers, every surface in the furnace (where this column is the identity of
    // "SMCIR without drift"); elsewhere the fresh set's estimate (the `area` column) is the yardstick.
    const double surfaceArea = sceneSurfaceArea(scene);
    std::printf("| option set | frames | bias | radiance part | density part | density part, 4k | area | area / all surfaces |\n"
                "|---|---|---|---|---|---|---|---|\n");
    std::vector<std::string> driftLines;
    for (std::size_t v = 0; v < variants.size(); ++v) {
        const Variant& variant = variants[v];
        SMCIRParams params = variantParams[v];
        std::vector<SMCIRSelectionRun> runs;
        for (int seed = 1; seed <= seeds; ++seed) {
            params.seed = static_cast<std::uint32_t>(seed);
            runs.push_back(runSMCIRSelection(scene, rays, params, snapshot, frames, checkpoints, referenceSamples));
            progress("smcir-selection " + variant.label, seed, seeds);
        }
        // The reference: a fresh set's Phi with accurate radiances, self-excluded densities, over the seeds.
        std::vector<double> freshPhi, freshWide, freshArea;
        for (const SMCIRSelectionRun& r : runs) {
            freshPhi.push_back(r.fresh.accurateExcluded);
            freshWide.push_back(r.fresh.accurateWide);
            freshArea.push_back(r.fresh.areaExcluded);
        }
        const MeanInterval phi0 = meanInterval(freshPhi), wide0 = meanInterval(freshWide), area0 = meanInterval(freshArea);
        nlohmann::ordered_json vj = {{"variant", variant.label},
                                     {"freshPhi", {{"mean", phi0.mean}, {"halfWidth95", phi0.halfWidth}}},
                                     {"freshArea", area0.mean},
                                     {"surfaceArea", surfaceArea},
                                     {"checkpoints", nlohmann::ordered_json::array()}};
        for (std::size_t c = 0; c < checkpoints.size(); ++c) {
            std::vector<double> bias, radiance, density, densityWide, area, areaOfSurfaces;
            for (const SMCIRSelectionRun& r : runs) {
                const SMCIRSetMeasure& m = r.checkpoints[c];
                bias.push_back(m.published / phi0.mean - 1.0);
                radiance.push_back(m.accurate > 0.0 ? m.published / m.accurate - 1.0 : 0.0);
                density.push_back(m.accurate / phi0.mean - 1.0);
                densityWide.push_back(m.accurateWide / wide0.mean - 1.0);
                area.push_back(m.area / area0.mean - 1.0);
                areaOfSurfaces.push_back(m.area / surfaceArea - 1.0);
            }
            const MeanInterval b = meanInterval(bias), rp = meanInterval(radiance), dp = meanInterval(density),
                               dw = meanInterval(densityWide), ar = meanInterval(area), as = meanInterval(areaOfSurfaces);
            std::printf("| %s | %d | %s | %s | %s | %s | %s | %s |\n", variant.label.c_str(), checkpoints[c],
                        percentText(b).c_str(), percentText(rp).c_str(), percentText(dp).c_str(), percentText(dw).c_str(),
                        percentText(ar).c_str(), percentText(as).c_str());
            auto j = [](const MeanInterval& i) { return nlohmann::ordered_json{{"mean", i.mean}, {"halfWidth95", i.halfWidth}}; };
            vj["checkpoints"].push_back({{"frames", checkpoints[c]}, {"bias", j(b)}, {"radiancePart", j(rp)},
                                         {"densityPart", j(dp)}, {"densityPart4k", j(dw)}, {"area", j(ar)},
                                         {"areaOfSurfaces", j(as)}});
        }
        std::vector<double> drift;
        for (const SMCIRSelectionRun& r : runs)
            drift.push_back(driftOf(r.published));
        const MeanInterval d = meanInterval(drift);
        vj["drift"] = {{"mean", d.mean}, {"halfWidth95", d.halfWidth}};
        char line[256];
        std::snprintf(line, sizeof line, "| %s | %s | %.2f%% |", variant.label.c_str(), percentText(d).c_str(),
                      100.0 * phi0.halfWidth / phi0.mean);
        driftLines.push_back(line);
        json["variants"].push_back(vj);
        std::fflush(stdout);
    }
    std::printf("\nDrift over %d frames (Phi of frames [0.9 N, N) over [0.4 N, 0.5 N), minus 1), and the fresh "
                "reference's own 95%% half-width:\n\n| option set | drift | reference noise |\n|---|---|---|\n",
                frames);
    for (const std::string& line : driftLines)
        std::printf("%s\n", line.c_str());
    if (parser.has("json")) {
        const std::string path = parser.get("json");
        const std::string temporary = path + ".partial";
        {
            std::ofstream out(temporary);
            require(static_cast<bool>(out), path + ": cannot write");
            out << json.dump(2) << "\n";
            require(static_cast<bool>(out), path + ": write failed");
        }
        require(std::rename(temporary.c_str(), path.c_str()) == 0, path + ": cannot write");
    }
    return 0;
}

} // namespace vplgi
