// auto (integrators/auto.cpp): unbiased against bdpt whatever plans it chooses, the same render
// for any thread count, and each pass's plan chosen from the passes before it alone.
#include <gtest/gtest.h>

#include <array>
#include <map>
#include <string>

#include "integrators/pass_plan.h"
#include "integrators/plan_choice.h"
#include "integrators/tile_passes.h"
#include "scenes/builtin_scenes.h"
#include "support.h"

namespace tripath {
namespace {

RenderRequest autoRequest(int spp) {
    RenderRequest r = test::smallRequest();
    r.integrator = "auto";
    r.width = r.height = 24;
    r.spp = spp;
    return r;
}

// The plans a render chose, as its EXR says them.
std::vector<std::pair<uint64_t, std::string>> plansOf(const RenderResult& r) { return r.plans.stretches; }

// auto against bdpt, block by block (Welch, Holm, the noise ceiling), on a diffuse box, a caustic
// under an area light (where merges and light tracing pay), and the textured sky, at 40 passes:
// every render chooses at 4, 8, 16 and 32 passes. A plan that weighed its own passes, or passes
// of different plans combined with weights that depend on them, would bias the image; so would
// a plan chosen although it cannot sample a path (pt's on the caustic's SDS light).
TEST(Auto, AgreesWithBdptWhateverItChooses) {
    for (const char* name : {"cornell", "caustic", "sky"}) {
        const Scene scene(builtinScene(name), 24, 24);
        RenderRequest a = autoRequest(40), b = a;
        b.integrator = "bdpt";
        b.spp = 160;  // bdpt's noise on the caustic, below the ceiling
        const std::vector<test::Block> blocks = test::blockGrid(24, 24, 2, 2);
        // The sky's sun makes auto's runs heavy-tailed in the lower right quadrant: 12 runs hold
        // its standard error at the noise ceiling (measured: 30 % of a run's value there), 24 under.
        const int runs = std::string(name) == "sky" ? 24 : 12;
        test::BlockAgreement agreement;
        agreement.compare(test::blockRuns(scene, a, runs, 700, blocks), test::blockRuns(scene, b, runs, 800, blocks),
                          std::string("auto against bdpt on ") + name);
        agreement.expectNoBias();
    }
}

// `passes` passes of the 32×32 cornell box whose four 16×16 tiles run `plans` (N_L of the first),
// as auto's passes render a choice (tile_passes.h), with `seed`; measuring, or weighed as they
// come.
Image renderTilePlans(const Scene& scene, const std::vector<PassPlan>& plans, int passes, uint64_t seed,
                      bool measures = true) {
    IntegratorSettings is;
    is.walk = {6, 2};
    const auto method = makePlannedPasses(unionOf(plans), is, measures);
    RenderSettings settings;
    settings.seed = seed;
    settings.threads = 2;
    PassRenderer renderer(scene, settings);
    RenderResult result{.film = Film(scene.camera().width(), scene.camera().height())};
    for (int pass = 0; pass < passes; ++pass) {
        renderer.run(*method, uint64_t(pass), result, nullptr, plans);
        if ((pass + 1) % kPassesPerBlock == 0 || pass + 1 == passes) renderer.endBlock(result.film);
    }
    return result.film.image(passes);
}

// Tiles that run different classes side by side, each set able to sample every path of the
// diffuse box: light tracing alone (no camera walk), path tracing alone, light tracing with
// merges, path tracing with connections. Each tile's image agrees with bdpt's (Welch per tile,
// Holm). A splat is weighed by the classes of the tile it lands in: weighed by those of the tile
// whose sample traced it, light tracing's splats into the path-tracing tile count twice there
// (checked: that change fails it), and the light tracer's tile, without them, loses its light.
TEST(Auto, TilesOfDifferentPlansEachAgreeWithBdpt) {
    const Scene scene(builtinScene("cornell"), 32, 32);
    const double n = 32 * 32;
    const std::vector<PassPlan> plans = {{n, false, true, false, false},
                                         {n, false, false, false, true},
                                         {n, false, true, true, false},
                                         {n, true, false, false, true}};
    const std::vector<test::Block> tiles = test::blockGrid(32, 32, 2, 2);
    test::BlockRuns runs(tiles.size());
    for (int run = 0; run < 12; ++run) {
        const Image image = renderTilePlans(scene, plans, 16, 900 + uint64_t(run));
        for (size_t k = 0; k < tiles.size(); ++k) runs[k].push_back(test::blockMean(image, tiles[k], luminance));
    }
    RenderRequest b = test::smallRequest();
    b.integrator = "bdpt";
    b.width = b.height = 32;
    b.maxDepth = 6;
    b.spp = 32;
    test::BlockAgreement agreement;
    agreement.compare(runs, test::blockRuns(scene, b, 12, 1000, tiles), "tiles of four plans against bdpt");
    agreement.expectNoBias();
}

// A pass that does not measure weighs each contribution as it comes, from the walk's running
// sums, where a pass that measures weighs it by its technique sums and the classes of the tile it
// lands in. Where every tile runs one plan the two weights are the same balance heuristic: from
// the same streams, the same image but for rounding, pixel by pixel, for plans with light
// tracing (whose splats land anywhere), connections and merges. Fails if the unmeasured passes
// weigh by another heuristic (the power heuristic fails both plans of more than one class,
// checked), or if a plan's strategies keep the camera walk's when it drops them (the light tracer's
// plan fails, checked).
TEST(Auto, APassOfOnePlanWeighsAsItsMeasuringPass) {
    const Scene scene(builtinScene("cornell"), 32, 32);
    const double n = 32 * 32;
    for (const PassPlan& plan : {PassPlan{n, false, true, false, true}, PassPlan{n / 4, true, true, true, true},
                                 PassPlan{4 * n, false, true, false, false}}) {
        const std::vector<PassPlan> plans(4, plan);
        const Image measured = renderTilePlans(scene, plans, 2, 31);
        const Image weighed = renderTilePlans(scene, plans, 2, 31, false);
        double largest = 0;
        for (size_t i = 0; i < measured.rgb.size(); ++i) {
            const double difference = std::abs(double(measured.rgb[i]) - weighed.rgb[i]);
            largest = std::max(largest, difference / (std::abs(measured.rgb[i]) + 1e-3));
        }
        EXPECT_LT(largest, 1e-3) << classesName(plan.classes());
    }
}

// The same image and the same plans on 1, 2 and 3 threads: the moments the plans are chosen from
// are exact sums, gathered in the film's order. Fails if a choice read a sum added in thread order.
TEST(Auto, TheSameRenderWhateverTheThreadCount) {
    const Scene scene(builtinScene("cornell-spheres"), 40, 24);
    RenderRequest r = autoRequest(20);
    r.width = 40;
    r.threads = 1;
    const RenderResult one = test::renderScene(scene, r);
    EXPECT_GE(plansOf(one).size(), 4u);
    for (int threads : {2, 3}) {
        r.threads = threads;
        const RenderResult other = test::renderScene(scene, r);
        EXPECT_EQ(one.image().rgb, other.image().rgb) << threads << " threads";
        EXPECT_EQ(plansOf(one), plansOf(other)) << threads << " threads";
    }
}

// The channels of auto's classes (plan_report.h) give each pixel its tile's classes: 16-pixel tiles,
// three to a row, on a 40×20 image whose last column and row of tiles are cut short. Fails with the
// tiles read column by column, a row counted at the image's width, or a class's bit mixed up.
TEST(Auto, ItsClassChannelsGiveEachPixelItsTilesClasses) {
    PlanReport plans;
    plans.tileSize = 16;
    plans.tilesAcross = 3;
    plans.tiles = {kCameraWalkClass, kTraceClass, kCameraWalkClass | kMergeClass,
                   kConnectClass | kTraceClass, kCameraWalkClass | kConnectClass | kTraceClass | kMergeClass, kMergeClass};
    const std::vector<ExrChannel> channels = classChannels(plans, 40, 20);
    ASSERT_EQ(channels.size(), 4u);
    std::map<std::string, const ExrChannel*> byName;
    for (const ExrChannel& c : channels) byName[c.name] = &c;
    // (x, y) and the classes on there: pt, connect, trace, merge.
    const std::vector<std::pair<std::pair<int, int>, std::array<float, 4>>> expected{
        {{0, 0}, {1, 0, 0, 0}},   {{15, 15}, {1, 0, 0, 0}}, {{16, 0}, {0, 0, 1, 0}},  {{39, 0}, {1, 0, 0, 1}},
        {{32, 15}, {1, 0, 0, 1}}, {{0, 16}, {0, 1, 1, 0}},  {{15, 19}, {0, 1, 1, 0}}, {{16, 16}, {1, 1, 1, 1}},
        {{31, 19}, {1, 1, 1, 1}}, {{39, 19}, {0, 0, 0, 1}}};
    const std::array<const char*, 4> names{"auto.pt", "auto.connect", "auto.trace", "auto.merge"};
    for (const auto& [at, classes] : expected)
        for (size_t k = 0; k < names.size(); ++k) {
            ASSERT_TRUE(byName.count(names[k])) << names[k];
            EXPECT_EQ(byName[names[k]]->values[size_t(at.second * 40 + at.first)], classes[k])
                << names[k] << " at " << at.first << "," << at.second;
        }
    EXPECT_TRUE(classChannels(PlanReport{}, 40, 20).empty());
}

// The plans of a render's first 12 passes do not depend on how many passes come after them.
// Fails if a plan were chosen from passes after it, or from the budget.
TEST(Auto, APassesPlanDependsOnThePassesBeforeItAlone) {
    const Scene scene(builtinScene("cornell"), 24, 24);
    const RenderResult longer = test::renderScene(scene, autoRequest(40));
    const RenderResult shorter = test::renderScene(scene, autoRequest(12));
    auto before = [](std::vector<std::pair<uint64_t, std::string>> plans, uint64_t passes) {
        std::erase_if(plans, [&](const auto& p) { return p.first >= passes; });
        return plans;
    };
    EXPECT_EQ(before(plansOf(longer), 12), plansOf(shorter));
    EXPECT_EQ(plansOf(shorter).size(), 3u);  // passes 0, 4 and 8 on
}

}  // namespace
}  // namespace tripath
