// A comparison sheet: images side by side, each labelled above, with one region outlined on
// every image and shown magnified below it, so that noise the full view hides can be compared.
#pragma once
#include <string>
#include <vector>

#include "evaluation/sheet.h"

namespace tripath {

struct Panel {
    Image image;         // linear radiance; every panel has the same size
    std::string title;   // first label line, in bold (e.g. the method)
    std::string detail;  // second label line (e.g. "1024 spp  relMSE 0.012")
};

struct SheetStyle {
    Theme theme = kDarkTheme;
    bool labels = true;  // false: no title lines, for a figure captioned elsewhere
};

// Small images are magnified (by a whole factor, nearest neighbour) to at least `minWidth`
// pixels per panel so that the labels fit; the inset fills the panel's width (or its height, for
// a tall region). Throws InputError if the panels differ in size or the region is not inside them.
Sheet sideBySide(const std::vector<Panel>& panels, const Region& inset, const SheetStyle& style = {},
                 int minWidth = 256);

// The region of `image`, magnified by the whole factor (at least 1) that brings its longer side
// closest to `size` pixels without passing it: a crop to print on its own, its pixels as blocks.
Image magnifiedCrop(const Image& image, const Region& r, int size = 512);

}  // namespace tripath
