// Writing reports: SVG line plots, small files written atomically, and the report of `vplgi compare`
// (index.html, metrics.csv, metrics.json, plots) from plain data; everything works offline in any
// browser.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "core/util/metrics.h"

namespace vplgi {

struct PlotSeries {
    std::string name;
    std::vector<double> values; // y per x index
    std::string color;          // CSS colour
    bool dashed = false;
};

// A line plot with axes, ticks and a legend, as a standalone SVG document.
std::string svgLinePlot(const std::string& title, const std::string& xLabel, const std::string& yLabel,
                        const std::vector<PlotSeries>& series, int width = 640, int height = 300);

// Writes text to a temporary sibling and renames it into place (never a half file).
void writeTextFile(const std::string& path, const std::string& text);

// A report directory built under a temporary sibling name (".<name>.partial-N") and moved into
// place by commit(): a run that fails part-way (bad input found late, a full disk, a file size
// limit) leaves no half report. Parent directories created for it are removed again when it is not
// committed. Committing into an existing directory replaces the files of the same names.
class StagedDirectory {
public:
    explicit StagedDirectory(const std::string& target); // throws Error naming target
    ~StagedDirectory();
    StagedDirectory(const StagedDirectory&) = delete;
    StagedDirectory& operator=(const StagedDirectory&) = delete;

    std::string path() const { return mStaging.string(); } // write everything here
    void commit();

private:
    std::string mName;                       // as given, for messages
    std::filesystem::path mTarget, mStaging;
    std::vector<std::filesystem::path> mCreated; // parents created for it, deepest first
    bool mCommitted = false;
};

std::string htmlEscape(const std::string& text);
std::string formatNumber(double value, int significant = 4);

// What `vplgi compare` measured for one technique.
struct CompareTechniqueResult {
    std::string name;
    ImageErrors meanErrors;                   // averaged over frames
    TemporalErrors temporal;                  // at the tracked pixels, against the tracked-pixel reference
    double medianFrameMs = 0.0;
    std::vector<std::vector<double>> tracked; // [frame][pixel] luminance
    std::string settings;                     // the --set overrides its session used, "key=value ..."
    ImageErrors againstErrors;                // against CompareReport::against's image, averaged over frames
    RatioInterval againstEPrime;              // |E'| / the against technique's |E'|, with its 95% interval
    // Per seed, seed 1 first (one entry without compare --seeds or without a seed of its own).
    // `temporal` and `meanErrors` are their means (`temporal` per tracked pixel too); `tracked` and
    // the images stay the first seed's.
    std::vector<double> seedAbsE, seedAbsEPrime;
    std::vector<ImageErrors> seedImageErrors; // each averaged over the frames
    int seeds() const { return static_cast<int>(seedAbsE.size()); }
};

// Everything the compare report shows besides the images (written while rendering, named by
// compareImageName).
struct CompareReport {
    std::string sceneSource, sceneName;
    int width = 0, height = 0, frames = 0;
    float fps = 0.0f;
    double exposure = 1.0;     // of the tone mapping behind |E| and the PNGs
    std::string referenceMode; // as given on the command line
    std::string referenceSettings; // the path tracer's effective settings, e.g. "maxDepth 4, ..."
    int referenceSpp = 0;       // of the full-image reference
    bool imageMetrics = true;   // false without a full-image reference (--spp 0): no image errors
    int referencesRendered = 0; // distinct reference frames
    std::string comparedPart;   // what the metrics compare, e.g. "each technique's direct light"
    std::vector<glm::ivec2> trackedPixels;
    std::string trackedChoice;  // how the tracked pixels were chosen
    int trackedReferenceSpp = 0;            // samples per tracked pixel of the tracked-pixel reference
    double trackedReferenceSeconds = 0.0;   // its render time, both seeds, all frames [s]
    std::vector<std::vector<double>> referenceTracked; // [frame][pixel] luminance (first seed)
    TemporalErrors referenceSelf;           // the second seed's run against the first: its own |E|, |E'|
    std::vector<CompareTechniqueResult> techniques;
    std::string against; // --against: the technique every image is also compared with ("" = none)
    int seeds = 1;       // --seeds
};

// Whether the tracked-pixel reference is quiet enough: its own |E'| <= 0.2x the smallest |E'| of
// any technique. Not applicable with one frame (no E') or when every technique has |E'| = 0.
struct ReferenceNoiseCheck {
    bool applicable = false;
    bool holds = false;
    double smallestEPrime = 0.0;
    std::string smallestName;
};
constexpr double kReferenceNoiseRatio = 0.2;
ReferenceNoiseCheck referenceNoiseCheck(const CompareReport& report);
// A few lines for stdout: Table 1's columns per technique, the reference's own |E'| and the check.
std::string compareTemporalSummary(const CompareReport& report);

// "images/<who>-f0007<suffix>": who is "reference" or a technique, suffix e.g. ".png", "-error.png".
std::string compareImageName(const std::string& who, int frame, const std::string& suffix);
// The frames whose images are kept: the first and the last.
bool compareKeepsImages(int frame, int frames);

std::string compareCsv(const CompareReport& report);
std::string compareJson(const CompareReport& report);
// Luminance over time at one tracked pixel, the reference dashed (SMCIR Fig. 7): made for the first
// kPlottedTrackedPixels tracked pixels (every tracked pixel's metrics are in the tables).
constexpr int kMaxTrackedPixels = 1024;
constexpr std::size_t kPlottedTrackedPixels = 16;
std::string compareTrackedPlot(const CompareReport& report, std::size_t pixel);
std::string compareTrackedPlotName(std::size_t pixel);
std::string compareHtml(const CompareReport& report);
// Writes the plots, metrics.csv, metrics.json and index.html into `directory`.
void writeCompareReport(const std::string& directory, const CompareReport& report);

} // namespace vplgi
