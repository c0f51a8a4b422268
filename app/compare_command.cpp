// `vplgi compare`: renders techniques side by side with path-traced references, still or along a
// scene-file animation, and writes DIR/index.html (images, error heat maps, a metrics table and
// plots of tracked-pixel luminance over time, like SMCIR Fig. 7) plus metrics.csv / metrics.json.
//
// Three steps: parseCompareOptions (every input checked before any GL work), renderFrames (per
// frame: the references when the scene state changed, each technique, its errors and tracked
// pixels) and the report writers of report.h, which take the measured numbers as plain data.
//
// Two references (SMCIR 5.2, Table 1 and Fig. 7):
//  - the full image at --spp samples per pixel, for the image metrics and heat maps (--spp 0: none);
//  - the tracked pixels only, at --reference-spp samples each (65536 by default; the paper used
//    692,100), for the temporal metrics |E| and |E'| at the tracked pixels. Reference noise enters
//    every method's E' and pushes ratios between methods towards 1, so this one is rendered twice
//    with different seeds: |E'| of one against the other is the reference's own |E'|, which must
//    be <= 0.2x the smallest |E'| of any method (printed and in the report).
// Both use the same path-tracer settings: --reference-mode, then what each technique's
// configureReference asks for (SMCIR: clamped indirect, untextured bounces, its bounce cap), then
// the reference.* settings given with --set.
//
// Tracked pixels (--tracked-choice): `indirect` (the default) picks --tracked pixels in indirectly
// lit regions of frame 0 from a cheap path-traced estimate (indirectTrackedPixels in
// core/util/metrics.h says how); `grid` spreads them over the image (trackedPixels).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "cli.h"
#include "commands.h"
#include "core/util/content_hash.h"
#include "core/util/error.h"
#include "core/util/metrics.h"
#include "core/util/params.h"
#include "gl/api/context.h"
#include "reference.h"
#include "report.h"
#include "session.h"

namespace vplgi {

namespace {

std::vector<std::string> splitList(const std::string& text)
{
    std::vector<std::string> items;
    std::stringstream s(text);
    std::string item;
    while (std::getline(s, item, ','))
        if (!item.empty()) items.push_back(item);
    return items;
}

double luminanceAt(const ImageRGBA32F& image, glm::ivec2 p)
{
    const float* c = image.at(p.x, p.y);
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
}

struct CompareOptions {
    SceneOptions scene;
    std::vector<std::string> techniques;
    ImageSize size;
    AnimationOptions animation;
    std::string referenceModeName;            // as given, for the report
    PathTracerParams reference;               // --reference-mode, --spp, then the reference.* settings
    std::set<std::string> referenceKeys;      // the --set keys the reference used
    int trackedCount = 8;
    bool trackedIndirect = true;              // --tracked-choice indirect (else grid)
    int trackedReferenceSpp = 65536;          // --reference-spp
    std::string outDir;
    std::string writeDir;                     // where files go while running (StagedDirectory of outDir)
    std::string cache;
    std::string against;                      // --against: a --techniques entry ("" = none)
    int seeds = 1;                            // --seeds: runs per technique with seeds of its own
};

std::optional<CompareOptions> parseCompareOptions(const std::vector<std::string>& args)
{
    OptionParser parser("vplgi compare",
                        "Renders each technique and a path-traced reference (per frame when the scene or camera\n"
                        "moves; references are cached) and writes DIR/index.html with images, error heat maps,\n"
                        "a metrics table and tracked-pixel luminance plots, plus metrics.csv and metrics.json.");
    addSceneOptions(parser, "set a parameter of the renderer, a technique or reference.*");
    parser.value("techniques", "A,B,...",
                 "techniques to compare; a variant with its own settings is written name[key=value;key=value], "
                 "e.g. smcir[smcir.shading=exhaustive]",
                 "direct");
    addSizeOptions(parser, "image", 320, 180);
    addAnimationOptions(parser, "frames to render and compare", 1);
    parser.value("reference-mode", "M",
                 "reference: full, direct, indirect, clamped or onebounce; techniques are compared by the same "
                 "part (indirect, clamped and onebounce: their radiance minus their direct light)",
                 "full");
    parser.value("spp", "N", "samples per pixel of the full-image reference (image metrics, heat maps); 0: none",
                 "256");
    parser.value("tracked", "N", "tracked pixels for the temporal metrics (SMCIR uses 8)", "8");
    parser.value("tracked-choice", "C",
                 "indirect: tracked pixels in indirectly lit regions of frame 0, well spread; grid: spread over "
                 "the image",
                 "indirect");
    parser.value("reference-spp", "N",
                 "samples per tracked pixel of the tracked-pixel reference (the temporal metrics; rendered twice, "
                 "two seeds, to measure its own |E'|)",
                 "65536");
    parser.value("against", "T",
                 "also compare every technique's image with that of T, one of --techniques: the mean and 99.9th "
                 "percentile of |A - B| after the fixed-exposure tone map (LightSkin+BRSM Fig. 3 and 6), and the ratio of "
                 "|E'| to T's with a 95% bootstrap interval over the tracked pixels");
    parser.value("seeds", "N",
                 "render every technique that has seed parameters of its own N times, with <group>.seed = 1..N: "
                 "|E| and |E'| and the image metrics become means over the seeds with 95% Student-t intervals "
                 "(SMCIR Table 1 over seeds); images and plots stay the first seed's",
                 "1");
    parser.value("out", "DIR", "output directory (created)", "out/compare");
    parser.value("cache", "DIR", "reference cache directory ($VPLGI_CACHE_DIR or out/reference-cache)");
    if (!parser.parse(args)) return std::nullopt;

    CompareOptions o;
    o.scene = sceneOptions(parser);
    o.techniques = splitList(parser.get("techniques"));
    require(!o.techniques.empty(), "--techniques needs at least one technique");
    o.animation = animationOptions(parser, 100000);
    o.size = imageSize(parser, 8, 8192);
    o.trackedCount = parser.getInt("tracked", 1, kMaxTrackedPixels);
    const std::string choice = parser.get("tracked-choice");
    require(choice == "indirect" || choice == "grid",
            "--tracked-choice \"" + choice + "\" must be indirect or grid");
    o.trackedIndirect = choice == "indirect";
    o.trackedReferenceSpp = parser.getInt("reference-spp", 1, 1 << 24);
    o.seeds = parser.getInt("seeds", 1, 1000);
    o.outDir = parser.get("out");
    o.referenceModeName = parser.get("reference-mode");
    o.reference.mode = parseReferenceMode(o.referenceModeName);
    o.reference.spp = parser.getInt("spp", 0, 1 << 24); // 0: no full-image reference (checked by visitParams
                                                         // only when set through reference.spp)
    ParamSetter referenceSetter(o.scene.settings);
    o.reference.visitParams(referenceSetter);
    o.referenceKeys = referenceSetter.usedKeys();
    o.cache = parser.has("cache") ? parser.get("cache") : defaultReferenceCache();
    std::error_code ec;
    require(!std::filesystem::exists(o.cache, ec) || std::filesystem::is_directory(o.cache, ec),
            "--cache " + o.cache + ": not a directory");
    if (parser.has("against")) {
        o.against = parser.get("against");
        require(std::count(o.techniques.begin(), o.techniques.end(), o.against) == 1,
                "--against \"" + o.against + "\" must be one of --techniques");
    }
    return o;
}

struct TechniqueRun {
    std::string name;   // as given to --techniques (a variant keeps its brackets)
    Settings settings;  // --set plus the variant's own
    std::unique_ptr<Session> session;
    std::vector<ImageErrors> frameErrors;
    std::vector<std::vector<double>> tracked; // [frame][pixel] luminance
    std::vector<double> frameMilliseconds;
    ImageRGBA32F image;                      // the compared part of the last frame
    std::vector<ImageErrors> againstErrors;  // per frame, against the --against run's image
};

struct FrameLoopResult {
    std::vector<std::vector<double>> referenceTracked;      // [frame][pixel] luminance, first seed
    std::vector<std::vector<double>> referenceCheckTracked; // [frame][pixel] luminance, second seed
    int referencesRendered = 0;
    double trackedReferenceSeconds = 0.0; // both seeds, rendered (not cached) frames
};

// The tracked pixels and how they were chosen (for the report).
struct TrackedChoice {
    std::vector<glm::ivec2> pixels;
    std::string description;
};

// Samples per pixel and seed of the cheap estimate behind --tracked-choice indirect: enough that the
// 3x3-averaged direct/indirect ratio is stable, cheap next to one reference frame.
constexpr int kTrackedEstimateSpp = 16;
constexpr std::uint32_t kTrackedEstimateSeed = 1;

TrackedChoice chooseTrackedPixels(const CompareOptions& o, Session& lead)
{
    TrackedChoice choice;
    const std::string grid = "grid: spread over the image (trackedPixels)";
    if (!o.trackedIndirect) {
        choice.pixels = trackedPixels(o.size.width, o.size.height, o.trackedCount);
        choice.description = grid;
        return choice;
    }
    lead.applyAnimations(o.animation.timeOf(0));
    const RayScene rays(lead.scene());
    PathTracerParams estimate = o.reference;
    estimate.spp = kTrackedEstimateSpp;
    estimate.seed = kTrackedEstimateSeed;
    estimate.timeBudgetSeconds = 0.0;
    estimate.progress = false;
    estimate.mode = PathTracerParams::Mode::Direct;
    const ImageRGBA32F direct =
        renderReference(lead.scene(), rays, lead.camera(), o.size.width, o.size.height, estimate).image;
    estimate.mode = PathTracerParams::Mode::Indirect;
    const ImageRGBA32F indirect =
        renderReference(lead.scene(), rays, lead.camera(), o.size.width, o.size.height, estimate).image;
    choice.pixels = indirectTrackedPixels(direct, indirect, o.trackedCount);
    if (choice.pixels.empty()) {
        choice.pixels = trackedPixels(o.size.width, o.size.height, o.trackedCount);
        choice.description = "grid (fallback: fewer than " + std::to_string(o.trackedCount) +
                             " indirectly lit pixels in frame 0)";
        std::fprintf(stderr, "tracked pixels: %s\n", choice.description.c_str());
        return choice;
    }
    choice.description = "indirect: indirect >= direct light and >= " + formatNumber(kTrackedMinIndirectFraction) +
                         "x the 90th percentile of indirect luminance (3x3 means of a " +
                         std::to_string(kTrackedEstimateSpp) +
                         " spp path-traced estimate of frame 0, seed " + std::to_string(kTrackedEstimateSeed) +
                         "), away from the region's edges, farthest-point spread from the centre";
    return choice;
}

std::vector<double> luminances(const std::vector<glm::vec3>& radiance)
{
    std::vector<double> values;
    for (const glm::vec3& c : radiance) values.push_back(0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b);
    return values;
}

// The part of a technique's image that the reference's mode simulates (compare like with like).
ImageRGBA32F comparablePart(const Renderer& renderer, PathTracerParams::Mode mode)
{
    if (mode == PathTracerParams::Mode::Full) return renderer.readRadiance();
    if (mode == PathTracerParams::Mode::Direct) return renderer.readDirect();
    return indirectPart(renderer);
}

std::string comparedPartText(PathTracerParams::Mode mode)
{
    if (mode == PathTracerParams::Mode::Full) return "each technique's whole image";
    if (mode == PathTracerParams::Mode::Direct) return "each technique's direct light";
    return "each technique's indirect light (its image minus its direct light)";
}

// Renders one frame of one technique and records its errors, tracked pixels and completed timings.
// `reference` is empty without a full-image reference (--spp 0): no image errors then.
void renderTechniqueFrame(const CompareOptions& o, TechniqueRun& run, const ImageRGBA32F& reference,
                          const std::vector<glm::ivec2>& tracked, int frame, double exposure, bool keepImages)
{
    Renderer& renderer = run.session->renderer();
    renderer.renderFrame(run.session->camera(), o.size.width, o.size.height, o.animation.timeOf(frame));
    // GPU timestamp queries publish frames late: take whichever frames completed (the rest after the loop).
    for (const gl::FrameTimes& f : renderer.timer().takeCompletedFrames()) run.frameMilliseconds.push_back(f.total());
    run.image = comparablePart(renderer, o.reference.mode);
    const ImageRGBA32F& image = run.image;
    const bool haveReference = !reference.pixels.empty();
    if (haveReference) run.frameErrors.push_back(compareImages(image, reference, exposure));
    std::vector<double> values;
    for (glm::ivec2 p : tracked) values.push_back(luminanceAt(image, p));
    run.tracked.push_back(values);
    if (keepImages && compareKeepsImages(frame, o.animation.frames)) {
        writeImage(o.writeDir + "/" + compareImageName(run.name, frame, ".png"), renderer.readDisplay());
        writeImage(o.writeDir + "/" + compareImageName(run.name, frame, ".exr"), image);
        if (haveReference)
            writeImage(o.writeDir + "/" + compareImageName(run.name, frame, "-error.png"),
                       errorHeatMap(image, reference, exposure, 0.25));
    }
}

// The frame loop: animations advance, the reference is obtained again (cache first) whenever the
// scene content or camera changed, then every technique renders and is measured against it.
// Seeds 2..N of compare --seeds write no images and take no --against errors; their references come
// from the cache the first seed's loop filled.
FrameLoopResult renderFrames(const CompareOptions& o, std::vector<TechniqueRun>& runs,
                             const std::vector<glm::ivec2>& tracked, double exposure, int seed = 1)
{
    const bool firstSeed = seed == 1;
    // The reference follows the first session's scene state (all sessions animate identically).
    Session& lead = *runs.front().session;
    FrameLoopResult result;
    ImageRGBA32F reference; // stays empty with --spp 0
    std::vector<double> trackedFirst, trackedSecond;
    std::uint64_t referenceKey = 0;
    for (int frame = 0; frame < o.animation.frames; ++frame) {
        for (TechniqueRun& run : runs) run.session->applyAnimations(o.animation.timeOf(frame));
        Hasher state;
        state.value(hashSceneContent(lead.scene()));
        hashCamera(state, lead.camera());
        if (frame == 0 || state.digest() != referenceKey) {
            RayScene rays(lead.scene());
            if (o.reference.spp > 0) {
                ReferenceRequest request{lead.scene(), rays, lead.camera(), o.size.width, o.size.height, o.reference,
                                         o.cache, true};
                reference = obtainReference(request).image;
            }
            // The tracked-pixel reference, twice: the second seed only measures the first's noise.
            PathTracerParams params = o.reference;
            params.spp = o.trackedReferenceSpp;
            params.timeBudgetSeconds = 0.0;
            params.progress = false;
            PixelReferenceRequest request{lead.scene(), rays, lead.camera(), o.size.width, o.size.height, tracked,
                                          params, o.cache};
            const CachedPixelReference first = obtainPixelReference(request);
            request.params.seed = params.seed + 1;
            const CachedPixelReference second = obtainPixelReference(request);
            trackedFirst = luminances(first.radiance);
            trackedSecond = luminances(second.radiance);
            result.trackedReferenceSeconds += first.seconds + second.seconds;
            referenceKey = state.digest();
            ++result.referencesRendered;
        }
        result.referenceTracked.push_back(trackedFirst);
        result.referenceCheckTracked.push_back(trackedSecond);
        if (firstSeed && o.reference.spp > 0 && compareKeepsImages(frame, o.animation.frames)) {
            writeImage(o.writeDir + "/" + compareImageName("reference", frame, ".exr"), reference);
            writeImage(o.writeDir + "/" + compareImageName("reference", frame, ".png"),
                       toneMapImage(reference, exposure));
        }
        for (TechniqueRun& run : runs) renderTechniqueFrame(o, run, reference, tracked, frame, exposure, firstSeed);
        if (firstSeed && !o.against.empty()) {
            const TechniqueRun& base = *std::find_if(runs.begin(), runs.end(),
                                                     [&](const TechniqueRun& r) { return r.name == o.against; });
            for (TechniqueRun& run : runs) {
                run.againstErrors.push_back(compareImages(run.image, base.image, exposure));
                if (&run != &base && compareKeepsImages(frame, o.animation.frames))
                    writeImage(o.writeDir + "/" + compareImageName(run.name, frame, "-difference.png"),
                               errorHeatMap(run.image, base.image, exposure, 0.05));
            }
        }
        if (o.seeds > 1)
            std::fprintf(stderr, "frame %d/%d done (seed %d/%d)\n", frame + 1, o.animation.frames, seed, o.seeds);
        else
            std::fprintf(stderr, "frame %d/%d done\n", frame + 1, o.animation.frames);
    }
    for (TechniqueRun& run : runs) {
        gl::PassTimer& timer = run.session->renderer().timer();
        timer.resolve(true);
        for (const gl::FrameTimes& f : timer.takeCompletedFrames()) run.frameMilliseconds.push_back(f.total());
    }
    return result;
}

// Image errors averaged, over a run's frames or over the seeds (zero for none: no full-image reference).
ImageErrors averageErrors(const std::vector<ImageErrors>& errors)
{
    ImageErrors mean;
    const double count = static_cast<double>(std::max<std::size_t>(1, errors.size()));
    for (const ImageErrors& e : errors) {
        mean.meanAbsToneMapped += e.meanAbsToneMapped / count;
        mean.p999AbsToneMapped += e.p999AbsToneMapped / count;
        mean.rmse += e.rmse / count;
        mean.relativeMSE += e.relativeMSE / count;
        mean.meanRelativeLuminance += e.meanRelativeLuminance / count;
    }
    return mean;
}

// Per technique: errors averaged over frames, temporal errors over the tracked pixels, median frame time.
CompareTechniqueResult summarize(const TechniqueRun& run, const std::vector<std::vector<double>>& referenceTracked,
                                 double exposure, const Settings& settings)
{
    CompareTechniqueResult result;
    result.name = run.name;
    result.meanErrors = averageErrors(run.frameErrors);
    result.seedImageErrors = {result.meanErrors};
    const double againstFrames = static_cast<double>(std::max<std::size_t>(1, run.againstErrors.size()));
    for (const ImageErrors& e : run.againstErrors) {
        result.againstErrors.meanAbsToneMapped += e.meanAbsToneMapped / againstFrames;
        result.againstErrors.p999AbsToneMapped += e.p999AbsToneMapped / againstFrames;
    }
    result.temporal = temporalErrors(run.tracked, referenceTracked, exposure);
    result.seedAbsE = {result.temporal.meanAbsError};
    result.seedAbsEPrime = {result.temporal.meanAbsDerivative};
    std::vector<double> ms = run.frameMilliseconds;
    std::sort(ms.begin(), ms.end());
    result.medianFrameMs = ms.empty() ? 0.0 : ms[ms.size() / 2];
    result.tracked = run.tracked;
    // The --set overrides this technique's session used (its row's settings in the report).
    for (const auto& [key, value] : settings)
        if (run.session->usedKeys().count(key) && key.rfind("reference.", 0) != 0)
            result.settings += (result.settings.empty() ? "" : " ") + key + "=" + value;
    return result;
}

// The report's plain data: the inputs that describe the run and each technique's summary.
CompareReport makeReport(const CompareOptions& o, const Scene& scene, const std::vector<TechniqueRun>& runs,
                         const FrameLoopResult& loop, const TrackedChoice& tracked, double exposure)
{
    CompareReport report;
    report.sceneSource = scene.source;
    report.sceneName = scene.name;
    report.width = o.size.width;
    report.height = o.size.height;
    report.frames = o.animation.frames;
    report.fps = o.animation.fps;
    report.exposure = exposure;
    report.referenceMode = o.referenceModeName;
    report.referenceSpp = o.reference.spp;
    report.referencesRendered = loop.referencesRendered;
    report.comparedPart = comparedPartText(o.reference.mode);
    report.imageMetrics = o.reference.spp > 0;
    report.referenceSettings = "maxDepth " + std::to_string(o.reference.maxDepth) + ", clampGeometry " +
                               formatNumber(o.reference.clampGeometry) + " 1/m^2 (clamped mode), untexturedBounces " +
                               (o.reference.untexturedBounces ? "true" : "false") + ", seed " +
                               std::to_string(o.reference.seed);
    report.trackedPixels = tracked.pixels;
    report.trackedChoice = tracked.description;
    report.referenceTracked = loop.referenceTracked;
    report.trackedReferenceSpp = o.trackedReferenceSpp;
    report.trackedReferenceSeconds = loop.trackedReferenceSeconds;
    report.referenceSelf = temporalErrors(loop.referenceCheckTracked, loop.referenceTracked, exposure);
    report.against = o.against;
    report.seeds = o.seeds;
    for (const TechniqueRun& run : runs)
        report.techniques.push_back(summarize(run, loop.referenceTracked, exposure, run.settings));
    return report;
}

// --against: every technique's |E'| over the base's, with its interval over the tracked pixels
// (after addSeeds: of the per-pixel means over the seeds).
void addAgainstRatios(CompareReport& report)
{
    if (report.against.empty()) return;
    const auto base = std::find_if(report.techniques.begin(), report.techniques.end(),
                                   [&](const CompareTechniqueResult& t) { return t.name == report.against; });
    for (CompareTechniqueResult& t : report.techniques)
        t.againstEPrime = temporalDerivativeRatio(t.temporal, base->temporal);
}

// --seeds N: the first seed is the run already in `report` (every technique's <group>.seed defaults
// to 1; parseSeedKeys refused a --set of them). Here each technique with seed keys renders the same
// frames again with <group>.seed = 2..N, one seed at a time (the sessions of one seed live only for
// its loop), against the same tracked-pixel reference. Its temporal metrics become the mean over the
// seeds (per tracked pixel too, for --against), with the 95% Student-t interval of |E| and |E'|.
void addSeeds(const CompareOptions& o, const std::vector<TechniqueRun>& first, const std::vector<std::string>& names,
              const std::vector<std::vector<std::string>>& seedKeys, const std::vector<glm::ivec2>& tracked,
              const FrameLoopResult& loop, double exposure, CompareReport& report)
{
    std::vector<std::vector<TemporalErrors>> perSeed(first.size());
    for (std::size_t i = 0; i < first.size(); ++i) perSeed[i].push_back(report.techniques[i].temporal);
    std::vector<std::vector<ImageErrors>> imagePerSeed(first.size());
    for (std::size_t i = 0; i < first.size(); ++i) imagePerSeed[i].push_back(report.techniques[i].meanErrors);
    for (int seed = 2; seed <= o.seeds; ++seed) {
        std::vector<std::size_t> which;
        std::vector<std::string> seedNames;
        std::vector<Settings> seedSettings;
        for (std::size_t i = 0; i < first.size(); ++i) {
            if (seedKeys[i].empty()) continue;
            which.push_back(i);
            seedNames.push_back(names[i]);
            Settings settings = first[i].settings;
            for (const std::string& key : seedKeys[i]) settings.emplace_back(key, std::to_string(seed));
            seedSettings.push_back(settings);
        }
        if (which.empty()) break;
        std::vector<std::unique_ptr<Session>> sessions =
            createSessions(o.scene.sceneSpec, o.scene.camera, seedNames, seedSettings, o.referenceKeys);
        std::vector<TechniqueRun> runs;
        for (std::size_t k = 0; k < which.size(); ++k) {
            TechniqueRun run;
            run.name = first[which[k]].name;
            run.settings = seedSettings[k];
            run.session = std::move(sessions[k]);
            run.session->createRenderer();
            runs.push_back(std::move(run));
        }
        renderFrames(o, runs, tracked, exposure, seed);
        for (std::size_t k = 0; k < which.size(); ++k) {
            perSeed[which[k]].push_back(temporalErrors(runs[k].tracked, loop.referenceTracked, exposure));
            imagePerSeed[which[k]].push_back(averageErrors(runs[k].frameErrors));
        }
    }
    for (std::size_t i = 0; i < first.size(); ++i) {
        CompareTechniqueResult& t = report.techniques[i];
        const std::vector<TemporalErrors>& seeds = perSeed[i];
        t.seedAbsE.clear();
        t.seedAbsEPrime.clear();
        for (const TemporalErrors& e : seeds) {
            t.seedAbsE.push_back(e.meanAbsError);
            t.seedAbsEPrime.push_back(e.meanAbsDerivative);
        }
        t.temporal.meanAbsError = meanInterval(t.seedAbsE).mean;
        t.temporal.meanAbsDerivative = meanInterval(t.seedAbsEPrime).mean;
        // The image metrics (with a full-image reference): each the mean over the seeds.
        t.seedImageErrors = imagePerSeed[i];
        t.meanErrors = averageErrors(t.seedImageErrors);
        for (std::size_t p = 0; p < t.temporal.pixelAbsDerivative.size(); ++p) {
            double sum = 0.0;
            for (const TemporalErrors& e : seeds) sum += e.pixelAbsDerivative[p];
            t.temporal.pixelAbsDerivative[p] = sum / static_cast<double>(seeds.size());
        }
    }
}

// The seed keys of each run's technique; with --seeds > 1, a --set of one of them is an error (the
// seeds are 1..N).
std::vector<std::vector<std::string>> parseSeedKeys(const CompareOptions& o, const std::vector<TechniqueRun>& runs)
{
    std::vector<std::vector<std::string>> keys;
    for (const TechniqueRun& run : runs) {
        keys.push_back(run.session->techniqueSeedKeys());
        if (o.seeds == 1) continue;
        for (const auto& [key, value] : run.settings)
            require(std::find(keys.back().begin(), keys.back().end(), key) == keys.back().end(),
                    "--seeds " + std::to_string(o.seeds) + " sets " + key + " to 1.." + std::to_string(o.seeds) +
                        ": do not also set it (" + run.name + ")");
    }
    return keys;
}

} // namespace

int runCompare(const std::vector<std::string>& args)
{
    std::optional<CompareOptions> parsed = parseCompareOptions(args);
    if (!parsed) return 0;
    CompareOptions& o = *parsed;

    std::unique_ptr<gl::Context> context; // outlives the sessions' GL objects
    // "name[key=value;...]": technique `name` with these settings after the --set ones.
    std::vector<std::string> names;
    std::vector<Settings> perRun;
    for (const std::string& entry : o.techniques) {
        require(std::count(o.techniques.begin(), o.techniques.end(), entry) == 1,
                "--techniques: \"" + entry + "\" given twice");
        Settings settings = o.scene.settings;
        const TechniqueEntry variant = parseTechniqueEntry(entry);
        names.push_back(variant.technique);
        settings.insert(settings.end(), variant.settings.begin(), variant.settings.end());
        perRun.push_back(settings);
    }
    std::vector<std::unique_ptr<Session>> sessions =
        createSessions(o.scene.sceneSpec, o.scene.camera, names, perRun, o.referenceKeys);
    std::vector<TechniqueRun> runs;
    for (std::size_t i = 0; i < o.techniques.size(); ++i) {
        TechniqueRun run;
        run.name = o.techniques[i];
        run.settings = perRun[i];
        run.session = std::move(sessions[i]);
        runs.push_back(std::move(run));
    }
    const std::vector<std::vector<std::string>> seedKeys = parseSeedKeys(o, runs);

    // Everything is written under a temporary name and moved into place at the end: a failure
    // part-way leaves no half report.
    StagedDirectory staged(o.outDir);
    o.writeDir = staged.path();
    std::filesystem::create_directories(o.writeDir + "/images");
    context = gl::createHeadlessContext();
    for (TechniqueRun& run : runs) run.session->createRenderer();
    // What the reference must simulate to be comparable (SMCIR: untextured bounces, the same clamp).
    for (TechniqueRun& run : runs) run.session->renderer().technique().configureReference(o.reference, o.referenceKeys);

    Session& lead = *runs.front().session;
    const double exposure = lead.renderer().params().exposure;
    const TrackedChoice tracked = chooseTrackedPixels(o, lead);
    const FrameLoopResult loop = renderFrames(o, runs, tracked.pixels, exposure);

    CompareReport report = makeReport(o, lead.scene(), runs, loop, tracked, exposure);
    if (o.seeds > 1) addSeeds(o, runs, names, seedKeys, tracked.pixels, loop, exposure, report);
    addAgainstRatios(report);
    writeCompareReport(o.writeDir, report);
    staged.commit();
    std::printf("%s", compareTemporalSummary(report).c_str());
    std::printf("%s/index.html\n", o.outDir.c_str());
    return 0;
}

} // namespace vplgi
