// mlt (integrators/mlt.cpp) against closed forms and against bdpt, within the error of independent
// runs: each run's chains are correlated, different seeds' are not, so Welch's test across runs
// still holds (and is what catches chains trapped in a part of path space).
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "paths/markov_chain.h"
#include "paths/primary_samples.h"
#include "scenes/builtin_scenes.h"
#include "support.h"

namespace tripath {
namespace {

using test::meanAndError;

RenderRequest metropolisRequest(int size, int spp, int maxDepth) {
    RenderRequest r = test::smallRequest();
    r.integrator = "mlt";
    r.width = r.height = size;
    r.spp = spp;
    r.maxDepth = maxDepth;
    return r;
}

// White furnace cut at path length K: a closed sphere of albedo a emitting Le reads
// Le (1 − a^K) / (1 − a) in every pixel (the Neumann series to k = K). Each quadrant of the image
// is held to it over 8 runs: the quadrants catch chains that spread their light unevenly, the
// whole image a normalisation that misses the strategies' count k + 1 or the image's P.
TEST(Metropolis, FurnaceReadsTheSeriesCutAtMaxDepthInEveryQuadrant) {
    for (const float albedo : {0.5f, 0.9f}) {
        const int K = 12;
        const Scene scene(furnaceScene(albedo, 1.0f), 8, 8);
        const double expected = (1.0 - std::pow(double(albedo), K)) / (1.0 - albedo);
        RenderRequest r = metropolisRequest(8, 256, K);
        r.metropolis.chains = 16;  // 4 steps per chain per pass
        const test::BlockRuns runs = test::blockRuns(scene, r, 8, 1, test::blockGrid(8, 8, 2, 2), average);
        for (size_t q = 0; q < runs.size(); ++q) {
            const auto m = meanAndError(runs[q]);
            EXPECT_NEAR(m.mean, expected, 4 * m.stderr_) << "albedo " << albedo << ", quadrant " << q;
            EXPECT_LT(m.stderr_, 0.03 * expected) << "albedo " << albedo << ": too noisy for the test to mean anything";
        }
    }
}

// mlt against bdpt block by block (4 × 4 blocks of a 32 × 32 image, 16 runs each, unless a test
// says otherwise), Welch's test Holm-corrected over the scene's blocks: a target, a normalisation
// or a chain that is wrong anywhere in the image fails here.
void expectAgreementWithBdpt(const std::string& name, int spp, int64_t bootstrap, int runs = 16, int grid = 4) {
    const Scene scene(builtinScene(name), 32, 32);
    RenderRequest r = metropolisRequest(32, spp, 8);
    r.metropolis.chains = 64;  // 16 steps per chain per pass
    r.metropolis.bootstrap = bootstrap;
    const std::vector<test::Block> blocks = test::blockGrid(32, 32, grid, grid);
    const test::BlockRuns mlt = test::blockRuns(scene, r, runs, 100, blocks);
    r.integrator = "bdpt";
    r.spp = 16;
    const test::BlockRuns bdpt = test::blockRuns(scene, r, runs, 200, blocks);
    test::BlockAgreement agreement;
    agreement.compare(mlt, bdpt, name + " (bootstrap " + std::to_string(bootstrap) + "): mlt against bdpt");
    agreement.expectNoBias();
}

// veach-mis over 32 runs: mlt's run-to-run error in a block holds a floor that more steps do not
// lower (each run's b_k, fixed after its bootstrap), and at 16 runs one block stood above the noise
// ceiling (test::kNoiseCeiling). The caustic in quadrants over 32 runs: bdpt finds the light through
// the ball by rare connections, and a 4 × 4 block's run-to-run error reached 40 % of its mean.
TEST(Metropolis, AgreesWithBdptOnCornell) { expectAgreementWithBdpt("cornell", 16, 100000); }
TEST(Metropolis, AgreesWithBdptOnVeachMis) { expectAgreementWithBdpt("veach-mis", 16, 100000, 32); }
TEST(Metropolis, AgreesWithBdptOnTheCaustic) { expectAgreementWithBdpt("caustic", 16, 100000, 32, 2); }

// No start-up bias, where it would be largest: one step per chain (as many chains as pixels, one
// pass), so that every contribution comes from a chain's first step after its start. A chain
// starts at a bootstrap sample drawn in proportion to its luminance L_i, and its length's
// contributions are scaled by the bootstrap's mean b = Σ L_i / N: for any function h of the
// state after any number of steps t,
//     E[b · h(x_t)] = E[(1/N) Σ_i L_i (K^t h)(x_i)] = ∫ L (K^t h) = b_true · π(K^t h) = b_true · π(h),
// π being the chain's stationary density L / b_true, which its kernel K keeps; so the image of
// one step per chain, averaged over 96 runs, agrees block by block with bdpt's. Catches chains
// started at a bootstrap sample drawn uniformly (the classic start-up bias: after one step the
// chains still over-weigh the dim paths a uniform draw favours), checked by making that change.
TEST(Metropolis, OneStepPerChainHasNoStartUpBias) {
    const Scene scene(builtinScene("cornell"), 16, 16);
    RenderRequest r = metropolisRequest(16, 1, 8);
    r.metropolis.chains = 16 * 16;  // one step per chain in the one pass
    r.metropolis.bootstrap = 2000;
    const std::vector<test::Block> blocks = test::blockGrid(16, 16, 2, 2);
    const test::BlockRuns mlt = test::blockRuns(scene, r, 96, 100, blocks);
    r.integrator = "bdpt";
    r.spp = 16;
    const test::BlockRuns bdpt = test::blockRuns(scene, r, 16, 300, blocks);
    test::BlockAgreement agreement;
    agreement.compare(mlt, bdpt, "cornell, one step per chain: mlt against bdpt");
    agreement.expectNoBias();
}

// The images of a render are the same for any number of threads (ranks: test_distributed.cpp),
// and another seed gives another image.
TEST(Metropolis, SameSeedSameImageWhateverTheThreadCount) {
    const Scene scene(builtinScene("cornell-spheres"), 40, 24);
    RenderRequest r = metropolisRequest(40, 3, 8);
    r.height = 24;
    r.threads = 1;
    const Image one = test::renderScene(scene, r).image();
    for (const int threads : {2, 3}) {
        r.threads = threads;
        EXPECT_EQ(one.rgb, test::renderScene(scene, r).image().rgb) << threads << " threads";
    }
    r.seed = 2;
    EXPECT_NE(one.rgb, test::renderScene(scene, r).image().rgb);
}

// A chain's state survives its bytes: a chain written and read back takes the same next steps
// as the original. Catches a coordinate, its last move or the large step's number left out of
// the state (lazy moves read them all).
TEST(Metropolis, AChainReadBackFromItsBytesStepsAsTheOriginal) {
    const Scene scene(builtinScene("cornell"), 16, 16);
    const MultiplexedTarget target{&scene, multiplexedMisContext(MisHeuristic::Power, 256), 256};
    TargetPaths paths;
    MarkovChain a(3);
    Rng fresh(7, uint64_t(StreamDomain::Test), 0);
    a.start(target, fresh, paths);
    auto noSplat = [](const PathSample&, float) {};
    for (uint64_t i = 1; i <= 50; ++i) {
        Rng rng(7, uint64_t(StreamDomain::Test), i);
        a.step(target, 0.3f, rng, paths, noSplat);
    }
    std::string bytes;
    a.write(bytes);
    MarkovChain b(3);
    std::string_view in = bytes;
    b.read(in);
    EXPECT_TRUE(in.empty());
    for (uint64_t i = 51; i <= 150; ++i) {
        Rng ra(7, uint64_t(StreamDomain::Test), i), rb = ra;
        EXPECT_EQ(a.step(target, 0.3f, ra, paths, noSplat), b.step(target, 0.3f, rb, paths, noSplat)) << "step " << i;
        ASSERT_EQ(a.current().value, b.current().value) << "step " << i;
    }
    std::string_view cut = std::string_view(bytes).substr(0, bytes.size() - 1);
    EXPECT_THROW(MarkovChain(3).read(cut), InputError);
}

}  // namespace
}  // namespace tripath
