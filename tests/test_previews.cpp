// The PNG previews of the command line, run through the real binary (TRIPATH_BINARY): `render
// --png` and `reference --png` are exposed from the image when no exposure is given (the library's
// rule, image/exposure.h, tested on its own in test_image.cpp).
#include <gtest/gtest.h>

#include <algorithm>
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
// exposure 0 (the Cornell box's 98th percentile is about 0.3: +1 2/3 stops).
TEST_F(Previews, RenderAndReferencePngsAreExposedFromTheImage) {
    const std::string small = "--scene cornell --spp 2 --width 24 --height 16 ";
    for (const std::string command : {"render", "reference"}) {
        const Outcome o = tripath(command + " " + small + "--out '" + path(command + ".exr") + "' --png '" +
                                  path(command + ".png") + "'");
        ASSERT_EQ(o.exitCode, 0) << o.err;
        const Image exr = readExr(path(command + ".exr"));
        const float stops = autoExposureStops(exr);
        EXPECT_GT(stops, 0.5f);  // else the test could not tell the two apart
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

}  // namespace
}  // namespace tripath
