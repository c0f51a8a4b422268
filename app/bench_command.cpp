// `vplgi bench`: per-pass timings of a technique over frames (median, min, max), with CPU stage
// statistics the technique reports, as a markdown table and JSON; `--against` runs a second
// technique in the same process and prints ratios (this machine is noisy: compare within one run).
#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "commands.h"
#include "core/util/error.h"
#include "core/util/image_io.h"
#include "core/util/params.h"
#include "core/trace/ray_scene.h"
#include "gl/api/context.h"
#include "report.h"
#include "session.h"

namespace vplgi {

namespace {

using Json = nlohmann::ordered_json;

struct PassStats {
    std::vector<double> samples; // [ms] per frame in which the pass ran
    double median() const
    {
        std::vector<double> s = samples;
        std::sort(s.begin(), s.end());
        return s.empty() ? 0.0 : (s.size() % 2 ? s[s.size() / 2] : 0.5 * (s[s.size() / 2 - 1] + s[s.size() / 2]));
    }
    double min() const { return samples.empty() ? 0.0 : *std::min_element(samples.begin(), samples.end()); }
    double max() const { return samples.empty() ? 0.0 : *std::max_element(samples.begin(), samples.end()); }
};

struct BenchResult {
    std::string technique;
    std::vector<std::string> order;        // passes in first-seen order
    std::map<std::string, PassStats> passes;
    PassStats total;
    std::map<std::string, PassStats> stats; // technique statistics per frame (rays, VPLs, ...)
};

BenchResult benchOne(Session& session, ImageSize size, const AnimationOptions& animation, int warmup)
{
    BenchResult r;
    r.technique = session.techniqueName();
    gl::PassTimer& timer = session.renderer().timer();
    // GPU timestamp queries publish a frame 1-3 frames after it was rendered (at once with glFinish +
    // wall clock), so samples are taken as frames complete and matched by the index of the frame that
    // issued them; the last frames are flushed after the loop.
    timer.resolve(true);
    timer.takeCompletedFrames();
    const std::int64_t firstTimed = timer.framesBegun() + warmup;
    auto addCompleted = [&] {
        for (const gl::FrameTimes& f : timer.takeCompletedFrames()) {
            if (f.frame < firstTimed) continue;
            for (const gl::PassTime& t : f.passes) { // nested scopes appear as "parent / child"
                if (!r.passes.count(t.path)) r.order.push_back(t.path);
                r.passes[t.path].samples.push_back(t.milliseconds);
            }
            r.total.samples.push_back(f.total());
        }
    };
    for (int frame = 0; frame < warmup + animation.frames; ++frame) {
        const float time = animation.timeOf(frame);
        session.applyAnimations(time);
        session.renderer().renderFrame(session.camera(), size.width, size.height, time);
        addCompleted();
        if (frame < warmup) continue;
        for (const auto& [name, value] : session.renderer().technique().frameStats())
            r.stats[name].samples.push_back(value);
    }
    timer.resolve(true);
    addCompleted();
    return r;
}

std::string markdown(const BenchResult& r, int frames)
{
    std::ostringstream s;
    s << "| " << r.technique << " (" << frames << " frames) | median ms | min ms | max ms | frames run |\n|---|---|---|---|---|\n";
    for (const std::string& name : r.order) {
        const PassStats& p = r.passes.at(name);
        s << "| " << name << " | " << formatNumber(p.median()) << " | " << formatNumber(p.min()) << " | "
          << formatNumber(p.max()) << " | " << p.samples.size() << " |\n";
    }
    s << "| **total** | " << formatNumber(r.total.median()) << " | " << formatNumber(r.total.min()) << " | "
      << formatNumber(r.total.max()) << " | " << r.total.samples.size() << " |\n";
    for (const auto& [name, p] : r.stats)
        s << "| " << name << " (stat) | " << formatNumber(p.median()) << " | " << formatNumber(p.min()) << " | "
          << formatNumber(p.max()) << " | " << p.samples.size() << " |\n";
    return s.str();
}

Json jsonOf(const BenchResult& r)
{
    Json passes = Json::array();
    for (const std::string& name : r.order) {
        const PassStats& p = r.passes.at(name);
        passes.push_back({{"name", name},
                          {"medianMs", p.median()},
                          {"minMs", p.min()},
                          {"maxMs", p.max()},
                          {"frames", p.samples.size()}});
    }
    Json stats = Json::object();
    for (const auto& [name, p] : r.stats) stats[name] = p.median();
    return {{"technique", r.technique}, {"passes", passes}, {"totalMedianMs", r.total.median()}, {"stats", stats}};
}

// A pass name with the technique's own name replaced by "<technique>", so that two techniques'
// scopes of the same name ("vsgl / RSMs", "vpl-brsm / RSMs") share a row.
std::string passKey(const std::string& name, const std::string& technique)
{
    if (name == technique) return "<technique>";
    const std::string prefix = technique + " / ";
    if (name.rfind(prefix, 0) == 0) return "<technique> / " + name.substr(prefix.size());
    return name;
}

double medianOfKey(const BenchResult& r, const std::string& key)
{
    for (const auto& [name, stats] : r.passes)
        if (passKey(name, r.technique) == key) return stats.median();
    return 0.0;
}

// Per-pass medians of two runs side by side with their ratio b / a (passes of either run; a
// technique's own scopes are matched by what follows its name).
void printRatioTable(const BenchResult& a, const BenchResult& b, const std::string& bSuffix)
{
    const std::string bName = b.technique + bSuffix;
    std::printf("| pass | %s ms | %s ms | ratio %s / %s |\n|---|---|---|---|\n", a.technique.c_str(), bName.c_str(),
                bName.c_str(), a.technique.c_str());
    std::vector<std::string> order;
    for (const BenchResult* r : {&a, &b})
        for (const std::string& n : r->order) {
            const std::string key = passKey(n, r->technique);
            if (std::find(order.begin(), order.end(), key) == order.end()) order.push_back(key);
        }
    for (const std::string& key : order) {
        const double ma = medianOfKey(a, key);
        const double mb = medianOfKey(b, key);
        std::printf("| %s | %s | %s | %s |\n", key.c_str(), formatNumber(ma).c_str(), formatNumber(mb).c_str(),
                    ma > 0.0 ? formatNumber(mb / ma, 3).c_str() : "-");
    }
    std::printf("| **total** | %s | %s | %s |\n\n", formatNumber(a.total.median()).c_str(),
                formatNumber(b.total.median()).c_str(), formatNumber(b.total.median() / a.total.median(), 3).c_str());
}

// VSGL Table 1's rows for the RSM techniques (vsgl, vpl-brsm: those that time "<t> / radiance
// estimation"), one column per run, and the ratio of the last run to the first when there are two.
void printRSMTable(const std::vector<BenchResult>& results, const std::vector<std::string>& labels)
{
    std::vector<std::size_t> runs;
    for (std::size_t i = 0; i < results.size(); ++i)
        if (medianOfKey(results[i], "<technique> / radiance estimation") > 0.0) runs.push_back(i);
    if (runs.empty()) return;
    std::printf("| pass (VSGL Table 1 rows) |");
    for (std::size_t i : runs) std::printf(" %s ms |", labels[i].c_str());
    if (runs.size() == 2) std::printf(" ratio %s / %s |", labels[runs[0]].c_str(), labels[runs[1]].c_str());
    std::printf("\n|---|");
    for (std::size_t k = 0; k < runs.size() + (runs.size() == 2 ? 1 : 0); ++k) std::printf("---|");
    std::printf("\n");
    // The paper's rows.
    const std::vector<std::pair<std::string, std::vector<std::string>>> rows = {
        {"G-buffer", {"gbuffer"}},
        {"RSMs", {"<technique> / RSMs"}},
        {"PDF of BRSMs", {"<technique> / PDF of BRSMs"}},
        {"VPL/VSGL generation", {"<technique> / VPL/VSGL generation"}},
        {"shadow maps", {"<technique> / shadow maps"}},
        {"radiance estimation", {"<technique> / radiance estimation"}},
        {"**total frame**", {}}};
    for (const auto& [label, keys] : rows) {
        std::vector<double> values;
        for (std::size_t i : runs) {
            double v = keys.empty() ? results[i].total.median() : 0.0;
            for (const std::string& key : keys) v += medianOfKey(results[i], key);
            values.push_back(v);
        }
        std::printf("| %s |", label.c_str());
        for (double v : values) std::printf(" %s |", formatNumber(v).c_str());
        if (values.size() == 2) std::printf(" %s |", values[1] > 0.0 ? formatNumber(values[0] / values[1], 3).c_str() : "-");
        std::printf("\n");
    }
    std::printf("\n");
}

// Ray efficiency of CPU stages that report their rays: the very rays the stage cast in a frame,
// replayed alone on the same threads, over the stage's wall time (SMCIR's goal: >= 0.75). Prints one
// line per run that reports its rays; returns the JSON array.
Json rayEfficiency(const std::vector<BenchResult>& results)
{
    Json efficiency = Json::array();
    for (const BenchResult& r : results) {
        auto rays = r.stats.find("sampler: rays");
        auto total = r.stats.find("sampler: total ms");
        auto replay = r.stats.find("sampler: ray replay ms");
        if (rays == r.stats.end() || total == r.stats.end() || replay == r.stats.end()) continue;
        if (!(replay->second.median() > 0.0)) {
            std::printf("%s: ray efficiency not measured (needs --set smcir.synchronous=true: the replay needs "
                        "the step alone on the render thread)\n\n", r.technique.c_str());
            continue;
        }
        const double ratio = replay->second.median() / total->second.median();
        std::printf("%s: sampler %.0f rays per frame in %.1f ms; the same rays replayed alone: %.1f ms; ray efficiency "
                    "(replay / sampler) %.2f\n\n",
                    r.technique.c_str(), rays->second.median(), total->second.median(), replay->second.median(),
                    ratio);
        efficiency.push_back({{"technique", r.technique},
                              {"samplerMs", total->second.median()},
                              {"replayMs", replay->second.median()},
                              {"efficiency", ratio}});
    }
    return efficiency;
}

// SMCIR Table 2's columns for the VPL techniques (smcir, ir: those that time "<t> / shadow maps"),
// one row per run, plus what the goals compare: shadow-map faces rendered per frame and the
// shading pass's light-pixel evaluations per second. VPL sampling runs on the worker thread,
// overlapped with the GPU frame (ours); the paper's Table 2 runs every step in sequence, so its
// "total" adds them: so does ours.
void printVPLTable(const std::vector<BenchResult>& results, const std::vector<std::string>& labels)
{
    bool header = false;
    for (std::size_t i = 0; i < results.size(); ++i) {
        const BenchResult& r = results[i];
        const std::string t = r.technique;
        auto pass = [&](const std::string& name) {
            auto it = r.passes.find(name);
            return it == r.passes.end() ? 0.0 : it->second.median();
        };
        auto stat = [&](const std::string& name) {
            auto it = r.stats.find(name);
            return it == r.stats.end() ? 0.0 : it->second.median();
        };
        if (!r.passes.count(t + " / interleaved shading") && !r.stats.count("light-pixel evaluations")) continue;
        if (!header) {
            std::printf("| run (SMCIR Table 2 columns) | VPL sampling ms | shadow maps ms | interleaved shading incl. "
                        "G-buffer ms | filter ms | total ms | faces per frame | light-pixel evaluations per s |\n"
                        "|---|---|---|---|---|---|---|---|\n");
            header = true;
        }
        const double sampling = stat("sampler: total ms");
        const double maps = pass(t + " / shadow maps");
        const double shading = pass("gbuffer") + pass(t + " / interleaved shading");
        const double filter = pass(t + " / bilateral filter");
        const double shadingOnly = pass(t + " / interleaved shading");
        const double evaluations = stat("light-pixel evaluations");
        std::printf("| %s | %s | %s | %s | %s | %s | %s | %s |\n", labels[i].c_str(), formatNumber(sampling).c_str(),
                    formatNumber(maps).c_str(), formatNumber(shading).c_str(), formatNumber(filter).c_str(),
                    formatNumber(sampling + maps + shading + filter).c_str(),
                    formatNumber(stat("shadow map faces")).c_str(),
                    shadingOnly > 0.0 ? formatNumber(evaluations / (shadingOnly * 1e-3), 4).c_str() : "-");
    }
    if (header) std::printf("\n");
}

} // namespace

int runBench(const std::vector<std::string>& args)
{
    OptionParser parser("vplgi bench",
                        "Times every pass of a technique over frames (glFinish + wall clock on llvmpipe, GPU\n"
                        "timestamp queries on GPUs) and prints median/min/max per pass as markdown and JSON.\n"
                        "--against runs a second technique in the same process and prints per-pass ratios.");
    addSceneOptions(parser, "set a parameter (both runs)");
    addTechniqueOption(parser, "technique to time", "direct");
    parser.value("against", "T2", "second technique, timed in the same run; ratios T2 / T");
    parser.value("against-set", "KEY=VALUE", "set a parameter of the --against run only (e.g. to time one option)", "",
                 true);
    addSizeOptions(parser, "image", 640, 360);
    addAnimationOptions(parser, "timed frames", 10);
    parser.value("warmup", "N", "untimed frames first (the first frame also builds shadow maps)", "1");
    parser.value("json", "FILE", "also write the JSON here");
    if (!parser.parse(args)) return 0;
    const SceneOptions scene = sceneOptions(parser);
    const AnimationOptions animation = animationOptions(parser, 100000);
    const int warmup = parser.getInt("warmup", 0, 100000);
    const ImageSize size = imageSize(parser, 1, 16384);
    const Settings& settings = scene.settings;
    if (parser.has("json")) checkWritableDirectory(parser.get("json")); // before the timing, not after it

    std::vector<std::string> names = {parser.get("technique")};
    if (parser.has("against")) names.push_back(parser.get("against"));
    require(parser.has("against") || !parser.has("against-set"), "--against-set needs --against");
    Settings againstSettings = settings;
    for (const std::string& s : parser.getAll("against-set")) againstSettings.push_back(parseSetting(s));
    std::unique_ptr<gl::Context> context; // outlives the sessions' GL objects
    std::vector<Settings> perTechnique = {settings};
    if (names.size() == 2) perTechnique.push_back(againstSettings);
    std::vector<std::unique_ptr<Session>> sessions =
        createSessions(scene.sceneSpec, scene.camera, names, perTechnique);
    context = gl::createHeadlessContext();
    std::printf("scene %s, %dx%d, %s\n\n", sessions.front()->scene().source.c_str(), size.width, size.height,
                context->description().c_str());
    // Said only on GPUs, so that llvmpipe output is as it was (glFinish + wall clock, no lag).
    if (gl::PassTimer::defaultMode() == gl::PassTimer::Mode::TimestampQueries)
        std::printf("timing: GPU timestamp queries, read 1-3 frames late (each sample is attributed to the frame "
                    "that issued it)\n\n");
    std::vector<BenchResult> results;
    for (auto& session : sessions) {
        session->createRenderer();
        results.push_back(benchOne(*session, size, animation, warmup));
        std::printf("%s\n", markdown(results.back(), animation.frames).c_str());
    }
    if (results.size() == 2)
        printRatioTable(results[0], results[1], parser.has("against-set") ? " (against-set)" : "");
    std::vector<std::string> labels;
    for (std::size_t i = 0; i < results.size(); ++i)
        labels.push_back(results[i].technique + (i == 1 && parser.has("against-set") ? " (against-set)" : ""));
    printVPLTable(results, labels);
    printRSMTable(results, labels);
    const Json efficiency = rayEfficiency(results);
    Json jsonResults = Json::array();
    for (const BenchResult& r : results) jsonResults.push_back(jsonOf(r));
    Json report = {{"scene", sessions.front()->scene().source},
                   {"glRenderer", gl::rendererName()},
                   {"width", size.width},
                   {"height", size.height},
                   {"frames", animation.frames},
                   {"results", jsonResults}};
    if (!efficiency.empty()) report["rayEfficiency"] = efficiency;
    const std::string json = report.dump() + "\n";
    std::printf("%s", json.c_str());
    if (parser.has("json")) writeTextFile(parser.get("json"), json);
    return 0;
}

} // namespace vplgi
