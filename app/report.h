// Writing reports: SVG line plots, small files written atomically, and the report of `vplgi compare`
// (index.html, metrics.csv, metrics.json, plots) from plain data; everything works offline in any
// browser.
#pragma once

#include <cstddef>
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

std::string htmlEscape(const std::string& text);
std::string formatNumber(double value, int significant = 4);

// What `vplgi compare` measured for one technique.
struct CompareTechniqueResult {
    std::string name;
    ImageErrors meanErrors;                   // averaged over frames
    TemporalErrors temporal;                  // at the tracked pixels
    double medianFrameMs = 0.0;
    std::vector<std::vector<double>> tracked; // [frame][pixel] luminance
};

// Everything the compare report shows besides the images (written while rendering, named by
// compareImageName).
struct CompareReport {
    std::string sceneSource, sceneName;
    int width = 0, height = 0, frames = 0;
    float fps = 0.0f;
    double exposure = 1.0;     // of the tone mapping behind |E| and the PNGs
    std::string referenceMode; // as given on the command line
    int referenceSpp = 0;
    int referencesRendered = 0; // distinct reference frames
    std::string comparedPart;   // what the metrics compare, e.g. "each technique's direct light"
    std::vector<glm::ivec2> trackedPixels;
    std::vector<std::vector<double>> referenceTracked; // [frame][pixel] luminance
    std::vector<CompareTechniqueResult> techniques;
};

// "images/<who>-f0007<suffix>": who is "reference" or a technique, suffix e.g. ".png", "-error.png".
std::string compareImageName(const std::string& who, int frame, const std::string& suffix);
// The frames whose images are kept: the first and the last.
bool compareKeepsImages(int frame, int frames);

std::string compareCsv(const CompareReport& report);
std::string compareJson(const CompareReport& report);
// Luminance over time at one tracked pixel, the reference dashed (SMCIR Fig. 7).
std::string compareTrackedPlot(const CompareReport& report, std::size_t pixel);
std::string compareTrackedPlotName(std::size_t pixel);
std::string compareHtml(const CompareReport& report);
// Writes the plots, metrics.csv, metrics.json and index.html into `directory`.
void writeCompareReport(const std::string& directory, const CompareReport& report);

} // namespace vplgi
