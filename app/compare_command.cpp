// `vplgi compare`: renders techniques side by side with path-traced references, still or along a
// scene-file animation, and writes DIR/index.html (images, error heat maps, a metrics table and
// plots of tracked-pixel luminance over time, like SMCIR Fig. 7) plus metrics.csv / metrics.json.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>

#include "cli.h"
#include "commands.h"
#include "core/content_hash.h"
#include "core/error.h"
#include "core/metrics.h"
#include "core/params.h"
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

const char* const kColors[] = {"#d62728", "#1f77b4", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2"};

struct TechniqueRun {
    std::string name;
    std::unique_ptr<Session> session;
    std::vector<ImageErrors> frameErrors;
    std::vector<std::vector<double>> tracked; // [frame][pixel] luminance
    std::vector<double> frameMilliseconds;
};

// Technique radiance minus its direct light: the indirect part, for indirect/clamped references.
ImageRGBA32F indirectPart(const Renderer& renderer)
{
    ImageRGBA32F total = renderer.readRadiance();
    const ImageRGBA32F direct = renderer.readDirect();
    for (std::size_t i = 0; i < total.pixels.size(); ++i)
        if (i % 4 != 3) total.pixels[i] -= direct.pixels[i];
    return total;
}

std::string frameName(int frame)
{
    char b[32];
    std::snprintf(b, sizeof b, "f%04d", frame);
    return b;
}

} // namespace

int runCompare(const std::vector<std::string>& args)
{
    OptionParser parser("vplgi compare",
                        "Renders each technique and a path-traced reference (per frame when the scene or camera\n"
                        "moves; references are cached) and writes DIR/index.html with images, error heat maps,\n"
                        "a metrics table and tracked-pixel luminance plots, plus metrics.csv and metrics.json.");
    parser.value("scene", "S", "built-in scene, scene file (.json) or .gltf/.glb");
    parser.value("techniques", "A,B,...", "techniques to compare", "direct");
    parser.value("camera", "NAME", "camera name (default: the scene's first camera)");
    parser.value("frames", "N", "frames (the scene file's animations advance 1/fps per frame)", "1");
    parser.value("fps", "F", "animation frames per second", "30");
    parser.value("width", "W", "image width", "320");
    parser.value("height", "H", "image height", "180");
    parser.value("reference-mode", "M",
                 "reference: full, direct, indirect, clamped or onebounce; techniques are compared by the same "
                 "part (indirect, clamped and onebounce: their radiance minus their direct light)",
                 "full");
    parser.value("spp", "N", "reference samples per pixel", "256");
    parser.value("tracked", "N", "tracked pixels for the temporal metrics (SMCIR uses 8)", "8");
    parser.value("out", "DIR", "output directory (created)", "out/compare");
    parser.value("cache", "DIR", "reference cache directory ($VPLGI_CACHE_DIR or out/reference-cache)");
    parser.value("set", "KEY=VALUE", "set a parameter of the renderer, a technique or reference.*", "", true);
    if (!parser.parse(args)) return 0;

    require(parser.has("scene"), "--scene is required (e.g. --scene cornell)");
    const std::vector<std::string> techniques = splitList(parser.get("techniques"));
    require(!techniques.empty(), "--techniques needs at least one technique");
    const int frames = parser.getInt("frames", 1, 100000);
    const float fps = parser.getFloat("fps", 0.001f, 10000.0f);
    const int width = parser.getInt("width", 8, 8192);
    const int height = parser.getInt("height", 8, 8192);
    const int trackedCount = parser.getInt("tracked", 1, 64);
    const std::string outDir = parser.get("out");

    Settings settings;
    for (const std::string& s : parser.getAll("set")) settings.push_back(parseSetting(s));
    PathTracerParams referenceParams;
    referenceParams.mode = parseReferenceMode(parser.get("reference-mode"));
    referenceParams.spp = parser.getInt("spp", 1, 1 << 24);
    ParamSetter referenceSetter(settings);
    referenceParams.visitParams(referenceSetter);
    std::unique_ptr<gl::Context> context; // outlives the sessions' GL objects
    std::vector<std::unique_ptr<Session>> sessions =
        createSessions(parser.get("scene"), parser.get("camera"), techniques,
                       std::vector<Settings>(techniques.size(), settings), referenceSetter.usedKeys());
    std::vector<TechniqueRun> runs;
    for (std::size_t i = 0; i < techniques.size(); ++i) {
        TechniqueRun run;
        run.name = techniques[i];
        run.session = std::move(sessions[i]);
        runs.push_back(std::move(run));
    }

    std::filesystem::create_directories(outDir + "/images");
    context = gl::createHeadlessContext();
    for (TechniqueRun& run : runs) run.session->createRenderer();
    // What the reference must simulate to be comparable (SMCIR: untextured bounces, the same clamp).
    for (TechniqueRun& run : runs)
        run.session->renderer().technique().configureReference(referenceParams, referenceSetter.usedKeys());

    // The reference follows the first session's scene state (all sessions animate identically).
    Session& lead = *runs.front().session;
    const double toneExposure = lead.renderer().params().exposure;
    const std::vector<glm::ivec2> tracked = trackedPixels(width, height, trackedCount);
    const std::string cache = parser.has("cache") ? parser.get("cache") : defaultReferenceCache();

    std::vector<std::vector<double>> referenceTracked;
    std::vector<double> referenceSeconds;
    ImageRGBA32F reference;
    std::uint64_t referenceKey = 0;
    int referencesRendered = 0;
    for (int frame = 0; frame < frames; ++frame) {
        const float time = static_cast<float>(frame) / fps;
        for (TechniqueRun& run : runs) run.session->applyAnimations(time);
        Hasher state;
        state.value(hashSceneContent(lead.scene()));
        hashCamera(state, lead.camera());
        if (frame == 0 || state.digest() != referenceKey) {
            RayScene rays(lead.scene());
            ReferenceRequest request{lead.scene(), rays, lead.camera(), width, height, referenceParams, cache, true};
            CachedReference r = obtainReference(request);
            reference = std::move(r.image);
            referenceKey = state.digest();
            referenceSeconds.push_back(r.seconds);
            ++referencesRendered;
        }
        std::vector<double> refTracked;
        for (glm::ivec2 p : tracked) refTracked.push_back(luminanceAt(reference, p));
        referenceTracked.push_back(refTracked);
        const bool keepImages = frame == 0 || frame == frames - 1;
        if (keepImages) {
            writeImage(outDir + "/images/reference-" + frameName(frame) + ".exr", reference);
            ImageRGBA8 png = toneMapImage(reference, toneExposure);
            writeImage(outDir + "/images/reference-" + frameName(frame) + ".png", png);
        }
        for (TechniqueRun& run : runs) {
            Renderer& renderer = run.session->renderer();
            renderer.renderFrame(run.session->camera(), width, height, time);
            // GPU timestamp queries publish frames late: take whichever frames completed (the rest below).
            for (const gl::FrameTimes& f : renderer.timer().takeCompletedFrames())
                run.frameMilliseconds.push_back(f.total());
            // Compare like with like: the reference's mode decides which part of the technique's image.
            ImageRGBA32F image = referenceParams.mode == PathTracerParams::Mode::Full     ? renderer.readRadiance()
                                 : referenceParams.mode == PathTracerParams::Mode::Direct ? renderer.readDirect()
                                                                                          : indirectPart(renderer);
            run.frameErrors.push_back(compareImages(image, reference, toneExposure));
            std::vector<double> values;
            for (glm::ivec2 p : tracked) values.push_back(luminanceAt(image, p));
            run.tracked.push_back(values);
            if (keepImages) {
                const std::string base = outDir + "/images/" + run.name + "-" + frameName(frame);
                writeImage(base + ".png", renderer.readDisplay());
                writeImage(base + ".exr", image);
                writeImage(base + "-error.png", errorHeatMap(image, reference, toneExposure, 0.25));
            }
        }
        std::fprintf(stderr, "frame %d/%d done\n", frame + 1, frames);
    }

    for (TechniqueRun& run : runs) {
        gl::PassTimer& timer = run.session->renderer().timer();
        timer.resolve(true);
        for (const gl::FrameTimes& f : timer.takeCompletedFrames()) run.frameMilliseconds.push_back(f.total());
    }

    // Metrics: per technique, averaged over frames; temporal metrics over the tracked pixels.
    std::ostringstream csv, json, table;
    csv << "technique,frames,mean_abs_tonemapped,rmse,relative_mse,mean_luminance_bias,temporal_abs_e,"
           "temporal_abs_e_prime,median_frame_ms\n";
    json << "{\n  \"scene\": \"" << lead.scene().source << "\",\n  \"width\": " << width << ", \"height\": " << height
         << ", \"frames\": " << frames << ",\n  \"exposure\": " << toneExposure << ",\n  \"reference\": {\"mode\": \""
         << parser.get("reference-mode") << "\", \"spp\": " << referenceParams.spp
         << ", \"rendered\": " << referencesRendered << "},\n  \"techniques\": [\n";
    for (std::size_t t = 0; t < runs.size(); ++t) {
        const TechniqueRun& run = runs[t];
        ImageErrors mean;
        for (const ImageErrors& e : run.frameErrors) {
            mean.meanAbsToneMapped += e.meanAbsToneMapped / frames;
            mean.rmse += e.rmse / frames;
            mean.relativeMSE += e.relativeMSE / frames;
            mean.meanRelativeLuminance += e.meanRelativeLuminance / frames;
        }
        TemporalErrors temporal = temporalErrors(run.tracked, referenceTracked, toneExposure);
        std::vector<double> ms = run.frameMilliseconds;
        std::sort(ms.begin(), ms.end());
        double median = ms.empty() ? 0.0 : ms[ms.size() / 2];
        csv << run.name << "," << frames << "," << mean.meanAbsToneMapped << "," << mean.rmse << "," << mean.relativeMSE
            << "," << mean.meanRelativeLuminance << "," << temporal.meanAbsError << "," << temporal.meanAbsDerivative
            << "," << median << "\n";
        json << "    {\"name\": \"" << run.name << "\", \"meanAbsToneMapped\": " << mean.meanAbsToneMapped
             << ", \"rmse\": " << mean.rmse << ", \"relativeMSE\": " << mean.relativeMSE
             << ", \"meanLuminanceBias\": " << mean.meanRelativeLuminance << ", \"temporalAbsE\": "
             << temporal.meanAbsError << ", \"temporalAbsEPrime\": " << temporal.meanAbsDerivative
             << ", \"medianFrameMs\": " << median << "}" << (t + 1 < runs.size() ? "," : "") << "\n";
        table << "<tr><td>" << htmlEscape(run.name) << "</td><td>" << formatNumber(mean.meanAbsToneMapped) << "</td><td>"
              << formatNumber(mean.rmse) << "</td><td>" << formatNumber(mean.relativeMSE) << "</td><td>"
              << formatNumber(100.0 * mean.meanRelativeLuminance, 3) << "%</td><td>"
              << formatNumber(temporal.meanAbsError) << "</td><td>" << formatNumber(temporal.meanAbsDerivative)
              << "</td><td>" << formatNumber(median, 4) << "</td></tr>\n";
    }
    json << "  ]\n}\n";

    // Plots: one per tracked pixel (reference dashed), like SMCIR Fig. 7.
    std::ostringstream plots;
    for (std::size_t j = 0; j < tracked.size(); ++j) {
        std::vector<PlotSeries> series;
        PlotSeries ref{"reference", {}, "#000000", true};
        for (const auto& f : referenceTracked) ref.values.push_back(f[j]);
        series.push_back(ref);
        for (std::size_t t = 0; t < runs.size(); ++t) {
            PlotSeries s{runs[t].name, {}, kColors[t % 7], false};
            for (const auto& f : runs[t].tracked) s.values.push_back(f[j]);
            series.push_back(s);
        }
        std::string name = "luminance-pixel" + std::to_string(j) + ".svg";
        writeTextFile(outDir + "/" + name,
                      svgLinePlot("tracked pixel " + std::to_string(j) + " (" + std::to_string(tracked[j].x) + ", " +
                                      std::to_string(tracked[j].y) + ")",
                                  "frame", "luminance [W/(m^2 sr)]", series, 480, 240));
        plots << "<img src=\"" << name << "\" alt=\"luminance over time at tracked pixel " << j << "\">\n";
    }

    std::ostringstream html;
    html << "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>vplgi compare: "
         << htmlEscape(lead.scene().name) << "</title>\n<style>body{font-family:sans-serif;margin:20px;max-width:1400px}"
         << "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:4px 8px;text-align:right}"
         << "td:first-child{text-align:left}figure{display:inline-block;margin:4px}figcaption{font-size:12px}"
         << "img{image-rendering:pixelated}</style></head><body>\n";
    html << "<h1>vplgi compare: " << htmlEscape(lead.scene().name) << "</h1>\n<p>" << width << "x" << height << ", "
         << frames << " frame(s) at " << fps << " fps; reference: Embree path tracer, mode "
         << htmlEscape(parser.get("reference-mode")) << ", " << referenceParams.spp << " spp (" << referencesRendered
         << " distinct reference frame(s)); tone mapping for |E|: Reinhard on luminance at exposure " << toneExposure
         << ". Tracked pixels: " << tracked.size() << ". Metrics compare "
         << (referenceParams.mode == PathTracerParams::Mode::Full     ? "each technique's whole image"
             : referenceParams.mode == PathTracerParams::Mode::Direct ? "each technique's direct light"
                                                                      : "each technique's indirect light (its image minus its direct light)")
         << " with the reference; the images show the whole display image.</p>\n";
    html << "<h2>Metrics</h2>\n<table><tr><th>technique</th><th>mean |E| (tone-mapped)</th><th>RMSE</th><th>rel. MSE</th>"
         << "<th>mean luminance bias</th><th>avg |E| tracked</th><th>avg |E'| tracked (SMCIR eq. 10)</th>"
         << "<th>median frame [ms]</th></tr>\n"
         << table.str() << "</table>\n<p>All numbers: <a href=\"metrics.csv\">metrics.csv</a>, "
         << "<a href=\"metrics.json\">metrics.json</a>. Frame times are on this machine's OpenGL implementation.</p>\n";
    for (int frame : {0, frames - 1}) {
        if (frame == frames - 1 && frames == 1 && frame != 0) continue;
        if (frame == frames - 1 && frames > 1) html << "<h2>Last frame (" << frame << ")</h2>\n";
        else if (frame == 0) html << "<h2>Frame 0</h2>\n";
        else continue;
        html << "<figure><img src=\"images/reference-" << frameName(frame) << ".png\"><figcaption>reference</figcaption></figure>\n";
        for (const TechniqueRun& run : runs)
            html << "<figure><img src=\"images/" << run.name << "-" << frameName(frame) << ".png\"><figcaption>"
                 << htmlEscape(run.name) << "</figcaption></figure>\n";
        html << "<br>\n";
        for (const TechniqueRun& run : runs)
            html << "<figure><img src=\"images/" << run.name << "-" << frameName(frame) << "-error.png\"><figcaption>"
                 << htmlEscape(run.name) << ": |E| heat map (black 0, white &ge; 0.25)</figcaption></figure>\n";
        if (frames == 1) break;
    }
    html << "<h2>Luminance over time at tracked pixels</h2>\n" << plots.str() << "\n</body></html>\n";

    writeTextFile(outDir + "/metrics.csv", csv.str());
    writeTextFile(outDir + "/metrics.json", json.str());
    writeTextFile(outDir + "/index.html", html.str());
    std::printf("%s/index.html\n", outDir.c_str());
    return 0;
}

} // namespace vplgi
