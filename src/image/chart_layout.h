// Private to the chart renderers (chart_svg.cpp, chart_raster.cpp): where the plot area, the
// ticks and the legend go, computed once so the SVG and the PNG agree.
#pragma once
#include <string>
#include <vector>

#include "image/chart.h"
#include "image/draw.h"

namespace tripath::chart {

// log10 of the values at the two ends of an axis.
struct LogAxis {
    double lo = 0, hi = 1;
    double unit(double v) const;  // 0 at lo, 1 at hi
};

struct Tick {
    double value;
    bool labelled;
};

struct Layout {
    Region plot;
    LogAxis x, y;
    std::vector<Tick> xTicks, yTicks;
    Region legend;
    static constexpr int legendRow = 20, fontSize = 13, titleSize = 15;
};

Layout layout(const LogLogChart& chart);
// Pixel position of a data point (y grows downwards in pixels, upwards in data).
Point toPixel(const Layout& l, double x, double y);
bool plottable(double v);
// The series' plottable points, and its band as a closed outline (high forwards, low backwards).
std::vector<Point> linePoints(const Layout& l, const ChartSeries& s);
std::vector<Point> bandOutline(const Layout& l, const ChartSeries& s);
std::string tickLabel(double v);

}  // namespace tripath::chart
