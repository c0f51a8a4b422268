// `vplgi conform`: every technique against the path-traced reference of what it estimates, over
// seeds, on several scenes: the instrument the fixes of SMCIR, the RSM techniques and LightSkin are
// measured with (docs/conformance.md).
//
// A cell is one scene and one technique. Per cell:
//  - two references at --spp samples per pixel (pixel centres, as the rasteriser samples): the
//    matched one, what the technique estimates (Technique::matchedReferenceMode, then
//    configureReference: SMCIR, smcir-rt and IR the clamped indirect light with untextured bounces
//    and their bounce cap; the RSM techniques one bounce), and the truth, all indirect light (path
//    tracing minus the direct part). Each is rendered a second time with another seed: the relative
//    difference of the two means is the reference's own noise, printed beside the biases;
//  - the technique once per seed (its own seed parameters, <group>.seed, set to 1..--seeds; a
//    technique without one, lightskin-full, runs once), --frames frames of the still scene each,
//    compared by its indirect part (radiance minus its direct light) on the last frame: the bias of
//    the mean luminance against each reference, the tone-mapped mean |E| and its 99.9th percentile
//    against the matched one, and with --frames >= 10 the drift: the mean indirect luminance of frames
//    [0.9 N, N) over that of [0.4 N, 0.5 N), minus 1 (frames counted from the first, warm-up included);
//  - over the seeds: each number's mean with a 95% Student-t interval;
//  - on a scene with a camera "closed" (the sealed rooms: a closed room beside a lit one, where the
//    path tracer gives exactly 0; the first camera is in the lit room), the same runs from inside
//    the closed room too: the largest indirect luminance there over the lit room's mean (the
//    largest over the seeds).
// Output: a markdown table on stdout, DIR/conform.json (nlohmann::json), DIR/index.html with the
// table and, per cell, the matched reference, the first seed's image and its error heat map.
// --shard i/n runs the cells whose index (scenes outer, techniques inner) is i-1 modulo n;
// --merge DIR,... joins the conform.json of earlier runs into one report (no rendering).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli.h"
#include "commands.h"
#include "core/util/error.h"
#include "core/util/metrics.h"
#include "core/util/params.h"
#include "gl/api/context.h"
#include "reference.h"
#include "report.h"
#include "session.h"

namespace vplgi {

namespace {

using Json = nlohmann::ordered_json;

struct ConformOptions {
    std::vector<std::string> scenes;
    std::vector<std::string> techniques;
    Settings settings; // --set, for every technique that knows the key
    int seeds = 8;
    ImageSize size;
    int frames = 1;
    int spp = 1024;
    int shardIndex = 1, shardCount = 1;
    std::vector<std::string> merge;
    std::string outDir, writeDir, cache;
};

std::vector<std::string> splitCommas(const std::string& text)
{
    std::vector<std::string> items;
    std::stringstream s(text);
    for (std::string item; std::getline(s, item, ',');)
        if (!item.empty()) items.push_back(item);
    return items;
}

std::optional<ConformOptions> parseConformOptions(const std::vector<std::string>& args)
{
    OptionParser parser(
        "vplgi conform",
        "Measures every technique against the path-traced reference of what it estimates and\n"
        "against all indirect light, over seeds, on several scenes: bias of the mean with its 95%\n"
        "interval, tone-mapped |E| and its 99.9th percentile, drift over frames. Writes DIR/conform.json\n"
        "and DIR/index.html and prints a markdown table.");
    parser.value("scenes", "A,B,...", "scenes: built-in names or scene files (required unless --merge)");
    parser.value("techniques", "all|A,B,...",
                 "techniques (all: every technique with indirect light); an entry may carry its own settings, "
                 "name[key=value;key=value]",
                 "all");
    parser.value("set", "KEY=VALUE",
                 "set a parameter of the renderer or a technique (repeatable; each key must "
                 "be known to one of the techniques)",
                 "", true);
    parser.value("seeds", "N", "seeds per technique (its <group>.seed = 1..N)", "8");
    addSizeOptions(parser, "image", 64, 36);
    parser.value("frames", "N", "frames of the still scene per seed (>= 10 also measures the drift)", "1");
    parser.value("spp", "N", "samples per pixel of each reference", "1024");
    parser.value("shard", "I/N", "run only the cells whose index is I-1 modulo N (a cluster's job array)", "1/1");
    parser.value("merge", "DIR,...", "join the conform.json of these earlier runs into one report (no rendering)");
    parser.value("out", "DIR", "output directory (created)", "out/conform");
    parser.value("cache", "DIR", "reference cache directory ($VPLGI_CACHE_DIR or out/reference-cache)");
    if (!parser.parse(args)) return std::nullopt;

    ConformOptions o;
    o.outDir = parser.get("out");
    o.merge = splitCommas(parser.get("merge"));
    o.cache = parser.has("cache") ? parser.get("cache") : defaultReferenceCache();
    if (!o.merge.empty()) {
        for (const std::string& dir : o.merge)
            require(std::filesystem::is_regular_file(dir + "/conform.json"), dir + ": no conform.json to merge");
        return o;
    }
    require(parser.has("scenes"), "--scenes is required (a comma-separated list)");
    o.scenes = splitCommas(parser.get("scenes"));
    require(!o.scenes.empty(), "--scenes needs at least one scene");
    const std::string techniques = parser.get("techniques");
    if (techniques == "all") {
        for (const std::string& name : techniqueNames())
            if (name != "direct") o.techniques.push_back(name);
    } else {
        o.techniques = splitCommas(techniques);
    }
    require(!o.techniques.empty(), "--techniques needs at least one technique");
    for (const std::string& s : parser.getAll("set"))
        o.settings.push_back(parseSetting(s));
    o.seeds = parser.getInt("seeds", 1, 1000);
    o.size = imageSize(parser, 8, 4096);
    o.frames = parser.getInt("frames", 1, 100000);
    o.spp = parser.getInt("spp", 1, 1 << 24);
    const std::string shard = parser.get("shard");
    const std::size_t slash = shard.find('/');
    try {
        require(slash != std::string::npos, "");
        std::size_t used = 0;
        o.shardIndex = std::stoi(shard.substr(0, slash), &used);
        require(used == slash, "");
        o.shardCount = std::stoi(shard.substr(slash + 1), &used);
        require(used == shard.size() - slash - 1, "");
    } catch (const std::exception&) {
        throw Error("--shard must be I/N with 1 <= I <= N (got \"" + shard + "\")");
    }
    require(o.shardCount >= 1 && o.shardIndex >= 1 && o.shardIndex <= o.shardCount,
            "--shard must be I/N with 1 <= I <= N (got \"" + shard + "\")");
    return o;
}

using Interval = MeanInterval; // core/util/metrics.h

Json toJson(const Interval& i)
{
    return Json{{"mean", i.mean}, {"halfWidth95", i.halfWidth}, {"count", i.count}};
}

Interval intervalFromJson(const Json& j)
{
    return Interval{j.at("mean").get<double>(), j.at("halfWidth95").get<double>(), j.at("count").get<int>()};
}

struct Cell {
    std::string scene, technique;
    std::string matchedMode;         // the matched reference's mode and settings, for the report
    int seeds = 0;                   // runs (1: a technique without a seed)
    Interval matchedBias, truthBias; // mean luminance / reference's - 1
    Interval absE, p999;             // tone-mapped, against the matched reference
    Interval drift;                  // count 0 when --frames < 10
    double matchedNoise = 0.0;       // the matched reference's second seed against its first (mean)
    double truthNoise = 0.0;
    double matchedMean = 0.0, truthMean = 0.0, techniqueMean = 0.0; // mean indirect luminance (seed 1)
    // Scenes with a camera "closed" (the sealed rooms): the largest indirect luminance seen
    // from inside the closed room, where the path tracer gives exactly 0, over the lit room's mean
    // (the largest over the seeds); -1 for other scenes.
    double sealedLeak = -1.0;
    std::string images; // "images/<cell>" prefix, empty when merged without images
    // Wall time of the cell [s]: its seeds' renders and any reference it rendered first (the cache
    // serves later cells); for sizing a matrix (scripts/conformance-matrix). -1: not recorded.
    double seconds = -1.0;
};

Json toJson(const Cell& c)
{
    return Json{{"scene", c.scene},
                {"technique", c.technique},
                {"matchedReference", c.matchedMode},
                {"seeds", c.seeds},
                {"biasMatched", toJson(c.matchedBias)},
                {"biasTruth", toJson(c.truthBias)},
                {"meanAbsToneMapped", toJson(c.absE)},
                {"p999AbsToneMapped", toJson(c.p999)},
                {"drift", c.drift.count > 0 ? toJson(c.drift) : Json()},
                {"matchedReferenceNoise", c.matchedNoise},
                {"truthReferenceNoise", c.truthNoise},
                {"matchedMeanLuminance", c.matchedMean},
                {"truthMeanLuminance", c.truthMean},
                {"techniqueMeanLuminance", c.techniqueMean},
                {"sealedLeak", c.sealedLeak >= 0.0 ? Json(c.sealedLeak) : Json()},
                {"images", c.images},
                {"seconds", c.seconds >= 0.0 ? Json(c.seconds) : Json()}};
}

Cell cellFromJson(const Json& j, const std::string& dir)
{
    Cell c;
    c.scene = j.at("scene").get<std::string>();
    c.technique = j.at("technique").get<std::string>();
    c.matchedMode = j.at("matchedReference").get<std::string>();
    c.seeds = j.at("seeds").get<int>();
    c.matchedBias = intervalFromJson(j.at("biasMatched"));
    c.truthBias = intervalFromJson(j.at("biasTruth"));
    c.absE = intervalFromJson(j.at("meanAbsToneMapped"));
    c.p999 = intervalFromJson(j.at("p999AbsToneMapped"));
    if (!j.at("drift").is_null()) c.drift = intervalFromJson(j.at("drift"));
    c.matchedNoise = j.at("matchedReferenceNoise").get<double>();
    c.truthNoise = j.at("truthReferenceNoise").get<double>();
    c.matchedMean = j.at("matchedMeanLuminance").get<double>();
    c.truthMean = j.at("truthMeanLuminance").get<double>();
    c.techniqueMean = j.at("techniqueMeanLuminance").get<double>();
    c.sealedLeak = j.at("sealedLeak").is_null() ? -1.0 : j.at("sealedLeak").get<double>();
    // Optional: reports written before it existed have none.
    c.seconds = j.contains("seconds") && !j.at("seconds").is_null() ? j.at("seconds").get<double>() : -1.0;
    const std::string images = j.at("images").get<std::string>();
    c.images = images.empty() ? "" : dir + "/" + images;
    return c;
}

std::string modeName(PathTracerParams::Mode mode)
{
    switch (mode) {
    case PathTracerParams::Mode::Full:
        return "full";
    case PathTracerParams::Mode::Direct:
        return "direct";
    case PathTracerParams::Mode::Indirect:
        return "indirect";
    case PathTracerParams::Mode::Clamped:
        return "clamped";
    case PathTracerParams::Mode::OneBounce:
        return "onebounce";
    }
    return "?";
}

double meanLuminance(const ImageRGBA32F& image)
{
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i + 3 < image.pixels.size(); i += 4, ++n)
        sum += 0.2126 * image.pixels[i] + 0.7152 * image.pixels[i + 1] + 0.0722 * image.pixels[i + 2];
    return n ? sum / static_cast<double>(n) : 0.0;
}

// `technique` is a --techniques entry: name or name[key=value;...] (settings after --set's).
SessionOptions sessionFor(const ConformOptions& o, const std::string& sceneSpec,
                          const std::shared_ptr<const SceneDescription>& scene, const std::string& technique,
                          const Settings& extra, const std::string& camera = "")
{
    const TechniqueEntry entry = parseTechniqueEntry(technique);
    SessionOptions options;
    options.sceneSpec = sceneSpec;
    options.loaded = scene; // loaded once per scene, copied for each run
    options.technique = entry.technique;
    options.camera = camera;
    options.settings = measuringSettings(o.settings);
    options.settings.insert(options.settings.end(), entry.settings.begin(), entry.settings.end());
    options.settings.insert(options.settings.end(), extra.begin(), extra.end());
    options.rejectUnknownSettings = false; // checked once for all techniques (createSessions)
    return options;
}

// One reference at o.spp and its own noise (a second seed's mean against the first's).
ImageRGBA32F referenceWithNoise(const ConformOptions& o, Session& session, const RayScene& rays,
                                PathTracerParams params, double& noise)
{
    params.spp = o.spp;
    params.jitterPixels = false; // pixel centres, as the rasteriser samples
    ReferenceRequest request{session.scene(), rays,   session.camera(), o.size.width,
                             o.size.height,   params, o.cache,          false};
    ImageRGBA32F first = obtainReference(request).image;
    request.params.seed = params.seed + 1;
    const double second = meanLuminance(obtainReference(request).image);
    const double mean = meanLuminance(first);
    noise = mean > 0.0 ? second / mean - 1.0 : 0.0;
    return first;
}

bool hasLight(const Scene& scene)
{
    if (!scene.lights.empty()) return true;
    for (const Material& m : scene.materials)
        if (m.isEmissive()) return true;
    return false;
}

Cell runCell(const ConformOptions& o, const std::string& sceneSpec,
            const std::shared_ptr<const SceneDescription>& scene, const std::string& technique, int cellIndex)
{
    const auto start = std::chrono::steady_clock::now();
    Cell cell;
    cell.scene = sceneSpec;
    cell.technique = technique;
    Session probe(sessionFor(o, sceneSpec, scene, technique, {}));
    require(hasLight(probe.scene()), sceneSpec + ": the scene has no light (no light source, no emissive material)");
    const std::vector<std::string> keys = probe.techniqueSeedKeys();
    cell.seeds = keys.empty() ? 1 : o.seeds;
    // The sealed rooms: the first camera ("default") in the lit room, "closed" in the closed one.
    const bool sealed = probe.scene().findCamera("closed") != nullptr;
    double closedMax = 0.0, litMean = 0.0;

    ImageRGBA32F matched, truth;
    std::vector<double> matchedBias, truthBias, absE, p999, drift;
    for (int seed = 1; seed <= cell.seeds; ++seed) {
        std::fprintf(stderr, "conform: %s / %s, seed %d/%d\n", sceneSpec.c_str(), technique.c_str(), seed, cell.seeds);
        Settings extra;
        for (const std::string& key : keys)
            extra.emplace_back(key, std::to_string(seed));
        Session session(sessionFor(o, sceneSpec, scene, technique, extra));
        session.createRenderer(ProgressSink{[](const std::string&, int, int) {}});
        Renderer& renderer = session.renderer();
        if (seed == 1) {
            RayScene rays(session.scene());
            PathTracerParams params;
            params.mode = renderer.technique().matchedReferenceMode();
            renderer.technique().configureReference(params, {});
            cell.matchedMode = modeName(params.mode);
            if (params.mode != PathTracerParams::Mode::OneBounce) // one bounce has no depth or clamp to say
                cell.matchedMode += " (maxDepth " + std::to_string(params.maxDepth) +
                                    (params.mode == PathTracerParams::Mode::Clamped
                                         ? ", clampGeometry " + formatNumber(params.clampGeometry) + " 1/m^2"
                                         : "") +
                                    (params.untexturedBounces ? ", untextured bounces)" : ")");
            matched = referenceWithNoise(o, session, rays, params, cell.matchedNoise);
            PathTracerParams all;
            all.mode = PathTracerParams::Mode::Indirect;
            truth = referenceWithNoise(o, session, rays, all, cell.truthNoise);
            cell.matchedMean = meanLuminance(matched);
            cell.truthMean = meanLuminance(truth);
        }
        std::vector<double> frameMeans;
        ImageRGBA32F image;
        for (int frame = 0; frame < o.frames; ++frame) {
            renderer.renderFrame(session.camera(), o.size.width, o.size.height, 0.0f);
            image = indirectPart(renderer);
            frameMeans.push_back(meanLuminance(image));
        }
        const double exposure = renderer.params().exposure;
        const ImageErrors errors = compareImages(image, matched, exposure);
        const double mean = frameMeans.back();
        matchedBias.push_back(cell.matchedMean > 0.0 ? mean / cell.matchedMean - 1.0 : 0.0);
        truthBias.push_back(cell.truthMean > 0.0 ? mean / cell.truthMean - 1.0 : 0.0);
        absE.push_back(errors.meanAbsToneMapped);
        p999.push_back(errors.p999AbsToneMapped);
        if (o.frames >= 10) drift.push_back(driftOf(frameMeans));
        if (sealed) {
            // The same technique and seed from inside the closed room: nothing may arrive there.
            Session inside(sessionFor(o, sceneSpec, scene, technique, extra, "closed"));
            inside.createRenderer(ProgressSink{[](const std::string&, int, int) {}});
            for (int frame = 0; frame < o.frames; ++frame)
                inside.renderer().renderFrame(inside.camera(), o.size.width, o.size.height, 0.0f);
            const ImageRGBA32F closedImage = indirectPart(inside.renderer());
            for (std::size_t i = 0; i + 3 < closedImage.pixels.size(); i += 4)
                closedMax = std::max(closedMax, 0.2126 * closedImage.pixels[i] + 0.7152 * closedImage.pixels[i + 1] +
                                                    0.0722 * closedImage.pixels[i + 2]);
            litMean += mean / cell.seeds;
        }
        if (seed == 1) {
            cell.techniqueMean = mean;
            cell.images = "images/cell" + std::to_string(cellIndex);
            const std::string prefix = o.writeDir + "/" + cell.images;
            writeImage(prefix + "-matched.png", toneMapImage(matched, exposure));
            writeImage(prefix + "-technique.png", toneMapImage(image, exposure));
            writeImage(prefix + "-error.png", errorHeatMap(image, matched, exposure, 0.25));
        }
    }
    cell.matchedBias = meanInterval(matchedBias);
    cell.truthBias = meanInterval(truthBias);
    cell.absE = meanInterval(absE);
    cell.p999 = meanInterval(p999);
    cell.drift = meanInterval(drift);
    if (sealed) cell.sealedLeak = litMean > 0.0 ? closedMax / litMean : (closedMax > 0.0 ? 1e30 : 0.0);
    cell.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "conform: %s / %s took %.1f s\n", sceneSpec.c_str(), technique.c_str(), cell.seconds);
    return cell;
}

std::string markdownTable(const std::vector<Cell>& cells)
{
    std::ostringstream t;
    t << "| scene | technique | seeds | matched reference | bias vs matched [95%] | bias vs all indirect [95%] | "
         "tone-mapped \\|E\\| | 99.9th pct | drift [95%] | closed room max / lit mean | reference noise (matched, all) "
         "|\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Cell& c : cells) {
        char noise[64];
        std::snprintf(noise, sizeof noise, "%+.2f%%, %+.2f%%", 100.0 * c.matchedNoise, 100.0 * c.truthNoise);
        t << "| " << c.scene << " | " << c.technique << " | " << c.seeds << " | " << c.matchedMode << " | "
          << percentText(c.matchedBias) << " | " << percentText(c.truthBias) << " | " << formatNumber(c.absE.mean, 3)
          << " | " << formatNumber(c.p999.mean, 3) << " | " << (c.drift.count ? percentText(c.drift) : "-") << " | "
          << (c.sealedLeak >= 0.0 ? formatNumber(c.sealedLeak, 3) : "-") << " | " << noise << " |\n";
    }
    return t.str();
}

std::string htmlReport(const std::vector<Cell>& cells, const std::string& commandLine)
{
    std::ostringstream h;
    h << "<!doctype html><html><head><meta charset=\"utf-8\"><title>vplgi conform</title><style>"
         "body{font-family:sans-serif}table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:2px 6px}"
         "img{image-rendering:pixelated;width:192px}</style></head><body><h1>vplgi conform</h1><p><code>"
      << htmlEscape(commandLine)
      << "</code></p><p>Biases are of the mean indirect luminance (the technique's radiance minus its direct light) "
         "against each reference, with 95% Student-t intervals over the seeds; |E| is tone-mapped, against the "
         "matched reference. Images: the matched reference, the first seed's indirect light, |E| (0 to 0.25).</p>"
         "<table><tr><th>scene</th><th>technique</th><th>seeds</th><th>matched reference</th><th>bias vs matched</th>"
         "<th>bias vs all indirect</th><th>|E|</th><th>99.9th pct</th><th>drift</th><th>closed room max / lit mean</th>"
         "<th>images</th></tr>";
    for (const Cell& c : cells) {
        h << "<tr><td>" << htmlEscape(c.scene) << "</td><td>" << htmlEscape(c.technique) << "</td><td>" << c.seeds
          << "</td><td>" << htmlEscape(c.matchedMode) << "</td><td>" << percentText(c.matchedBias) << "</td><td>"
          << percentText(c.truthBias) << "</td><td>" << formatNumber(c.absE.mean, 3) << "</td><td>"
          << formatNumber(c.p999.mean, 3) << "</td><td>" << (c.drift.count ? percentText(c.drift) : "-") << "</td><td>"
          << (c.sealedLeak >= 0.0 ? formatNumber(c.sealedLeak, 3) : "-") << "</td><td>";
        if (!c.images.empty())
            for (const char* part : {"-matched.png", "-technique.png", "-error.png"})
                h << "<img src=\"" << htmlEscape(c.images + part) << "\">";
        h << "</td></tr>";
    }
    h << "</table></body></html>\n";
    return h.str();
}

std::string joinArgs(const std::vector<std::string>& args)
{
    std::string line = "vplgi conform";
    for (const std::string& a : args)
        line += " " + a;
    return line;
}

void writeReport(const std::string& dir, const std::vector<Cell>& cells, const std::string& commandLine,
                 const ConformOptions& o)
{
    Json cellsJson = Json::array();
    for (const Cell& c : cells)
        cellsJson.push_back(toJson(c));
    Json doc{{"command", commandLine}, {"width", o.size.width}, {"height", o.size.height},
             {"frames", o.frames},     {"spp", o.spp},          {"cells", cellsJson}};
    writeTextFile(dir + "/conform.json", doc.dump(2) + "\n");
    writeTextFile(dir + "/index.html", htmlReport(cells, commandLine));
}

} // namespace

int runConform(const std::vector<std::string>& args)
{
    std::optional<ConformOptions> parsed = parseConformOptions(args);
    if (!parsed) return 0;
    ConformOptions& o = *parsed;
    const std::string commandLine = joinArgs(args);
    StagedDirectory staged(o.outDir);
    o.writeDir = staged.path();

    std::vector<Cell> cells;
    if (!o.merge.empty()) {
        for (const std::string& dir : o.merge) {
            std::ifstream in(dir + "/conform.json");
            Json doc;
            try {
                doc = Json::parse(in);
                if (cells.empty()) {
                    o.size.width = doc.at("width").get<int>();
                    o.size.height = doc.at("height").get<int>();
                    o.frames = doc.at("frames").get<int>();
                    o.spp = doc.at("spp").get<int>();
                }
                const std::string relative = std::filesystem::relative(dir, o.outDir).string();
                for (const Json& c : doc.at("cells"))
                    cells.push_back(cellFromJson(c, relative));
            } catch (const nlohmann::json::exception& e) {
                throw Error(dir + "/conform.json: not a conform report (" + e.what() + ")");
            }
        }
    } else {
        // Every --set key must be known to one of the techniques, on every scene (before any GL work).
        std::vector<std::string> names;
        std::vector<Settings> settings;
        for (const std::string& entry : o.techniques) {
            const TechniqueEntry variant = parseTechniqueEntry(entry);
            names.push_back(variant.technique);
            settings.push_back(o.settings);
            settings.back().insert(settings.back().end(), variant.settings.begin(), variant.settings.end());
        }
        for (const std::string& scene : o.scenes)
            createSessions(scene, "", names, settings);
        std::filesystem::create_directories(o.writeDir + "/images");
        std::unique_ptr<gl::Context> context = gl::createHeadlessContext();
        int index = 0;
        for (const std::string& scene : o.scenes) {
            std::shared_ptr<const SceneDescription> loaded;
            for (const std::string& technique : o.techniques) {
                if (index % o.shardCount == o.shardIndex - 1) {
                    if (!loaded) loaded = std::make_shared<const SceneDescription>(loadSceneSpec(scene));
                    cells.push_back(runCell(o, scene, loaded, technique, index));
                }
                ++index;
            }
        }
    }
    writeReport(o.writeDir, cells, commandLine, o);
    staged.commit();
    std::printf("%s", markdownTable(cells).c_str());
    std::printf("%s/index.html\n", o.outDir.c_str());
    return 0;
}

} // namespace vplgi
