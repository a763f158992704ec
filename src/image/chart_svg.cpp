// The SVG rendering of a chart: plain SVG 1.1 text, viewable in any browser without scripts.
#include <fmt/format.h>

#include "image/chart_layout.h"
#include "image/markup.h"

namespace tripath {

namespace {

using chart::Layout;

std::string escape(const std::string& s) { return escapeMarkup(s); }

std::string hex(const std::array<uint8_t, 3>& c) { return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]); }

std::string pointList(const std::vector<Point>& pts) {
    std::string s;
    for (const Point& p : pts) s += fmt::format("{:.1f},{:.1f} ", p.x, p.y);
    return s;
}

std::string grid(const Layout& l) {
    std::string s;
    const Region& p = l.plot;
    for (const chart::Tick& t : l.xTicks) {
        const double x = chart::toPixel(l, t.value, 1).x;
        s += fmt::format(R"(<line x1="{0:.1f}" y1="{1}" x2="{0:.1f}" y2="{2}" stroke="{3}"/>)"
                         "\n",
                         x, p.y, p.y + p.h, t.labelled ? "#c8c8c8" : "#ececec");
        if (t.labelled)
            s += fmt::format(R"(<text x="{:.1f}" y="{}" text-anchor="middle" font-size="{}">{}</text>)"
                             "\n",
                             x, p.y + p.h + 17, Layout::fontSize, chart::tickLabel(t.value));
    }
    for (const chart::Tick& t : l.yTicks) {
        const double y = chart::toPixel(l, 1, t.value).y;
        s += fmt::format(R"(<line x1="{1}" y1="{0:.1f}" x2="{2}" y2="{0:.1f}" stroke="{3}"/>)"
                         "\n",
                         y, p.x, p.x + p.w, t.labelled ? "#c8c8c8" : "#ececec");
        if (t.labelled)
            s += fmt::format(R"(<text x="{}" y="{:.1f}" text-anchor="end" font-size="{}">{}</text>)"
                             "\n",
                             p.x - 6, y + 4, Layout::fontSize, chart::tickLabel(t.value));
    }
    return s;
}

std::string series(const Layout& l, const LogLogChart& c) {
    std::string s = R"~(<g clip-path="url(#plot)">)~"
                    "\n";
    for (const ChartSeries& cs : c.series) {
        const auto band = chart::bandOutline(l, cs);
        if (band.size() >= 3)
            s += fmt::format(R"(<polygon points="{}" fill="{}" fill-opacity="0.2" stroke="none"/>)"
                             "\n",
                             pointList(band), hex(cs.color));
    }
    for (const ChartSeries& cs : c.series) {
        const auto line = chart::linePoints(l, cs);
        s += fmt::format(R"(<polyline points="{}" fill="none" stroke="{}" stroke-width="2"/>)"
                         "\n",
                         pointList(line), hex(cs.color));
        for (const Point& p : line)
            s += fmt::format(R"(<circle cx="{:.1f}" cy="{:.1f}" r="2.5" fill="{}"/>)", p.x, p.y, hex(cs.color));
        s += "\n";
    }
    return s + "</g>\n";
}

std::string legend(const Layout& l, const LogLogChart& c) {
    const Region& r = l.legend;
    std::string s = fmt::format(
        R"(<rect x="{}" y="{}" width="{}" height="{}" fill="white" fill-opacity="0.85" stroke="#999"/>)"
        "\n",
        r.x, r.y, r.w, r.h);
    for (size_t i = 0; i < c.series.size(); ++i) {
        const int y = r.y + 5 + Layout::legendRow * static_cast<int>(i) + Layout::legendRow / 2;
        s += fmt::format(R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="2"/>)", r.x + 8, y,
                         r.x + 34, y, hex(c.series[i].color));
        s += fmt::format(R"(<text x="{}" y="{}" font-size="{}">{}</text>)"
                         "\n",
                         r.x + 40, y + 4, Layout::fontSize, escape(c.series[i].name));
    }
    return s;
}

}  // namespace

std::string chartSvg(const LogLogChart& c) {
    const Layout l = chart::layout(c);
    const Region& p = l.plot;
    std::string s = fmt::format(
        R"(<svg xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}" )"
        R"(font-family="DejaVu Sans, Verdana, sans-serif">)"
        "\n"
        R"(<defs><clipPath id="plot"><rect x="{2}" y="{3}" width="{4}" height="{5}"/></clipPath></defs>)"
        "\n"
        R"(<rect width="{0}" height="{1}" fill="white"/>)"
        "\n",
        c.width, c.height, p.x, p.y, p.w, p.h);
    s += fmt::format(R"(<text x="{}" y="24" text-anchor="middle" font-size="{}" font-weight="bold">{}</text>)"
                     "\n",
                     p.x + p.w / 2, Layout::titleSize, escape(c.title));
    s += grid(l);
    s += series(l, c);
    s += fmt::format(R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="black"/>)"
                     "\n",
                     p.x, p.y, p.w, p.h);
    s += fmt::format(R"(<text x="{}" y="{}" text-anchor="middle" font-size="{}">{}</text>)"
                     "\n",
                     p.x + p.w / 2, p.y + p.h + 42, Layout::fontSize + 1, escape(c.xLabel));
    s += fmt::format(R"~(<text transform="translate(20,{}) rotate(-90)" text-anchor="middle" font-size="{}">{}</text>)~"
                     "\n",
                     p.y + p.h / 2, Layout::fontSize + 1, escape(c.yLabel));
    return s + legend(l, c) + "</svg>\n";
}

}  // namespace tripath
