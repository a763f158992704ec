// The PNG rendering of a chart: the same layout as the SVG, drawn with draw.h and text.h.
#include <algorithm>

#include "image/chart_layout.h"
#include "image/text.h"

namespace tripath {

namespace {

using chart::Layout;

Rgb colorOf(const ChartSeries& s) { return fromSrgb(s.color[0], s.color[1], s.color[2]); }

void drawGrid(Image& img, const Layout& l) {
    const Region& p = l.plot;
    const Rgb major = fromSrgb(200, 200, 200), minor = fromSrgb(236, 236, 236), ink{0, 0, 0};
    const TextStyle label{Layout::fontSize, ink, false, Align::Center};
    for (const chart::Tick& t : l.xTicks) {
        const double x = chart::toPixel(l, t.value, 1).x;
        drawLine(img, {x, double(p.y)}, {x, double(p.y + p.h)}, t.labelled ? major : minor, 1);
        if (t.labelled) drawText(img, static_cast<int>(x), p.y + p.h + 17, chart::tickLabel(t.value), label);
    }
    TextStyle right = label;
    right.align = Align::Right;
    for (const chart::Tick& t : l.yTicks) {
        const double y = chart::toPixel(l, 1, t.value).y;
        drawLine(img, {double(p.x), y}, {double(p.x + p.w), y}, t.labelled ? major : minor, 1);
        if (t.labelled) drawText(img, p.x - 6, static_cast<int>(y) + 4, chart::tickLabel(t.value), right);
    }
}

// Lines and bands are drawn onto a copy of the plot area so that nothing spills into the margins.
void drawSeries(Image& img, const Layout& l, const LogLogChart& c) {
    Image plot = img;
    for (const ChartSeries& s : c.series) fillPolygon(plot, chart::bandOutline(l, s), colorOf(s), 0.2f);
    for (const ChartSeries& s : c.series) {
        const auto pts = chart::linePoints(l, s);
        drawPolyline(plot, pts, colorOf(s), 2);
        for (const Point& p : pts) drawLine(plot, p, p, colorOf(s), 5);
    }
    const Region& r = l.plot;
    for (int y = r.y; y < r.y + r.h; ++y)
        std::copy(plot.at(r.x, y), plot.at(r.x, y) + 3 * r.w, img.at(r.x, y));
}

void drawLegend(Image& img, const Layout& l, const LogLogChart& c) {
    const Region& r = l.legend;
    fillRect(img, r, {1, 1, 1}, 0.85f);
    strokeRect(img, r, fromSrgb(153, 153, 153));
    for (size_t i = 0; i < c.series.size(); ++i) {
        const int y = r.y + 5 + Layout::legendRow * static_cast<int>(i) + Layout::legendRow / 2;
        drawLine(img, {r.x + 8.0, y + 0.5}, {r.x + 34.0, y + 0.5}, colorOf(c.series[i]), 2);
        drawText(img, r.x + 40, y + 5, c.series[i].name, {Layout::fontSize, {0, 0, 0}});
    }
}

}  // namespace

Image chartImage(const LogLogChart& c) {
    const Layout l = chart::layout(c);
    const Region& p = l.plot;
    Image img(c.width, c.height);
    fillRect(img, {0, 0, c.width, c.height}, {1, 1, 1});
    const Rgb ink{0, 0, 0};
    drawText(img, p.x + p.w / 2, 24, c.title, {Layout::titleSize, ink, true, Align::Center});
    drawGrid(img, l);
    drawSeries(img, l, c);
    strokeRect(img, p, ink);
    drawText(img, p.x + p.w / 2, p.y + p.h + 42, c.xLabel, {Layout::fontSize + 1, ink, false, Align::Center});
    drawTextUp(img, 15, p.y + p.h / 2, c.yLabel, {Layout::fontSize + 1, ink});
    drawLegend(img, l, c);
    return img;
}

}  // namespace tripath
