// What the chart and the sheets share to draw with Cairo: colours, one line of text anchored at a
// point, and one drawing routine written to an SVG, a PDF or an Image (for PNG) alike, so that a
// figure's formats show the same thing by construction. Used by evaluation's .cpp files only
// (Cairo is a private dependency of this layer: only its context type is named here).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>

#include "image/image.h"

typedef struct _cairo cairo_t;  // as cairo.h declares it

namespace tripath::canvas {

using Srgb8 = std::array<uint8_t, 3>;  // as "#rrggbb"

void setColor(cairo_t* cr, const Srgb8& c, double alpha = 1);

enum class Anchor { Start, Middle, End };

struct Font {
    double size = 13;
    bool bold = false;
};

// Width of one line of text in DejaVu Sans, with that font selected for drawing it.
double advance(cairo_t* cr, const std::string& s, const Font& font);
// The same without a drawing under way.
double textWidth(const std::string& s, const Font& font);

// One line of text with its baseline at y, anchored at x; turned by `angle` (radians, clockwise)
// about (x, y).
void text(cairo_t* cr, double x, double y, const std::string& s, const Font& font, Anchor anchor = Anchor::Start,
          double angle = 0);

using Drawing = std::function<void(cairo_t*)>;

// The drawing on a width × height page: SVG text (in pixels), PDF bytes (one pixel one point),
// or an Image whose pixels writePng encodes back into the bytes Cairo drew.
std::string svgOf(int width, int height, const Drawing& draw);
std::string pdfOf(int width, int height, const Drawing& draw);
Image imageOf(int width, int height, const Drawing& draw);

}  // namespace tripath::canvas
