// replaySample (integrators/render.h), behind `tripath render --replay PASS,PIXEL`: a sample
// rendered again gives the contributions the render gave. Under pt every contribution of a camera
// sample lands in its own pixel, so a one-pass render's pixel must equal the replayed sum, bit for
// bit (the same additions in the same order). Under vcm the sample also reads the pass's light
// paths, which the replay must trace again as the render did. The pass is not the first, so a
// replay that drew from another pass's stream, or jittered the raster differently, fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

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
    for (int pixel = 0; pixel < 256; ++pixel) {
        SumSink sink;
        replaySample(scene, *pt->pixelSamples(), rs, 5, pixel, sink);
        lit += sink.sum[0] > 0;
        for (int c = 0; c < 3; ++c) EXPECT_EQ(float(sink.sum[c]), image.rgb[3 * pixel + c]) << "pixel " << pixel << " channel " << c;
    }
    EXPECT_GE(lit, 64);
}

// Every weighted contribution of the samples replayed, per strategy and pixel, as the render's
// film files them: a connection to the sensor (t = 1) in the pixel it lands in, as one of the
// pass's N_L estimates there; any other in the sample's own pixel.
class LayerSink final : public ContributionSink {
public:
    using Layers = std::map<Strategy, std::vector<double>>;
    LayerSink(Layers& layers, const Camera& camera, double lightPaths)
        : layers_(layers), camera_(camera), share_(1 / lightPaths) {}
    void setPixel(int pixel) { pixel_ = pixel; }
    void add(Strategy st, const Connection& c) override {
        const auto it = layers_.find(st);
        ASSERT_NE(it, layers_.end()) << "a contribution of strategy " << st.s << "," << st.t << " that has no layer";
        const Spectrum w = c.weighted();
        const bool splat = !st.merge && st.t == 1;
        const int pixel = splat ? std::min(int(c.raster->y), camera_.height() - 1) * camera_.width() +
                                      std::min(int(c.raster->x), camera_.width() - 1)
                                : pixel_;
        for (int ch = 0; ch < 3; ++ch) it->second[3 * pixel + ch] += splat ? w[ch] * share_ : w[ch];
    }

private:
    Layers& layers_;
    const Camera& camera_;
    const double share_;
    int pixel_ = 0;
};

// Under vcm a pass first traces and stores its light paths; every camera sample connects to them
// (s ≥ 2) and merges with their vertices, and sample p also splats light path p's connections to
// the sensor (t = 1). The film's strategy layers (--strategy-images) keep the strategies apart. A
// layer of t ≥ 2 or of a merge holds, at each pixel, that pixel's own sample's contributions alone,
// added in its order: the replayed sum must equal it bit for bit. A layer of t = 1 holds the splats
// of every sample that landed in the pixel, so every sample of the pass is replayed and their
// splats summed where they land (to rounding: the render scales each in float). Catches a replay
// whose light phase traces another pass's paths, or draws from another seed's or domain's
// streams, or is skipped: then the connections with s ≥ 2, the merges and the splats all change.
TEST(Replay, AVcmSampleRendersAgainWithTheLightPathsOfItsPass) {
    constexpr int kSize = 16;
    const Scene scene(builtinScene("cornell-spheres"), kSize, kSize);
    IntegratorSettings is;
    is.walk.maxDepth = 6;
    is.merge.radiusFactor = 0.05f;  // large, so that merges happen at this size
    const auto vcm = makeIntegrator("vcm", is);
    RenderSettings rs;
    rs.spp = 1;
    rs.firstPass = 5;
    rs.seed = 9;
    rs.threads = 2;
    rs.layers.strategyLength = is.walk.maxDepth;  // every strategy of every path
    const RenderResult result = render(scene, *vcm, rs);

    LayerSink::Layers replayed;
    for (const Strategy& st : result.film.strategies()) replayed[st].assign(3 * kSize * kSize, 0.0);
    LayerSink sink(replayed, scene.camera(), vcm->pixelSamples()->lightPaths(scene));
    for (int pixel = 0; pixel < kSize * kSize; ++pixel) {
        sink.setPixel(pixel);
        replaySample(scene, *vcm->pixelSamples(), rs, 5, pixel, sink);
    }
    // Values lit by merges, by connections with s ≥ 2 and by splats (489, 1437 and 936 here).
    int merged = 0, connected = 0, splatted = 0;
    for (const auto& [st, sums] : replayed) {
        const Image layer = result.film.strategyImage(st, true, 1);
        const bool splats = !st.merge && st.t == 1;
        int lit = 0;
        for (size_t i = 0; i < sums.size(); ++i) {
            const std::string what = std::to_string(st.s) + "," + std::to_string(st.t) + (st.merge ? " merge" : "") +
                                     ", value " + std::to_string(i);
            if (splats) EXPECT_NEAR(sums[i], layer.rgb[i], 1e-5 * sums[i] + 1e-9) << what;
            else EXPECT_EQ(float(sums[i]), layer.rgb[i]) << what;
            lit += sums[i] > 0;
        }
        if (st.merge) merged += lit;
        else if (splats) splatted += lit;
        else if (st.s >= 2) connected += lit;
    }
    for (const int lit : {merged, connected, splatted}) EXPECT_GE(lit, 200) << "too few values to mean anything";
}

}  // namespace
}  // namespace tripath
