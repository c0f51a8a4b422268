#include "report.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/util/error.h"

namespace vplgi {

std::string htmlEscape(const std::string& text)
{
    std::string out;
    for (char c : text) {
        switch (c) {
        case '&': out += "&amp;"; break;
        case '<': out += "&lt;"; break;
        case '>': out += "&gt;"; break;
        case '"': out += "&quot;"; break;
        default: out += c;
        }
    }
    return out;
}

std::string formatNumber(double value, int significant)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*g", significant, value);
    return buffer;
}

void writeTextFile(const std::string& path, const std::string& text)
{
    namespace fs = std::filesystem;
    const fs::path target(path);
    // A unique temporary sibling: two runs writing the same report never share one.
    const fs::path temporary = target.parent_path() / ("." + target.filename().string() + ".partial-" +
                                                       std::to_string(std::random_device()()));
    std::error_code ec;
    bool ok = false;
    {
        std::ofstream out(temporary, std::ios::binary);
        if (out.good()) {
            out << text;
            out.close(); // flushes: a full disk or a file size limit shows here
            ok = !out.fail();
        }
    }
    if (!ok) {
        fs::remove(temporary, ec);
        throw Error(path + ": cannot write");
    }
    fs::rename(temporary, target, ec);
    if (ec) {
        fs::remove(temporary, ec);
        throw Error(path + ": cannot rename the finished file into place");
    }
}

StagedDirectory::StagedDirectory(const std::string& target) : mName(target)
{
    namespace fs = std::filesystem;
    std::error_code ec;
    mTarget = fs::path(target).lexically_normal();
    if (mTarget.filename().empty()) mTarget = mTarget.parent_path(); // "dir/"
    // ".", ".." and "/": the staging sibling needs a parent and a name.
    if (mTarget.filename() == "." || mTarget.filename() == ".." || !mTarget.has_parent_path())
        mTarget = fs::absolute(mTarget, ec).lexically_normal();
    if (mTarget.filename().empty()) mTarget = mTarget.parent_path();
    require(!ec && !mTarget.filename().empty() && mTarget.has_parent_path() && mTarget != mTarget.root_path(),
            target + ": not a usable output directory");
    require(!fs::exists(mTarget, ec) || fs::is_directory(mTarget, ec), target + ": exists and is not a directory");
    // The parents that do not exist yet; an existing one must be a directory.
    fs::path parent = mTarget.parent_path();
    for (fs::path p = parent; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        mCreated.push_back(p);
        if (p == p.parent_path()) break;
    }
    fs::path existing = mCreated.empty() ? parent : mCreated.back().parent_path();
    if (existing.empty()) existing = ".";
    require(fs::is_directory(existing, ec), target + ": " + existing.string() + " is not a directory");
    fs::create_directories(parent, ec);
    if (!ec) {
        mStaging = parent / ("." + mTarget.filename().string() + ".partial-" + std::to_string(std::random_device()()));
        fs::create_directory(mStaging, ec);
    }
    if (ec) {
        const std::string why = ec.message();
        for (const fs::path& p : mCreated)
            fs::remove(p, ec);
        throw Error(target + ": cannot write in " + parent.string() + ": " + why);
    }
}

StagedDirectory::~StagedDirectory()
{
    if (mCommitted) return;
    std::error_code ec;
    std::filesystem::remove_all(mStaging, ec);
    for (const std::filesystem::path& p : mCreated)
        std::filesystem::remove(p, ec); // only while empty
}

void StagedDirectory::commit()
{
    namespace fs = std::filesystem;
    std::error_code ec;
    if (!fs::exists(mTarget, ec)) {
        fs::rename(mStaging, mTarget, ec);
        require(!ec, mName + ": cannot move the finished report into place: " + ec.message());
        mCommitted = true;
        return;
    }
    // An earlier report is there: its files are replaced one by one (each rename is atomic).
    for (auto it = fs::recursive_directory_iterator(mStaging, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec)) {
        const fs::path destination = mTarget / fs::relative(it->path(), mStaging);
        if (it->is_directory())
            fs::create_directories(destination, ec);
        else
            fs::rename(it->path(), destination, ec);
        require(!ec, mName + ": cannot move " + destination.string() + " into place: " + ec.message());
    }
    require(!ec, mName + ": cannot move the finished report into place: " + ec.message());
    fs::remove_all(mStaging, ec);
    mCommitted = true;
}

std::string svgLinePlot(const std::string& title, const std::string& xLabel, const std::string& yLabel,
                        const std::vector<PlotSeries>& series, int width, int height)
{
    const double left = 64, right = 150, top = 30, bottom = 44;
    const double plotW = width - left - right, plotH = height - top - bottom;
    double yMin = 1e300, yMax = -1e300;
    std::size_t count = 0;
    for (const PlotSeries& s : series) {
        count = std::max(count, s.values.size());
        for (double v : s.values) {
            if (!std::isfinite(v)) continue;
            yMin = std::min(yMin, v);
            yMax = std::max(yMax, v);
        }
    }
    if (yMin > yMax) yMin = 0.0, yMax = 1.0;
    if (yMax - yMin < 1e-12) yMax = yMin + std::max(1e-6, std::abs(yMin) * 0.1);
    const double pad = 0.05 * (yMax - yMin);
    yMin -= pad;
    yMax += pad;
    const double xMax = std::max<double>(1.0, static_cast<double>(count) - 1.0);
    auto px = [&](double x) { return left + plotW * x / xMax; };
    auto py = [&](double y) { return top + plotH * (1.0 - (y - yMin) / (yMax - yMin)); };

    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\"" << height
        << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
    svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    svg << "<text x=\"" << left << "\" y=\"18\" font-size=\"13\" font-weight=\"bold\">" << htmlEscape(title)
        << "</text>\n";
    // Axes and ticks.
    svg << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << plotW << "\" height=\"" << plotH
        << "\" fill=\"none\" stroke=\"#444\"/>\n";
    for (int i = 0; i <= 4; ++i) {
        double y = yMin + (yMax - yMin) * i / 4.0;
        svg << "<line x1=\"" << left << "\" x2=\"" << left + plotW << "\" y1=\"" << py(y) << "\" y2=\"" << py(y)
            << "\" stroke=\"#ddd\"/>\n";
        svg << "<text x=\"" << left - 6 << "\" y=\"" << py(y) + 4 << "\" text-anchor=\"end\">" << formatNumber(y, 3)
            << "</text>\n";
    }
    const int xTicks = static_cast<int>(std::min<double>(10.0, xMax));
    for (int i = 0; i <= xTicks; ++i) {
        double x = xMax * i / std::max(1, xTicks);
        svg << "<text x=\"" << px(x) << "\" y=\"" << top + plotH + 16 << "\" text-anchor=\"middle\">"
            << formatNumber(std::round(x), 4) << "</text>\n";
    }
    svg << "<text x=\"" << left + plotW / 2 << "\" y=\"" << height - 8 << "\" text-anchor=\"middle\">"
        << htmlEscape(xLabel) << "</text>\n";
    svg << "<text transform=\"translate(14," << top + plotH / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
        << htmlEscape(yLabel) << "</text>\n";
    // Series and legend.
    for (std::size_t s = 0; s < series.size(); ++s) {
        const PlotSeries& ps = series[s];
        svg << "<polyline fill=\"none\" stroke=\"" << ps.color << "\" stroke-width=\"1.6\""
            << (ps.dashed ? " stroke-dasharray=\"5,3\"" : "") << " points=\"";
        for (std::size_t i = 0; i < ps.values.size(); ++i)
            if (std::isfinite(ps.values[i])) svg << px(static_cast<double>(i)) << "," << py(ps.values[i]) << " ";
        svg << "\"/>\n";
        if (ps.values.size() == 1)
            svg << "<circle cx=\"" << px(0) << "\" cy=\"" << py(ps.values[0]) << "\" r=\"3\" fill=\"" << ps.color
                << "\"/>\n";
        double ly = top + 10 + 16.0 * static_cast<double>(s);
        svg << "<line x1=\"" << left + plotW + 10 << "\" x2=\"" << left + plotW + 30 << "\" y1=\"" << ly << "\" y2=\""
            << ly << "\" stroke=\"" << ps.color << "\" stroke-width=\"2\"" << (ps.dashed ? " stroke-dasharray=\"5,3\"" : "")
            << "/>\n";
        svg << "<text x=\"" << left + plotW + 34 << "\" y=\"" << ly + 4 << "\">" << htmlEscape(ps.name) << "</text>\n";
    }
    svg << "</svg>\n";
    return svg.str();
}

namespace {

const char* const kColors[] = {"#d62728", "#1f77b4", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2"};

} // namespace

std::string compareImageName(const std::string& who, int frame, const std::string& suffix)
{
    char b[32];
    std::snprintf(b, sizeof b, "f%04d", frame);
    // Variants ("smcir[smcir.shading=exhaustive]") keep only file-name-safe characters.
    std::string safe = who;
    for (char& c : safe)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
    return "images/" + safe + "-" + b + suffix;
}

bool compareKeepsImages(int frame, int frames)
{
    return frame == 0 || frame == frames - 1;
}

ReferenceNoiseCheck referenceNoiseCheck(const CompareReport& report)
{
    ReferenceNoiseCheck check;
    for (const CompareTechniqueResult& t : report.techniques)
        if (check.smallestName.empty() || t.temporal.meanAbsDerivative < check.smallestEPrime) {
            check.smallestEPrime = t.temporal.meanAbsDerivative;
            check.smallestName = t.name;
        }
    check.applicable = report.frames > 1 && check.smallestEPrime > 0.0;
    check.holds = check.applicable && report.referenceSelf.meanAbsDerivative <= kReferenceNoiseRatio * check.smallestEPrime;
    return check;
}

namespace {

std::string noiseCheckText(const CompareReport& report)
{
    const ReferenceNoiseCheck check = referenceNoiseCheck(report);
    std::ostringstream text;
    text << "reference's own |E'| (its second seed against its first) " << formatNumber(report.referenceSelf.meanAbsDerivative)
         << ", |E| " << formatNumber(report.referenceSelf.meanAbsError) << "; ";
    if (!check.applicable)
        text << "the " << kReferenceNoiseRatio << "x check does not apply (one frame, or no technique has |E'| > 0)";
    else
        text << "smallest technique |E'| " << formatNumber(check.smallestEPrime) << " (" << check.smallestName
             << "): reference <= " << kReferenceNoiseRatio << "x it: " << (check.holds ? "yes" : "NO") << " (ratio "
             << formatNumber(report.referenceSelf.meanAbsDerivative / check.smallestEPrime, 3) << ")";
    return text.str();
}

// A metric over compare --seeds' seeds: "0.0156 [0.0150, 0.0162]" (the mean with its 95% interval),
// or "0.0156" for one value; `unit` after the numbers.
std::string seedsText(const std::vector<double>& values, int digits = 4, const std::string& unit = "")
{
    const MeanInterval m = meanInterval(values);
    if (m.count <= 1) return formatNumber(m.mean, digits) + unit;
    return formatNumber(m.mean, digits) + unit + " [" + formatNumber(m.mean - m.halfWidth, digits) + ", " +
           formatNumber(m.mean + m.halfWidth, digits) + "]";
}

// The half-width of the 95% interval of a metric over the seeds (0 for one value).
double seedsHalfWidth(const std::vector<double>& values)
{
    return meanInterval(values).halfWidth;
}

// "0.42 [0.35, 0.49]": a ratio with its interval.
std::string ratioIntervalText(const RatioInterval& r)
{
    return formatNumber(r.ratio, 3) + " [" + formatNumber(r.low, 3) + ", " + formatNumber(r.high, 3) + "]";
}

// An image metric, or "" (CSV) / "null" (JSON) / "-" (HTML) without a full-image reference.
std::string imageMetric(const CompareReport& report, double value, const char* missing)
{
    if (!report.imageMetrics) return missing;
    std::ostringstream s;
    s << value;
    return s.str();
}

} // namespace

std::string compareTemporalSummary(const CompareReport& report)
{
    std::ostringstream text;
    text << "tracked pixels (" << report.trackedChoice << "):";
    for (const glm::ivec2& p : report.trackedPixels) text << " (" << p.x << "," << p.y << ")";
    text << "\ntemporal metrics at the tracked pixels (" << report.frames << " frames, reference "
         << report.trackedReferenceSpp << " spp per pixel, " << formatNumber(report.trackedReferenceSeconds, 3)
         << " s for both seeds):\n";
    for (const CompareTechniqueResult& t : report.techniques)
        text << "  " << t.name << (t.settings.empty() ? "" : " [" + t.settings + "]") << ": |E| "
             << seedsText(t.seedAbsE) << "  |E'| " << seedsText(t.seedAbsEPrime)
             << (t.seeds() > 1 ? " (" + std::to_string(t.seeds()) + " seeds)" : std::string()) << "\n";
    text << "  " << noiseCheckText(report) << "\n";
    if (!report.against.empty()) {
        text << "difference from " << report.against << " (mean |A - B| after the tone map, 99.9th percentile;"
             << " |E'| / " << report.against << "'s |E'| with its 95% interval over the tracked pixels):\n";
        for (const CompareTechniqueResult& t : report.techniques)
            if (t.name != report.against)
                text << "  " << t.name << (t.settings.empty() ? "" : " [" + t.settings + "]") << ": "
                     << formatNumber(t.againstErrors.meanAbsToneMapped) << "  "
                     << formatNumber(t.againstErrors.p999AbsToneMapped) << "  |E'| ratio "
                     << ratioIntervalText(t.againstEPrime) << "\n";
    }
    return text.str();
}

std::string compareCsv(const CompareReport& report)
{
    std::ostringstream csv;
    csv << "technique,frames,mean_abs_tonemapped,p999_abs_tonemapped,rmse,relative_mse,mean_luminance_bias,temporal_abs_e,"
           "temporal_abs_e_prime,median_frame_ms,seeds,temporal_abs_e_half95,temporal_abs_e_prime_half95,against,against_mean_abs_tonemapped,against_p999_abs_tonemapped,"
           "against_abs_e_prime_ratio,against_abs_e_prime_ratio_low,against_abs_e_prime_ratio_high,settings\n";
    for (const CompareTechniqueResult& t : report.techniques) {
        const ImageErrors& mean = t.meanErrors;
        csv << t.name << "," << report.frames << "," << imageMetric(report, mean.meanAbsToneMapped, "") << ","
            << imageMetric(report, mean.p999AbsToneMapped, "") << "," << imageMetric(report, mean.rmse, "") << "," << imageMetric(report, mean.relativeMSE, "") << ","
            << imageMetric(report, mean.meanRelativeLuminance, "") << "," << t.temporal.meanAbsError << ","
            << t.temporal.meanAbsDerivative << "," << t.medianFrameMs << "," << t.seeds() << ","
            << seedsHalfWidth(t.seedAbsE) << "," << seedsHalfWidth(t.seedAbsEPrime) << "," << report.against << ",";
        if (!report.against.empty())
            csv << t.againstErrors.meanAbsToneMapped << "," << t.againstErrors.p999AbsToneMapped << ","
                << t.againstEPrime.ratio << "," << t.againstEPrime.low << "," << t.againstEPrime.high;
        else
            csv << ",,,,";
        csv << "," << t.settings << "\n";
    }
    return csv.str();
}

std::string compareJson(const CompareReport& report)
{
    using Json = nlohmann::ordered_json;
    // A whole-image metric, null when the run had no image metrics (no reference image).
    auto metric = [&](double value) { return report.imageMetrics ? Json(value) : Json(nullptr); };
    auto imagePerSeed = [&](const CompareTechniqueResult& t) {
        if (!report.imageMetrics) return Json(nullptr);
        Json seeds = {{"meanAbsToneMapped", Json::array()}, {"rmse", Json::array()}, {"meanLuminanceBias", Json::array()}};
        for (const ImageErrors& e : t.seedImageErrors) {
            seeds["meanAbsToneMapped"].push_back(e.meanAbsToneMapped);
            seeds["rmse"].push_back(e.rmse);
            seeds["meanLuminanceBias"].push_back(e.meanRelativeLuminance);
        }
        return seeds;
    };
    const ReferenceNoiseCheck check = referenceNoiseCheck(report);
    Json pixels = Json::array();
    for (const glm::ivec2& p : report.trackedPixels) pixels.push_back({p.x, p.y});
    Json techniques = Json::array();
    for (const CompareTechniqueResult& t : report.techniques) {
        const ImageErrors& mean = t.meanErrors;
        Json entry = {{"name", t.name},
                      {"settings", t.settings},
                      {"meanAbsToneMapped", metric(mean.meanAbsToneMapped)},
                      {"p999AbsToneMapped", metric(mean.p999AbsToneMapped)},
                      {"rmse", metric(mean.rmse)},
                      {"relativeMSE", metric(mean.relativeMSE)},
                      {"meanLuminanceBias", metric(mean.meanRelativeLuminance)},
                      {"temporalAbsE", t.temporal.meanAbsError},
                      {"temporalAbsEPrime", t.temporal.meanAbsDerivative},
                      {"medianFrameMs", t.medianFrameMs},
                      // compare --seeds: temporalAbsE(Prime) are the means over the seeds, with the
                      // half-widths of their 95% Student-t intervals and the per-seed values.
                      {"seeds", t.seeds()},
                      {"temporalAbsEHalf95", seedsHalfWidth(t.seedAbsE)},
                      {"temporalAbsEPrimeHalf95", seedsHalfWidth(t.seedAbsEPrime)},
                      {"temporalAbsEPerSeed", t.seedAbsE},
                      {"temporalAbsEPrimePerSeed", t.seedAbsEPrime},
                      // The image metrics above are means over the seeds; per seed here (null
                      // without a full-image reference).
                      {"imageMetricsPerSeed", imagePerSeed(t)},
                      {"trackedLuminance", t.tracked}}; // [frame][tracked pixel] linear luminance
        if (!report.against.empty())
            entry["against"] = {{"technique", report.against},
                                {"meanAbsToneMapped", t.againstErrors.meanAbsToneMapped},
                                {"p999AbsToneMapped", t.againstErrors.p999AbsToneMapped},
                                {"absEPrimeRatio", t.againstEPrime.ratio},
                                {"absEPrimeRatioLow", t.againstEPrime.low},
                                {"absEPrimeRatioHigh", t.againstEPrime.high}};
        techniques.push_back(std::move(entry));
    }
    const Json json = {{"scene", report.sceneSource},
                       {"width", report.width},
                       {"height", report.height},
                       {"frames", report.frames},
                       {"exposure", report.exposure},
                       {"reference",
                        {{"mode", report.referenceMode},
                         {"spp", report.referenceSpp},
                         {"rendered", report.referencesRendered},
                         {"settings", report.referenceSettings}}},
                       {"tracked",
                        {{"choice", report.trackedChoice},
                         {"pixels", pixels},
                         {"referenceSpp", report.trackedReferenceSpp},
                         {"referenceSeconds", report.trackedReferenceSeconds},
                         {"referenceAbsE", report.referenceSelf.meanAbsError},
                         {"referenceAbsEPrime", report.referenceSelf.meanAbsDerivative},
                         {"noiseCheckApplies", check.applicable},
                         {"noiseCheckHolds", check.holds},
                         {"referenceLuminance", report.referenceTracked}}},
                       {"techniques", techniques}};
    return json.dump(2) + "\n";
}

std::string compareTrackedPlotName(std::size_t pixel)
{
    return "luminance-pixel" + std::to_string(pixel) + ".svg";
}

std::string compareTrackedPlot(const CompareReport& report, std::size_t pixel)
{
    std::vector<PlotSeries> series;
    PlotSeries reference{"reference", {}, "#000000", true};
    for (const std::vector<double>& frame : report.referenceTracked) reference.values.push_back(frame[pixel]);
    series.push_back(reference);
    for (std::size_t t = 0; t < report.techniques.size(); ++t) {
        PlotSeries s{report.techniques[t].name, {}, kColors[t % 7], false};
        for (const std::vector<double>& frame : report.techniques[t].tracked) s.values.push_back(frame[pixel]);
        series.push_back(s);
    }
    const glm::ivec2 p = report.trackedPixels[pixel];
    return svgLinePlot("tracked pixel " + std::to_string(pixel) + " (" + std::to_string(p.x) + ", " +
                           std::to_string(p.y) + ")",
                       "frame", "luminance [W/(m^2 sr)]", series, 480, 240);
}

namespace {

std::string metricsTableRows(const CompareReport& report)
{
    std::ostringstream table;
    for (const CompareTechniqueResult& t : report.techniques) {
        const ImageErrors& mean = t.meanErrors;
        auto cell = [&](double value, int digits = 4, const char* unit = "") {
            return report.imageMetrics ? formatNumber(value, digits) + unit : std::string("-");
        };
        // Over seeds (compare --seeds): the mean with its 95% interval.
        auto seedsCell = [&](double ImageErrors::*field, double scale = 1.0, int digits = 4, const char* unit = "") {
            if (!report.imageMetrics) return std::string("-");
            std::vector<double> values;
            for (const ImageErrors& e : t.seedImageErrors) values.push_back(scale * (e.*field));
            return seedsText(values, digits, unit);
        };
        table << "<tr><td>" << htmlEscape(t.name) << "</td><td>" << htmlEscape(t.settings) << "</td><td>"
              << seedsCell(&ImageErrors::meanAbsToneMapped) << "</td><td>" << cell(mean.p999AbsToneMapped) << "</td><td>"
              << seedsCell(&ImageErrors::rmse) << "</td><td>"
              << cell(mean.relativeMSE) << "</td><td>" << seedsCell(&ImageErrors::meanRelativeLuminance, 100.0, 3, "%")
              << "</td><td>" << seedsText(t.seedAbsE) << "</td><td>" << seedsText(t.seedAbsEPrime)
              << "</td><td>" << formatNumber(t.medianFrameMs, 4);
        if (!report.against.empty())
            table << "</td><td>" << formatNumber(t.againstErrors.meanAbsToneMapped) << "</td><td>"
                  << formatNumber(t.againstErrors.p999AbsToneMapped) << "</td><td>"
                  << ratioIntervalText(t.againstEPrime);
        table << "</td></tr>\n";
    }
    return table.str();
}

// The reference, each technique and each technique's error heat map at one frame.
std::string frameFigures(const CompareReport& report, int frame)
{
    std::ostringstream html;
    if (report.imageMetrics)
        html << "<figure><img src=\"" << compareImageName("reference", frame, ".png")
             << "\"><figcaption>reference</figcaption></figure>\n";
    for (const CompareTechniqueResult& t : report.techniques)
        html << "<figure><img src=\"" << compareImageName(t.name, frame, ".png") << "\"><figcaption>"
             << htmlEscape(t.name) << "</figcaption></figure>\n";
    if (!report.against.empty()) {
        html << "<br>\n";
        for (const CompareTechniqueResult& t : report.techniques)
            if (t.name != report.against)
                html << "<figure><img src=\"" << compareImageName(t.name, frame, "-difference.png")
                     << "\"><figcaption>" << htmlEscape(t.name) << " against " << htmlEscape(report.against)
                     << ": |A - B| after the tone map (black 0, white &ge; 0.05)</figcaption></figure>\n";
    }
    if (!report.imageMetrics) return html.str();
    html << "<br>\n";
    for (const CompareTechniqueResult& t : report.techniques)
        html << "<figure><img src=\"" << compareImageName(t.name, frame, "-error.png") << "\"><figcaption>"
             << htmlEscape(t.name) << ": |E| heat map (black 0, white &ge; 0.25)</figcaption></figure>\n";
    return html.str();
}

} // namespace

std::string compareHtml(const CompareReport& report)
{
    std::ostringstream html;
    html << "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>vplgi compare: "
         << htmlEscape(report.sceneName) << "</title>\n<style>body{font-family:sans-serif;margin:20px;max-width:1400px}"
         << "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:4px 8px;text-align:right}"
         << "td:first-child{text-align:left}figure{display:inline-block;margin:4px}figcaption{font-size:12px}"
         << "img{image-rendering:pixelated}</style></head><body>\n";
    html << "<h1>vplgi compare: " << htmlEscape(report.sceneName) << "</h1>\n<p>" << report.width << "x"
         << report.height << ", " << report.frames << " frame(s) at " << report.fps
         << " fps; reference: Embree path tracer, mode " << htmlEscape(report.referenceMode) << " ("
         << htmlEscape(report.referenceSettings) << "), full image "
         << (report.imageMetrics ? std::to_string(report.referenceSpp) + " spp" : std::string("not rendered (--spp 0)"))
         << ", tracked pixels " << report.trackedReferenceSpp << " spp each ("
         << report.referencesRendered
         << " distinct reference frame(s)); tone mapping for |E|: Reinhard on luminance at exposure "
         << report.exposure << ". Metrics compare " << report.comparedPart
         << " with the reference; the images show the whole display image.</p>\n";
    html << "<p>Tracked pixels (" << report.trackedPixels.size() << "): " << htmlEscape(report.trackedChoice) << ":";
    for (const glm::ivec2& p : report.trackedPixels) html << " (" << p.x << ", " << p.y << ")";
    html << ". Their temporal metrics (SMCIR Table 1: average |E| and |E'| after Reinhard tone mapping, eq. 10) "
         << "are measured against the tracked-pixel reference; the image metrics against the full-image one."
         << (report.seeds > 1 ? " Over " + std::to_string(report.seeds) +
                                    " seeds (--seeds; each technique's own seeds 1.." + std::to_string(report.seeds) +
                                    "): |E| and |E'| at the tracked pixels and the image metrics' mean |E|, RMSE and "
                                    "luminance bias are means with 95% Student-t intervals (the other image metrics "
                                    "means); images and plots are seed 1's."
                              : std::string())
         << "</p>\n";
    html << "<p>Reference noise: " << htmlEscape(noiseCheckText(report)) << ".</p>\n";
    html << "<h2>Metrics</h2>\n<table><tr><th>technique</th><th>settings (--set)</th><th>mean |E| (tone-mapped)</th>"
         << "<th>99.9th pct |E|</th><th>RMSE</th><th>rel. MSE</th>"
         << "<th>mean luminance bias</th><th>avg |E| tracked</th><th>avg |E'| tracked (SMCIR eq. 10)</th>"
         << "<th>median frame [ms]</th>"
         << (report.against.empty() ? std::string()
                                    : "<th>mean |A - " + htmlEscape(report.against) + "| (tone-mapped)</th><th>99.9th pct</th>"
                                      "<th>|E'| / " + htmlEscape(report.against) +
                                          "'s [95% interval over the tracked pixels]</th>")
         << "</tr>\n"
         << metricsTableRows(report) << "</table>\n<p>All numbers: <a href=\"metrics.csv\">metrics.csv</a>, "
         << "<a href=\"metrics.json\">metrics.json</a>. Frame times are on this machine's OpenGL implementation.</p>\n";
    html << "<h2>Frame 0</h2>\n" << frameFigures(report, 0);
    if (report.frames > 1) {
        const int last = report.frames - 1;
        html << "<h2>Last frame (" << last << ")</h2>\n" << frameFigures(report, last);
    }
    html << "<h2>Luminance over time at tracked pixels</h2>\n";
    if (report.trackedPixels.size() > kPlottedTrackedPixels)
        html << "<p>The first " << kPlottedTrackedPixels << " of " << report.trackedPixels.size() << ".</p>\n";
    for (std::size_t j = 0; j < std::min(report.trackedPixels.size(), kPlottedTrackedPixels); ++j)
        html << "<img src=\"" << compareTrackedPlotName(j) << "\" alt=\"luminance over time at tracked pixel " << j
             << "\">\n";
    html << "\n</body></html>\n";
    return html.str();
}

void writeCompareReport(const std::string& directory, const CompareReport& report)
{
    for (std::size_t j = 0; j < std::min(report.trackedPixels.size(), kPlottedTrackedPixels); ++j)
        writeTextFile(directory + "/" + compareTrackedPlotName(j), compareTrackedPlot(report, j));
    writeTextFile(directory + "/metrics.csv", compareCsv(report));
    writeTextFile(directory + "/metrics.json", compareJson(report));
    writeTextFile(directory + "/index.html", compareHtml(report));
}

} // namespace vplgi
