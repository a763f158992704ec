// replaySample (integrators/render.h), behind `tripath render --replay PASS,PIXEL`: a sample
// rendered again gives the contributions the render gave. Under pt every contribution of a camera
// sample lands in its own pixel, so a one-pass render's pixel must equal the replayed sum, bit for
// bit (the same additions in the same order). The pass is not the first, so a replay that drew
// from another pass's stream, or jittered the raster differently, fails.
#include <gtest/gtest.h>

#include "scenes/builtin_scenes.h"
#include "integrators/render.h"

namespace tripath {
namespace {

class SumSink final : public ContributionSink {
public:
    void add(Strategy, const Connection& c) override {
        const Spectrum w = c.weighted();
        sum[0] += w.x, sum[1] += w.y, sum[2] += w.z;
    }
    double sum[3] = {0, 0, 0};
};

TEST(Replay, ASampleRendersAgainAsTheFilmSawIt) {
    const Scene scene(builtinScene("cornell-spheres"), 16, 16);
    IntegratorSettings is;
    is.walk.maxDepth = 8;
    const auto pt = makeIntegrator("pt", is);
    RenderSettings rs;
    rs.spp = 1;
    rs.firstPass = 5;
    rs.seed = 9;
    rs.threads = 2;
    const Image image = render(scene, *pt, rs).image();
    int lit = 0;  // pixels with light, so that the equality is not 0 == 0
    for (int pixel : {0, 37, 130, 255}) {
        SumSink sink;
        replaySample(scene, *pt, rs, 5, pixel, sink);
        lit += sink.sum[0] > 0;
        for (int c = 0; c < 3; ++c) EXPECT_EQ(float(sink.sum[c]), image.rgb[3 * pixel + c]) << "pixel " << pixel << " channel " << c;
    }
    EXPECT_GE(lit, 3);
}

}  // namespace
}  // namespace tripath
