// auto's passes beside vcm's, all through the render loop's pass renderer (tile_passes.h): what
// measuring the candidates costs, and what a pass that does not measure saves.
//
//   auto_pass/vcm/<scene>         one pass of vcm
//   auto_pass/measuring/<scene>   one pass of auto's first plan (every class, one light path per
//                                 pixel) that measures every candidate's moments in every tile
//   auto_pass/planned/<scene>     the same plan weighed by its technique sums, measuring nothing
//   auto_pass/weighed/<scene>     the same plan weighed as it comes, from the walk's running sums:
//                                 auto's passes between measuring blocks where every tile runs
//                                 one plan
//
// 512², max-depth 8, one thread, on `cornell` and `caustic`; samples/s, CPU time beside the wall
// clock. measuring / vcm is the cost of measuring; weighed / vcm, what a pass of auto's that does
// not measure costs against the fixed method of the same strategies.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "bench_scenes.h"
#include "integrators/pass_plan.h"
#include "integrators/plan_choice.h"
#include "integrators/plan_moments.h"
#include "integrators/tile_passes.h"
#include "pass_timing.h"

namespace tripath::bench {

namespace {

constexpr int kDepth = 8;  // the depth bench/README.md states its targets at

enum class Variant { Vcm, Measuring, Planned, Weighed };

void runPasses(benchmark::State& state, const std::string& key, Variant variant) {
    const Scene& scene = cachedScene(key);
    const double pixels = double(kWidth) * kHeight;
    IntegratorSettings settings;
    settings.walk.maxDepth = kDepth;
    settings.walk.rrDepth = defaultRouletteDepth("vcm");
    const PassPlan plan{pixels, true, true, true, true};
    const std::unique_ptr<Integrator> vcm = makeIntegrator("vcm", settings);
    const std::unique_ptr<PixelSampleIntegrator> planned = makePlannedPasses(plan, settings, variant != Variant::Weighed);
    const PixelSampleIntegrator& method = variant == Variant::Vcm ? *vcm->pixelSamples() : *planned;
    const size_t tiles = size_t((kWidth + kTileSize - 1) / kTileSize) * size_t((kHeight + kTileSize - 1) / kTileSize);
    const std::vector<PassPlan> tilePlans = variant == Variant::Vcm ? std::vector<PassPlan>{}
                                                                     : std::vector<PassPlan>(tiles, plan);

    const std::vector<PassPlan> candidates = candidatePlans(pixels);
    PlanMoments moments(kWidth, kHeight, kTileSize, candidates.size());
    std::vector<TechniqueSums> factors;
    for (const PassPlan& c : candidates) factors.push_back(c.factors(pixels));
    moments.setFactors(std::move(factors));
    const size_t everything = size_t(std::find(candidates.begin(), candidates.end(), plan) - candidates.begin());
    moments.setRunning(std::vector<size_t>(tiles, everything));

    RenderSettings rs;
    rs.threads = 1;
    PassRenderer renderer(scene, rs);
    uint64_t pass = 0, samples = 0;
    for (auto _ : state) {
        RenderResult result{.film = Film(kWidth, kHeight)};
        renderer.run(method, pass++, result, variant == Variant::Measuring ? &moments : nullptr, tilePlans);
        renderer.endBlock(result.film);
        if (variant == Variant::Measuring) moments.endBlock();
        benchmark::DoNotOptimize(result.film.width());
        samples += uint64_t(kWidth) * kHeight;
    }
    using C = benchmark::Counter;
    state.counters["samples_per_s"] = C(double(samples), C::kIsRate);
}

const bool registered = [] {
    for (const char* scene : {"cornell", "caustic"})
        for (const auto& [name, variant] : {std::pair{"vcm", Variant::Vcm}, {"measuring", Variant::Measuring},
                                            {"planned", Variant::Planned}, {"weighed", Variant::Weighed}})
            registerPasses("auto_pass/" + std::string(name) + "/" + scene,
                           [scene = std::string(scene), variant = variant](benchmark::State& st) {
                               runPasses(st, scene, variant);
                           });
    return true;
}();

}  // namespace

}  // namespace tripath::bench
