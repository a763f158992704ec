// The PNG previews of the command line, run through the real binary (TRIPATH_BINARY): `render
// --png` and `reference --png` are exposed from the image when no exposure is given (the library's
// rule, image/exposure.h, tested on its own in test_image.cpp), and `montage` scales each row so
// that no image is blown out by another's darkness, warning about a black image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "image/exposure.h"
#include "image/image.h"
#include "shell_test.h"

namespace tripath {
namespace {

class Previews : public test::ShellTest {
protected:
    Outcome tripath(const std::string& args) const { return shell("'" TRIPATH_BINARY "' " + args); }
};

// How many of two same-sized PNGs' 8-bit values differ.
size_t differingValues(const std::string& a, const std::string& b) {
    const Image x = readImage(a), y = readImage(b);
    EXPECT_EQ(x.rgb.size(), y.rgb.size());
    size_t differing = 0;
    for (size_t i = 0; i < std::min(x.rgb.size(), y.rgb.size()); ++i) differing += x.rgb[i] != y.rgb[i];
    return differing;
}

// The preview of each command is the library's automatic one of its EXR, and not the one at
// exposure 0 (at 24 × 16 the Cornell box's 98th percentile lies on its light, about 2.5: −1 1/3 stops).
TEST_F(Previews, RenderAndReferencePngsAreExposedFromTheImage) {
    const std::string small = "--scene cornell --spp 2 --width 24 --height 16 ";
    for (const std::string command : {"render", "reference"}) {
        const Outcome o = tripath(command + " " + small + "--out '" + path(command + ".exr") + "' --png '" +
                                  path(command + ".png") + "'");
        ASSERT_EQ(o.exitCode, 0) << o.err;
        const Image exr = readExr(path(command + ".exr"));
        const float stops = autoExposureStops(exr);
        EXPECT_GT(std::abs(stops), 0.5f);  // else the test could not tell the two apart
        writePng(path("automatic.png"), exr, stops);
        writePng(path("zero.png"), exr, 0.0f);
        EXPECT_EQ(differingValues(path(command + ".png"), path("automatic.png")), 0u) << command;
        EXPECT_GT(differingValues(path(command + ".png"), path("zero.png")), 0u) << command;
    }
    // --exposure keeps meaning stops.
    ASSERT_EQ(tripath("render " + small + "--out '" + path("r.exr") + "' --png '" + path("r.png") + "' --exposure -2")
                  .exitCode,
              0);
    writePng(path("given.png"), readExr(path("r.exr")), -2.0f);
    EXPECT_EQ(differingValues(path("r.png"), path("given.png")), 0u);
}

// An 8 × 8 image of the greys value × 1, 2, 3 and 4, written as an EXR.
std::string greyExr(const std::string& file, float value) {
    Image img(8, 8);
    for (int i = 0; i < 64; ++i) std::fill_n(img.at(i % 8, i / 8), 3, value * float(1 + i % 4));  // 4 shades
    writeExr(file, img);
    return file;
}

// The share of a montage cell's pixels that are white: cell `column` of a one-row sheet of 8 × 8
// images (no labels: 2-pixel gaps).
double whiteShare(const Image& sheet, int column) {
    int white = 0;
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) white += sheet.at(column * 10 + x, y)[1] >= 1.0f;
    return white / 64.0;
}

// A dim image first (a method that barely sees the scene) does not set the row's scale, which
// would leave the others white: the brightest image's percentile is white and the dim one dark; a
// black one is named.
TEST_F(Previews, MontageRowIsNotBlownOutByADimOrBlackImage) {
    const std::string dim = greyExr(path("dim.exr"), 1e-4f), bright = greyExr(path("bright.exr"), 0.5f);
    const std::string black = greyExr(path("black.exr"), 0.0f);
    const Outcome o = tripath("montage '" + dim + "' '" + bright + "' '" + black + "' --columns 3 --percentile 0.5 " +
                              "--out '" + path("sheet.png") + "'");
    ASSERT_EQ(o.exitCode, 0) << o.err;
    EXPECT_NE(o.err.find("warning: " + black + ": the image is black"), std::string::npos) << o.err;
    EXPECT_EQ(o.err.find(dim + ": the image is black"), std::string::npos) << o.err;
    const Image sheet = readImage(path("sheet.png"));
    // Percentile 0.5 of the shades 1..4, 16 pixels each (rank round(0.5 × 63) = 32 of 64 values), is
    // shade 3: it and shade 4 are white.
    EXPECT_EQ(whiteShare(sheet, 1), 0.5);
    EXPECT_EQ(whiteShare(sheet, 0), 0.0);
    EXPECT_EQ(whiteShare(sheet, 2), 0.0);
}

// A montage for a paper: --theme light on white, and .pdf or .svg give the same page as the .png
// (two 8 × 8 cells 2 pixels apart, under 20 pixels of column labels: 20 × 30), with the labels as
// text. Catches a theme or format ignored (a dark corner, PNG bytes in a .pdf), and a page of
// another size; other extensions are refused in one line.
TEST_F(Previews, MontageWritesPngPdfOrSvgOfOneSize) {
    const std::string a = greyExr(path("a.exr"), 0.1f), b = greyExr(path("b.exr"), 0.2f);
    const std::string args = "montage '" + a + "' '" + b + "' --columns 2 --column-labels x,y --theme light --out ";
    for (const char* name : {"m.png", "m.pdf", "m.svg"}) {
        const Outcome o = tripath(args + "'" + path(name) + "'");
        ASSERT_EQ(o.exitCode, 0) << name << ": " << o.err;
    }
    const Image png = readImage(path("m.png"));
    EXPECT_EQ(png.width, 20);
    EXPECT_EQ(png.height, 30);
    EXPECT_EQ(png.at(19, 0)[0], 1.0f) << "the light theme's background is white";
    std::ifstream pdf(path("m.pdf")), svg(path("m.svg"));
    std::stringstream pdfText, svgText;
    pdfText << pdf.rdbuf();
    svgText << svg.rdbuf();
    EXPECT_EQ(pdfText.str().rfind("%PDF-", 0), 0u);
    EXPECT_NE(pdfText.str().find("/MediaBox [ 0 0 20 30 ]"), std::string::npos);
    EXPECT_NE(svgText.str().find("width=\"20px\" height=\"30px\""), std::string::npos);
    const Outcome gif = tripath(args + "'" + path("m.gif") + "'");
    EXPECT_NE(gif.exitCode, 0);
    EXPECT_NE(gif.err.find("--out must name a .png, .pdf or .svg file"), std::string::npos) << gif.err;
}

}  // namespace
}  // namespace tripath
