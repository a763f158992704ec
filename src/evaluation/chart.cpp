// Log-log charts drawn with Cairo: one routine, drawChart, lays the chart out and draws it onto
// whichever surface it is given, so the SVG and the PNG are the same drawing by construction.
#include "evaluation/chart.h"

#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "evaluation/cairo_canvas.h"

namespace tripath {

namespace {

using canvas::Anchor, canvas::setColor, canvas::text;

constexpr double kLegendRow = 20;
constexpr canvas::Font kLabel{13}, kTitle{15, true}, kAxisName{14};

// log10 of the values at the two ends of an axis.
struct LogAxis {
    double lo = 0, hi = 1;
    double unit(double v) const { return (std::log10(v) - lo) / (hi - lo); }  // 0 at lo, 1 at hi
};

struct Tick {
    double value;
    bool labelled;
};

struct Box {
    double x, y, w, h;
};

bool plottable(double v) { return std::isfinite(v) && v > 0; }

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

// Where the plot area and its axes go; data points map to pixels through it.
struct Layout {
    Box plot;
    LogAxis x, y;

    explicit Layout(const LogLogChart& chart) : plot{78, 40, chart.width - 78.0 - 24, chart.height - 40.0 - 56} {
        std::vector<double> xs, ys;
        for (const ChartSeries& s : chart.series) {
            xs.insert(xs.end(), s.x.begin(), s.x.end());
            for (const auto* v : {&s.y, &s.low, &s.high}) ys.insert(ys.end(), v->begin(), v->end());
        }
        x = axisFor(xs);
        y = axisFor(ys);
    }
    // y grows downwards in pixels, upwards in data.
    double px(double v) const { return plot.x + x.unit(v) * plot.w; }
    double py(double v) const { return plot.y + (1 - y.unit(v)) * plot.h; }
};

// A 1-pixel line on a pixel row or column rather than across two (crisp in the PNG).
double crisp(double v) { return std::floor(v) + 0.5; }

void setGrey(cairo_t* cr, int v) { setColor(cr, {uint8_t(v), uint8_t(v), uint8_t(v)}); }

std::string tickLabel(double v) { return fmt::format("{:g}", v); }

void drawGrid(cairo_t* cr, const Layout& l) {
    const Box& p = l.plot;
    cairo_set_line_width(cr, 1);
    for (const Tick& t : ticksFor(l.x)) {
        const double x = crisp(l.px(t.value));
        setGrey(cr, t.labelled ? 200 : 236);
        cairo_move_to(cr, x, p.y);
        cairo_line_to(cr, x, p.y + p.h);
        cairo_stroke(cr);
        setGrey(cr, 0);
        if (t.labelled) text(cr, x, p.y + p.h + 17, tickLabel(t.value), kLabel, Anchor::Middle);
    }
    for (const Tick& t : ticksFor(l.y)) {
        const double y = crisp(l.py(t.value));
        setGrey(cr, t.labelled ? 200 : 236);
        cairo_move_to(cr, p.x, y);
        cairo_line_to(cr, p.x + p.w, y);
        cairo_stroke(cr);
        setGrey(cr, 0);
        if (t.labelled) text(cr, p.x - 6, y + 4, tickLabel(t.value), kLabel, Anchor::End);
    }
}

// Bands (high forwards, low backwards, translucent) under the lines, each point marked with a dot;
// clipped to the plot area. A point a log axis cannot show is left out.
void drawSeries(cairo_t* cr, const Layout& l, const LogLogChart& c) {
    cairo_save(cr);
    cairo_rectangle(cr, l.plot.x, l.plot.y, l.plot.w, l.plot.h);
    cairo_clip(cr);
    for (const ChartSeries& s : c.series) {
        if (s.low.size() != s.x.size() || s.high.size() != s.x.size()) continue;
        std::vector<size_t> shown;
        for (size_t i = 0; i < s.x.size(); ++i)
            if (plottable(s.x[i]) && plottable(s.low[i]) && plottable(s.high[i])) shown.push_back(i);
        if (shown.size() < 2) continue;
        for (size_t i : shown) cairo_line_to(cr, l.px(s.x[i]), l.py(s.high[i]));
        for (auto i = shown.rbegin(); i != shown.rend(); ++i) cairo_line_to(cr, l.px(s.x[*i]), l.py(s.low[*i]));
        cairo_close_path(cr);
        setColor(cr, s.color, 0.2);
        cairo_fill(cr);
    }
    cairo_set_line_width(cr, 2);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (const ChartSeries& s : c.series) {
        setColor(cr, s.color);
        std::vector<std::pair<double, double>> points;
        for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
            if (plottable(s.x[i]) && plottable(s.y[i])) points.emplace_back(l.px(s.x[i]), l.py(s.y[i]));
        for (const auto& [x, y] : points) cairo_line_to(cr, x, y);
        cairo_stroke(cr);
        for (const auto& [x, y] : points) {
            cairo_new_sub_path(cr);
            cairo_arc(cr, x, y, 2.5, 0, 2 * std::numbers::pi);
        }
        cairo_fill(cr);
    }
    cairo_restore(cr);
}

// In the plot's top-right corner: a line of each series' colour and its name.
void drawLegend(cairo_t* cr, const Layout& l, const LogLogChart& c) {
    double nameWidth = 0;
    for (const ChartSeries& s : c.series) nameWidth = std::max(nameWidth, canvas::advance(cr, s.name, kLabel));
    const double w = std::ceil(46 + nameWidth), h = 10 + kLegendRow * c.series.size();
    const double x = l.plot.x + l.plot.w - w - 10 + 0.5, y = l.plot.y + 10 + 0.5;
    cairo_rectangle(cr, x, y, w, h);
    cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
    cairo_fill_preserve(cr);
    setGrey(cr, 153);
    cairo_set_line_width(cr, 1);
    cairo_stroke(cr);
    cairo_set_line_width(cr, 2);
    for (size_t i = 0; i < c.series.size(); ++i) {
        const double rowY = std::floor(y) + 5 + kLegendRow * i + kLegendRow / 2;
        setColor(cr, c.series[i].color);
        cairo_move_to(cr, x + 8, rowY);
        cairo_line_to(cr, x + 34, rowY);
        cairo_stroke(cr);
        setGrey(cr, 0);
        text(cr, x + 40, rowY + 4, c.series[i].name, kLabel);
    }
}

void drawChart(cairo_t* cr, const LogLogChart& c) {
    const Layout l(c);
    const Box& p = l.plot;
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    drawGrid(cr, l);
    drawSeries(cr, l, c);
    setGrey(cr, 0);
    cairo_set_line_width(cr, 1);
    cairo_rectangle(cr, crisp(p.x), crisp(p.y), std::round(p.w), std::round(p.h));
    cairo_stroke(cr);
    text(cr, p.x + p.w / 2, 24, c.title, kTitle, Anchor::Middle);
    text(cr, p.x + p.w / 2, p.y + p.h + 42, c.xLabel, kAxisName, Anchor::Middle);
    text(cr, 20, p.y + p.h / 2, c.yLabel, kAxisName, Anchor::Middle, -std::numbers::pi / 2);
    drawLegend(cr, l, c);
}

}  // namespace

std::string chartSvg(const LogLogChart& c) {
    return canvas::svgOf(c.width, c.height, [&](cairo_t* cr) { drawChart(cr, c); });
}

Image chartImage(const LogLogChart& c) {
    return canvas::imageOf(c.width, c.height, [&](cairo_t* cr) { drawChart(cr, c); });
}

}  // namespace tripath
