// Welch's t-test per block with Holm's correction (evaluation/bias.h): Student's t tail against closed
// forms, the test and the correction on hand-worked numbers, a bias map that finds one offset
// block among noise and nothing in pure noise, and on renders: light tracing flagged where it
// cannot see (the caustic behind `sds`'s pane), unbiased integrators passed on `cornell`.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "scenes/builtin_scenes.h"
#include "evaluation/bias.h"
#include "support.h"

namespace tripath {
namespace {

// ν = 1 is Cauchy: P(|T| ≥ t) = 1 − (2/π) atan t; ν = 2: 1 − t/√(t² + 2); large ν: the normal's
// 2(1 − Φ(t)); ν = 10 at t = 2.228: the textbook 5 % point.
TEST(Bias, StudentTailMatchesClosedForms) {
    for (double t : {0.1, 0.7, 1.5, 4.0, 30.0}) {
        EXPECT_NEAR(studentTwoSidedP(t, 1), 1 - 2 / std::numbers::pi * std::atan(t), 1e-12) << t;
        EXPECT_NEAR(studentTwoSidedP(-t, 2), 1 - t / std::sqrt(t * t + 2), 1e-12) << t;
        EXPECT_NEAR(studentTwoSidedP(t, 1e7), std::erfc(t / std::sqrt(2.0)), 1e-6) << t;
    }
    EXPECT_NEAR(studentTwoSidedP(2.228, 10), 0.05, 2e-4);
    EXPECT_EQ(studentTwoSidedP(0, 5), 1.0);
}

// a = 1..4, b = 2, 4, …, 10: means 2.5 and 6, variances 5/3 and 10;
// t = −3.5 / √(5/12 + 2) = −2.2514, ν = (29/12)² / ((5/12)²/3 + 2²/4) = 5.8403 / 1.05787 = 5.5208.
TEST(Bias, WelchOnHandWorkedSamples) {
    const WelchTest w = welchTest({1, 2, 3, 4}, {2, 4, 6, 8, 10});
    EXPECT_NEAR(w.t, -2.2514, 1e-4);
    EXPECT_NEAR(w.dof, 5.5208, 1e-4);
    EXPECT_NEAR(w.p, studentTwoSidedP(2.2514, 5.5208), 1e-4);
    EXPECT_EQ(welchTest({0, 0, 0}, {0, 0}).p, 1.0);  // two black blocks agree
    EXPECT_EQ(welchTest({0, 0, 0}, {1, 1}).p, 0.0);  // a deterministic difference is bias
}

// Holm at α = 0.05 over p = {0.01, 0.04, 0.03, 0.005}: 0.005 ≤ 0.05/4 and 0.01 ≤ 0.05/3 pass,
// 0.03 > 0.05/2 stops it, so 0.04 is not significant either (though 0.04 < 0.05).
TEST(Bias, HolmStepsDownAndStops) {
    EXPECT_EQ(holmSignificant({0.01, 0.04, 0.03, 0.005}, 0.05), (std::vector<bool>{true, false, false, true}));
    EXPECT_EQ(holmSignificant({0.2, 0.5}, 0.05), (std::vector<bool>{false, false}));
}

// Noise images: the same mean everywhere finds nothing; a block whose mean is off by 10 % of the
// noise in one set of runs (3σ of the block mean over 16 runs of 64 pixels) is the one found.
TEST(Bias, AMapFindsTheOffsetBlockAndNothingElse) {
    std::mt19937 rng(5);
    std::normal_distribution<float> noise(1.0f, 0.5f);
    auto runs = [&](float offset) {
        std::vector<Image> out;
        for (int r = 0; r < 16; ++r) {
            Image img(32, 32);
            for (int y = 0; y < 32; ++y)
                for (int x = 0; x < 32; ++x)
                    for (int c = 0; c < 3; ++c) img.rgb[3 * (y * 32 + x) + c] = noise(rng) + (x >= 8 && x < 16 && y < 8 ? offset : 0);
            out.push_back(img);
        }
        return out;
    };
    const auto reference = runs(0);
    EXPECT_EQ(biasMap(runs(0), reference, 8).count(), 0);
    const BiasMap offset = biasMap(runs(0.2f), reference, 8);
    EXPECT_EQ(offset.count(), 1);
    EXPECT_TRUE(offset.biased[1]);
    EXPECT_EQ(offset.blocksX, 4);
}

// `runs` independent 32×32 renders (seeds 40, 41, …).
std::vector<Image> renders(const std::string& scene, const std::string& integrator, int runs, int spp) {
    RenderRequest r = test::smallRequest();
    r.integrator = integrator;
    r.width = r.height = 32;
    r.spp = spp;
    r.maxDepth = 8;
    return test::renderRuns(Scene(builtinScene(scene), r.width, r.height), r, runs, 40);
}

// Light tracing cannot see the caustic behind `sds`'s pane (its only path ends through the pane
// at the pinhole): the map must flag it against path tracing. On `cornell`, pt, lt and bdpt are
// unbiased: nothing may be flagged.
TEST(Bias, FlagsLightTracingOnSdsAndPassesUnbiasedMethodsOnCornell) {
    const BiasMap sds = biasMap(renders("sds", "lt", 8, 16), renders("sds", "pt", 8, 16), 8);
    EXPECT_GT(sds.count(), 0);
    const auto reference = renders("cornell", "bdpt", 8, 8);
    EXPECT_EQ(biasMap(renders("cornell", "pt", 8, 8), reference, 8).count(), 0);
    EXPECT_EQ(biasMap(renders("cornell", "lt", 8, 8), reference, 8).count(), 0);
}

}  // namespace
}  // namespace tripath
