// Simple 2-D drawing into a linear RGB Image: rectangles, anti-aliased lines, filled polygons and
// magnified copies. Enough for charts and labelled comparison sheets; colours are linear, so a
// colour picked as sRGB goes through fromSrgb first (writePng encodes back to sRGB).
#pragma once
#include <cstdint>
#include <vector>

#include "image/image.h"

namespace tripath {

struct Rgb {
    float r = 0, g = 0, b = 0;
};

// A rectangle of pixels: top-left corner and size.
struct Region {
    int x = 0, y = 0, w = 0, h = 0;
};

struct Point {
    double x = 0, y = 0;
};

// An 8-bit sRGB colour (as in CSS "#rrggbb") as the linear value that writePng turns back into it.
Rgb fromSrgb(uint8_t r, uint8_t g, uint8_t b);

// Blends `c` over one pixel with the given coverage in [0, 1]; pixels outside the image are ignored.
void blendPixel(Image& img, int x, int y, Rgb c, float coverage);
void fillRect(Image& img, Region r, Rgb c, float alpha = 1);
void strokeRect(Image& img, Region r, Rgb c, int thickness = 1);
// A line of the given width (pixels) with anti-aliased edges; coordinates are pixel-continuous
// (the centre of pixel (x, y) is (x + 0.5, y + 0.5)).
void drawLine(Image& img, Point a, Point b, Rgb c, double width, float alpha = 1);
void drawPolyline(Image& img, const std::vector<Point>& points, Rgb c, double width, float alpha = 1);
// Fills a simple polygon (even-odd rule, sampled at pixel centres), blended with `alpha`.
void fillPolygon(Image& img, const std::vector<Point>& points, Rgb c, float alpha = 1);
// Copies `src` into `dst` with its top-left corner at (x, y), each pixel repeated scale x scale
// times (nearest neighbour: magnified noise stays noise, not blur).
void paste(Image& dst, const Image& src, int x, int y, int scale = 1);

}  // namespace tripath
