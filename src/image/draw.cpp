#include "image/draw.h"

#include <algorithm>
#include <cmath>

namespace tripath {

namespace {

float srgbDecode(uint8_t v) {
    const float c = v / 255.0f;
    return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// Distance from p to the segment ab.
double segmentDistance(Point p, Point a, Point b) {
    const double dx = b.x - a.x, dy = b.y - a.y, len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2 : 0;
    t = std::clamp(t, 0.0, 1.0);
    return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

}  // namespace

Rgb fromSrgb(uint8_t r, uint8_t g, uint8_t b) { return {srgbDecode(r), srgbDecode(g), srgbDecode(b)}; }

void blendPixel(Image& img, int x, int y, Rgb c, float coverage) {
    if (x < 0 || y < 0 || x >= img.width || y >= img.height || !(coverage > 0)) return;
    const float a = std::min(coverage, 1.0f);
    float* p = img.at(x, y);
    p[0] += a * (c.r - p[0]);
    p[1] += a * (c.g - p[1]);
    p[2] += a * (c.b - p[2]);
}

void fillRect(Image& img, Region r, Rgb c, float alpha) {
    for (int y = std::max(0, r.y); y < std::min(img.height, r.y + r.h); ++y)
        for (int x = std::max(0, r.x); x < std::min(img.width, r.x + r.w); ++x) blendPixel(img, x, y, c, alpha);
}

void strokeRect(Image& img, Region r, Rgb c, int t) {
    fillRect(img, {r.x, r.y, r.w, t}, c);
    fillRect(img, {r.x, r.y + r.h - t, r.w, t}, c);
    fillRect(img, {r.x, r.y + t, t, r.h - 2 * t}, c);
    fillRect(img, {r.x + r.w - t, r.y + t, t, r.h - 2 * t}, c);
}

void drawLine(Image& img, Point a, Point b, Rgb c, double width, float alpha) {
    // Coverage falls off linearly over the last pixel of each edge: cheap anti-aliasing that keeps
    // thin chart lines from looking like staircases.
    const double half = width / 2;
    const int x0 = static_cast<int>(std::floor(std::min(a.x, b.x) - half - 1));
    const int x1 = static_cast<int>(std::ceil(std::max(a.x, b.x) + half + 1));
    const int y0 = static_cast<int>(std::floor(std::min(a.y, b.y) - half - 1));
    const int y1 = static_cast<int>(std::ceil(std::max(a.y, b.y) + half + 1));
    for (int y = std::max(0, y0); y <= std::min(img.height - 1, y1); ++y)
        for (int x = std::max(0, x0); x <= std::min(img.width - 1, x1); ++x) {
            const double d = segmentDistance({x + 0.5, y + 0.5}, a, b);
            const double coverage = std::clamp(half + 0.5 - d, 0.0, 1.0);
            if (coverage > 0) blendPixel(img, x, y, c, static_cast<float>(coverage) * alpha);
        }
}

void drawPolyline(Image& img, const std::vector<Point>& points, Rgb c, double width, float alpha) {
    for (size_t i = 1; i < points.size(); ++i) drawLine(img, points[i - 1], points[i], c, width, alpha);
    if (points.size() == 1) drawLine(img, points[0], points[0], c, width, alpha);
}

void fillPolygon(Image& img, const std::vector<Point>& points, Rgb c, float alpha) {
    const size_t n = points.size();
    if (n < 3) return;
    for (int y = 0; y < img.height; ++y) {
        // Crossings of the scanline through the pixel centres with every edge.
        const double sy = y + 0.5;
        std::vector<double> xs;
        for (size_t i = 0; i < n; ++i) {
            const Point p = points[i], q = points[(i + 1) % n];
            if ((p.y <= sy) == (q.y <= sy)) continue;
            xs.push_back(p.x + (sy - p.y) * (q.x - p.x) / (q.y - p.y));
        }
        std::sort(xs.begin(), xs.end());
        for (size_t i = 0; i + 1 < xs.size(); i += 2) {
            const int from = static_cast<int>(std::ceil(xs[i] - 0.5));
            const int to = static_cast<int>(std::floor(xs[i + 1] - 0.5));
            for (int x = std::max(0, from); x <= std::min(img.width - 1, to); ++x) blendPixel(img, x, y, c, alpha);
        }
    }
}

void paste(Image& dst, const Image& src, int x, int y, int scale) {
    for (int sy = 0; sy < src.height * scale; ++sy)
        for (int sx = 0; sx < src.width * scale; ++sx) {
            const int dx = x + sx, dy = y + sy;
            if (dx < 0 || dy < 0 || dx >= dst.width || dy >= dst.height) continue;
            const float* s = src.at(sx / scale, sy / scale);
            std::copy(s, s + 3, dst.at(dx, dy));
        }
}

}  // namespace tripath
