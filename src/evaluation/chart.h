// Log-log line charts (error against time), as SVG text and as an Image for PNG: one drawing
// (Cairo, in chart.cpp) onto both, so that the two always show the same thing.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "image/image.h"

namespace tripath {

struct ChartSeries {
    std::string name;
    std::array<uint8_t, 3> color{0, 0, 0};  // sRGB, as "#rrggbb" in the SVG
    std::vector<double> x, y;               // the line, one point per entry
    std::vector<double> low, high;          // optional band around it (empty, or one per point)
};

struct LogLogChart {
    std::string title, xLabel, yLabel;
    std::vector<ChartSeries> series;
    int width = 800, height = 500;
};

// Points that a log axis cannot show (zero, negative, NaN) are left out of lines and bands. Text
// is in DejaVu Sans (text.h's requireFont checks for it), drawn as glyph outlines in the SVG.
std::string chartSvg(const LogLogChart& chart);
Image chartImage(const LogLogChart& chart);

}  // namespace tripath
