// The three integrators against analytic answers and against each other, within statistical
// error estimated from independent runs (fixed seeds, so the outcome is reproducible).
#include <gtest/gtest.h>

#include <utility>

#include "geometry/builtin_scenes.h"
#include "geometry/vec.h"
#include "support.h"

namespace tripath {
namespace {

using test::meanAndError;
using test::RenderRequest;

const char* kIntegrators[] = {"pt", "lt", "bdpt"};

double imageMean(const Image& img) { return test::blockMean(img, 0, 0, img.width, img.height); }

// White furnace: a closed sphere of albedo a emitting Le has radiance Le / (1 − a) everywhere.
void expectFurnace(float albedo) {
    const SceneDesc desc = furnaceScene(albedo, 1.0f);
    const double expected = 1.0 / (1.0 - albedo);
    for (const char* integrator : kIntegrators) {
        std::vector<double> runs;
        for (uint64_t seed = 1; seed <= 8; ++seed) {
            RenderRequest r;
            r.integrator = integrator;
            r.width = r.height = 8;
            r.spp = 32;
            r.seed = seed;
            r.maxDepth = 1000;  // a^1000 is negligible: the whole Neumann series
            const RenderResult res = test::renderDesc(desc, r);
            EXPECT_EQ(res.droppedSamples, 0u);
            runs.push_back(imageMean(res.image()));
        }
        const auto m = meanAndError(runs);
        EXPECT_NEAR(m.mean, expected, 4 * m.stderr_) << integrator << " a=" << albedo;
        EXPECT_LT(m.stderr_, 0.02 * expected) << integrator << ": too noisy for the test to mean anything";
    }
}

TEST(Furnace, AlbedoHalf) { expectFurnace(0.5f); }
TEST(Furnace, AlbedoNineTenths) { expectFurnace(0.9f); }

// Luminance of each 8×8 block, for R independent runs of one integrator.
std::vector<std::vector<double>> blockRuns(const SceneDesc& desc, const char* integrator, int runs, int spp) {
    std::vector<std::vector<double>> blocks;
    for (int run = 0; run < runs; ++run) {
        RenderRequest r;
        r.integrator = integrator;
        r.width = r.height = 32;
        r.spp = spp;
        r.seed = 100 + run;
        r.maxDepth = 8;
        const Image img = test::renderDesc(desc, r).image();
        for (int b = 0; b < 16; ++b) {
            if (run == 0) blocks.emplace_back();
            const int bx = (b % 4) * 8, by = (b / 4) * 8;
            blocks[b].push_back(0.2126 * test::blockMean(img, bx, by, 8, 8, 0) + 0.7152 * test::blockMean(img, bx, by, 8, 8, 1) +
                                0.0722 * test::blockMean(img, bx, by, 8, 8, 2));
        }
    }
    return blocks;
}

// Every pair of integrators agrees on every block. 48 comparisons per scene with 16 runs each
// (15 degrees of freedom): |Δ| < 5σ keeps the family-wise false-alarm rate near 1%.
// `ltRows` limits the light tracer to the top rows of blocks: see Agreement.VeachMis.
void expectAgreement(const SceneDesc& desc, const std::string& scene, int spp, int ltRows = 4) {
    std::vector<std::vector<std::vector<double>>> all;
    for (const char* integrator : kIntegrators) all.push_back(blockRuns(desc, integrator, 16, spp));
    for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b)
            for (int block = 0; block < 16; ++block) {
                if ((a == 1 || b == 1) && block / 4 >= ltRows) continue;
                const auto ma = meanAndError(all[a][block]), mb = meanAndError(all[b][block]);
                const double sigma = std::hypot(ma.stderr_, mb.stderr_);
                EXPECT_LT(std::abs(ma.mean - mb.mean), 5 * sigma + 1e-6)
                    << scene << " block " << block << ": " << kIntegrators[a] << " " << ma.mean << " ± " << ma.stderr_
                    << " vs " << kIntegrators[b] << " " << mb.mean << " ± " << mb.stderr_;
            }
}

TEST(Agreement, Cornell) { expectAgreement(builtinScene("cornell"), "cornell", 8); }
TEST(Agreement, CornellSmall) { expectAgreement(builtinScene("cornell-small"), "cornell-small", 8); }
// The bottom row of veach-mis is the sharpest plate (GGX alpha 0.01) seen directly: a light
// tracer must hit its narrow lobe toward the pinhole by chance, so its estimate there is
// heavy-tailed (at 4096 spp two seeds still differ by 2×) and the run-to-run error bars are
// meaningless at test budgets. That is light tracing's known failure, shown in the README;
// here LT is held to the other three rows, and PT and BDPT to all of them.
TEST(Agreement, VeachMis) { expectAgreement(builtinScene("veach-mis"), "veach-mis", 8, 3); }

// Shading normals: light subpaths use the adjoint BSDF (Veach §5.3), so all three agree on a
// smooth-normal Lambertian sphere (the tessellated Cornell variant) as on flat geometry.
TEST(Agreement, SmoothShadingNormals) { expectAgreement(cornellTessellated(100), "smooth sphere", 8); }

// Each BDPT strategy alone, unweighted, estimates every path of its length (in the Cornell box
// all strategies can sample all paths), so it agrees with the MIS-combined image of that length.
TEST(Bdpt, EachStrategyUnweightedAgreesWithItsPathLength) {
    const SceneDesc desc = builtinScene("cornell");
    std::map<std::pair<int, int>, std::vector<double>> diffs;
    for (uint64_t seed = 1; seed <= 16; ++seed) {
        RenderRequest r;
        r.integrator = "bdpt";
        r.width = r.height = 16;
        r.spp = 8;
        r.seed = seed;
        r.maxDepth = 3;
        r.layers.depthImages = 3;
        r.layers.strategyLength = 3;
        const RenderResult res = test::renderDesc(desc, r);
        for (const auto& [s, t] : res.film.strategies()) {
            const double strategy = imageMean(res.film.strategyImage(s, t, false, res.passes));
            const double total = imageMean(res.film.depthImage(s + t - 1, res.passes));
            diffs[{s, t}].push_back(strategy - total);
        }
    }
    ASSERT_EQ(diffs.size(), 9u);  // k = 1: 2 strategies, k = 2: 3, k = 3: 4
    for (const auto& [st, d] : diffs) {
        const auto m = meanAndError(d);
        EXPECT_LT(std::abs(m.mean), 4.5 * m.stderr_ + 1e-6) << "s=" << st.first << " t=" << st.second;
    }
}

TEST(Film, DepthImagesAddUpToTheFullImage) {
    for (const char* integrator : kIntegrators) {
        RenderRequest r;
        r.integrator = integrator;
        r.maxDepth = 6;
        r.layers.depthImages = 6;
        const RenderResult res = test::renderDesc(builtinScene("cornell-spheres"), r);
        const Image full = res.image();
        Image sum(full.width, full.height);
        for (int k = 1; k <= 6; ++k) {
            const Image d = res.film.depthImage(k, res.passes);
            for (size_t i = 0; i < sum.rgb.size(); ++i) sum.rgb[i] += d.rgb[i];
        }
        for (size_t i = 0; i < sum.rgb.size(); ++i)
            ASSERT_NEAR(sum.rgb[i], full.rgb[i], 1e-5f * std::abs(full.rgb[i]) + 1e-7f) << integrator;
        EXPECT_GT(imageMean(full), 0.0);
    }
}

// The image of `desc` with its BVH built on `buildThreads` threads, rendered on `renderThreads`.
Image renderBuiltWith(const SceneDesc& desc, test::RenderRequest r, int buildThreads, int renderThreads) {
    const auto scene = test::buildWithThreads(desc, r.width, r.height, buildThreads);
    r.threads = renderThreads;
    return test::renderScene(*scene, r).image();
}

// The same seed and sample count give the same image whatever the numbers of threads that built
// the BVH and that rendered. `contact` has coincident faces (box faces inside walls and floor): a
// ray meets two triangles at the same distance, and which one Embree reports depends on the
// order its traversal finds them in, i.e. on the BVH's shape. Embree builds `cornell` and
// `contact` (36 and 48 triangles) on one thread whatever it is given; cornell-spheres and the
// tessellated contact are large enough for its parallel build. Those faces are hidden inside
// the boxes, where few paths of an image go: Determinism.SameHitsWhateverTheThreadsThatBuiltTheBvh
// (test_scene.cpp) compares the hits themselves.
TEST(Determinism, SameSeedSameImageWhateverTheThreadCount) {
    const std::pair<const char*, SceneDesc> scenes[] = {
        {"cornell", builtinScene("cornell")},
        {"contact", builtinScene("contact")},
        {"contact tessellated", test::tessellated(builtinScene("contact"), 10)},
        {"cornell-spheres", builtinScene("cornell-spheres")}};
    // (build threads, render threads): the reference, then the others.
    const std::pair<int, int> reference{1, 1};
    const std::pair<int, int> others[] = {{2, 1}, {1, 2}, {2, 2}, {4, 3}};
    for (const auto& [name, desc] : scenes)
        for (const char* integrator : kIntegrators) {
            RenderRequest r;
            r.integrator = integrator;
            r.width = 40;  // not a multiple of the tile size
            r.height = 24;
            r.spp = 3;
            r.seed = 42;
            const Image one = renderBuiltWith(desc, r, reference.first, reference.second);
            for (const auto& [build, render] : others)
                EXPECT_EQ(one.rgb, renderBuiltWith(desc, r, build, render).rgb)
                    << name << " " << integrator << ": BVH built on " << build << " threads, rendered on "
                    << render;
            r.seed = 43;  // the comparison can fail: another seed gives another image
            EXPECT_NE(one.rgb, renderBuiltWith(desc, r, 2, 2).rgb) << name << " " << integrator;
        }
}

TEST(Robustness, NoNanOrInfOnAnyBuiltinScene) {
    for (const BuiltinInfo& info : builtinScenes())
        for (const char* integrator : kIntegrators) {
            RenderRequest r;
            r.integrator = integrator;
            r.spp = 2;
            const RenderResult res = test::renderDesc(builtinScene(info.name), r);
            EXPECT_EQ(res.droppedSamples, 0u) << info.name << " " << integrator;
        }
}

}  // namespace
}  // namespace tripath
