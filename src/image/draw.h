// Rectangles and magnified and shrunk copies in a linear RGB Image: enough for labelled comparison sheets and
// colour bars. Colours are linear, so a colour picked as sRGB goes through fromSrgb first
// (writePng encodes back to sRGB).
#pragma once
#include <cstdint>

#include "image/image.h"

namespace tripath {

struct Rgb {
    float r = 0, g = 0, b = 0;
};

// A rectangle of pixels: top-left corner and size.
struct Region {
    int x = 0, y = 0, w = 0, h = 0;
};

// An 8-bit sRGB colour (as in CSS "#rrggbb") as the linear value that writePng turns back into it.
Rgb fromSrgb(uint8_t r, uint8_t g, uint8_t b);

// Pixels outside the image are left out.
void fillRect(Image& img, Region r, Rgb c);
void strokeRect(Image& img, Region r, Rgb c, int thickness = 1);
// Copies `src` into `dst` with its top-left corner at (x, y), each pixel repeated scale x scale
// times (nearest neighbour: magnified noise stays noise, not blur).
void paste(Image& dst, const Image& src, int x, int y, int scale = 1);
// `img` with each pixel repeated scale × scale times.
Image magnified(const Image& img, int scale);
// Each factor × factor block of `img` averaged into one pixel (a box filter; a partial block at the
// right or bottom edge is left out): a thumbnail, or a figure small enough to keep.
Image shrink(const Image& img, int factor);

}  // namespace tripath
