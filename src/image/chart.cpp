#include "image/chart_layout.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tripath::chart {

namespace {

LogAxis axisFor(const std::vector<double>& values) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (double v : values)
        if (plottable(v)) {
            lo = std::min(lo, std::log10(v));
            hi = std::max(hi, std::log10(v));
        }
    if (lo > hi) return {0, 1};  // nothing to show: one decade
    // At least a third of a decade, so a flat line still gets ticks, plus a margin on both ends.
    const double span = std::max(hi - lo, 0.3), mid = (lo + hi) / 2;
    lo = std::min(lo, mid - span / 2);
    hi = std::max(hi, mid + span / 2);
    return {lo - 0.05 * span, hi + 0.05 * span};
}

// 1..9 x 10^d inside the axis; decades are labelled, and 2 and 5 (then every one) as well when
// the axis spans too little for two labelled decades.
std::vector<Tick> ticksFor(const LogAxis& a) {
    std::vector<Tick> ticks;
    for (int d = static_cast<int>(std::floor(a.lo)); d <= static_cast<int>(std::ceil(a.hi)); ++d)
        for (int m = 1; m <= 9; ++m) {
            const double v = m * std::pow(10.0, d);
            if (std::log10(v) >= a.lo && std::log10(v) <= a.hi) ticks.push_back({v, m == 1});
        }
    auto labelled = [&] { return std::count_if(ticks.begin(), ticks.end(), [](const Tick& t) { return t.labelled; }); };
    auto mantissa = [](double v) { return static_cast<int>(std::lround(v / std::pow(10.0, std::floor(std::log10(v) + 1e-9)))); };
    if (labelled() < 2)
        for (Tick& t : ticks) t.labelled = t.labelled || mantissa(t.value) == 2 || mantissa(t.value) == 5;
    if (labelled() < 2)
        for (Tick& t : ticks) t.labelled = true;
    return ticks;
}

}  // namespace

double LogAxis::unit(double v) const { return (std::log10(v) - lo) / (hi - lo); }

bool plottable(double v) { return std::isfinite(v) && v > 0; }

Layout layout(const LogLogChart& chart) {
    std::vector<double> xs, ys;
    for (const ChartSeries& s : chart.series) {
        xs.insert(xs.end(), s.x.begin(), s.x.end());
        for (const auto* v : {&s.y, &s.low, &s.high}) ys.insert(ys.end(), v->begin(), v->end());
    }
    Layout l;
    l.plot = {78, 40, chart.width - 78 - 24, chart.height - 40 - 56};
    l.x = axisFor(xs);
    l.y = axisFor(ys);
    l.xTicks = ticksFor(l.x);
    l.yTicks = ticksFor(l.y);
    int nameWidth = 0;
    for (const ChartSeries& s : chart.series) nameWidth = std::max<int>(nameWidth, 8 * s.name.size());
    const int w = 46 + nameWidth, h = 10 + Layout::legendRow * static_cast<int>(chart.series.size());
    l.legend = {l.plot.x + l.plot.w - w - 10, l.plot.y + 10, w, h};
    return l;
}

Point toPixel(const Layout& l, double x, double y) {
    return {l.plot.x + l.x.unit(x) * l.plot.w, l.plot.y + (1 - l.y.unit(y)) * l.plot.h};
}

std::vector<Point> linePoints(const Layout& l, const ChartSeries& s) {
    std::vector<Point> pts;
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
        if (plottable(s.x[i]) && plottable(s.y[i])) pts.push_back(toPixel(l, s.x[i], s.y[i]));
    return pts;
}

std::vector<Point> bandOutline(const Layout& l, const ChartSeries& s) {
    std::vector<Point> upper, lower;
    if (s.low.size() != s.x.size() || s.high.size() != s.x.size()) return {};
    for (size_t i = 0; i < s.x.size(); ++i)
        if (plottable(s.x[i]) && plottable(s.low[i]) && plottable(s.high[i])) {
            upper.push_back(toPixel(l, s.x[i], s.high[i]));
            lower.push_back(toPixel(l, s.x[i], s.low[i]));
        }
    upper.insert(upper.end(), lower.rbegin(), lower.rend());
    return upper;
}

std::string tickLabel(double v) { return fmt::format("{:g}", v); }

}  // namespace tripath::chart
