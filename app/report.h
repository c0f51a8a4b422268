// Writing reports: SVG line plots and small files written atomically. The HTML of `vplgi compare`
// is assembled in compare_command.cpp from these parts; everything works offline in any browser.
#pragma once

#include <string>
#include <vector>

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

} // namespace vplgi
