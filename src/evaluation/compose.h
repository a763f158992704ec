// A comparison sheet: images side by side, each labelled above, with one region outlined on
// every image and shown magnified below it, so that noise the full view hides can be compared.
#pragma once
#include <string>
#include <vector>

#include "image/draw.h"

namespace tripath {

struct Panel {
    Image image;         // linear radiance; every panel has the same size
    std::string title;   // first label line, in bold (e.g. the method)
    std::string detail;  // second label line (e.g. "1024 spp  relMSE 0.012")
};

// Small images are magnified (by a whole factor, nearest neighbour) to at least `minWidth`
// pixels per panel so that the labels fit. Throws InputError if the panels differ in size or the
// region is not inside them.
Image sideBySide(const std::vector<Panel>& panels, const Region& inset, int minWidth = 256);

// Images one under the other, left-aligned, on the sheets' dark background.
Image stackRows(const std::vector<Image>& rows);

}  // namespace tripath
