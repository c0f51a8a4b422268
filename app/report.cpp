#include "report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"

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
    fs::path target(path);
    fs::path temporary = target.parent_path() / ("." + target.filename().string() + ".partial");
    {
        std::ofstream out(temporary, std::ios::binary);
        require(out.good(), path + ": cannot write");
        out << text;
        require(out.good(), path + ": write failed");
    }
    fs::rename(temporary, target);
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

} // namespace vplgi
