// Text labels drawn into an Image, in DejaVu Sans (Debian's fonts-dejavu-core, installed by
// scripts/install-deps.sh; the charts of evaluation/chart.h use the same font through Cairo).
// OpenImageIO draws the glyphs; it stays inside text.cpp.
#pragma once
#include <string>

#include "image/draw.h"

namespace tripath {

enum class Align { Left, Center, Right };

struct TextStyle {
    int size = 14;  // nominal height in pixels
    Rgb color{1, 1, 1};
    bool bold = false;
    Align align = Align::Left;
};

// Throws InputError naming the missing font package unless text can be drawn. Commands that
// end by drawing text call it first, so a missing font costs nothing but the error line.
void requireFont();

// Draws one line of UTF-8 text with its baseline at y, anchored at x by `style.align`.
void drawText(Image& img, int x, int y, const std::string& text, const TextStyle& style);
// Width in pixels that drawText would take.
int textWidth(const std::string& text, const TextStyle& style);

}  // namespace tripath
