// Whether sampling the sky by importance pays: on the built-in `sky` scene (a sun of a few texels
// over a dim sky), the per-sample variance of next-event estimation of the environment at the
// surfaces the camera sees, with directions drawn from the map (the renderer's sampler) and drawn
// uniformly over the sphere. Both estimates go through the same production connection (strategy
// (1, 2) of `connect`, unweighted: f/p); only the emitter vertex differs: one from
// sampleEmitterVertex, one built here with the uniform density 1/(4π). The variance is taken per
// surface point over kDirections directions and averaged over the points, so the comparison is of
// the estimators, not of the image's content. Counters: both variances and uniform / importance.
#include <benchmark/benchmark.h>

#include "bench_scenes.h"
#include "core/rng.h"
#include "paths/strategies.h"
#include "paths/walk.h"

namespace tripath::bench {
namespace {

constexpr int kPoints = 256, kDirections = 256;

// The variance of luminance over one point's estimates, from their sum and sum of squares.
double variance(double sum, double sumSquares, int n) { return (sumSquares - sum * sum / n) / (n - 1); }

void environmentSampling(benchmark::State& state) {
    const Scene& scene = cachedScene("sky");
    const int sky = scene.emitters().environment();
    const MisContext mis{MisHeuristic::Power, StrategySet{}, Roulette{1000}, passConstants(1.0, 0.0f)};
    WalkSettings walk;
    walk.maxDepth = 1;
    double importance = 0, uniform = 0;
    int points = 0;
    for (auto _ : state) {
        importance = uniform = 0;
        points = 0;
        Subpath camera;
        for (int i = 0; points < kPoints && i < 100 * kPoints; ++i) {
            Rng rng(7, uint64_t(StreamDomain::Test), uint64_t(i));
            const float x = rng.uniform() * float(scene.camera().width()), y = rng.uniform() * float(scene.camera().height());
            cameraSubpath(scene, Vec2{x, y}, rng, walk, WalkPdfs::None, 1.0, camera);
            if (camera.size() < 2 || camera[1].atInfinity || camera[1].delta) continue;
            double s[2] = {0, 0}, s2[2] = {0, 0};
            for (int j = 0; j < kDirections; ++j) {
                const Connection drawn = connectNextEvent(scene, rng, camera, 2, mis);
                Vertex y0;
                y0.kind = Vertex::Kind::Emitter;
                y0.atInfinity = true;
                y0.emitter = sky;
                const float a = rng.uniform();
                y0.ns = sampleUniformSphere({a, rng.uniform()});
                y0.pdfFwd = kUniformSpherePdf;
                y0.beta = Spectrum(1.0f / kUniformSpherePdf);
                const Connection flat = connect(scene, SubpathView(std::span<const Vertex>(&y0, 1)), 1, camera, 2, mis);
                const double v[2] = {luminance(drawn.unweighted), luminance(flat.unweighted)};
                for (int k = 0; k < 2; ++k) s[k] += v[k], s2[k] += v[k] * v[k];
            }
            importance += variance(s[0], s2[0], kDirections);
            uniform += variance(s[1], s2[1], kDirections);
            ++points;
        }
        benchmark::DoNotOptimize(importance + uniform);
    }
    state.counters["points"] = points;
    state.counters["variance_importance"] = importance / points;
    state.counters["variance_uniform"] = uniform / points;
    state.counters["uniform_over_importance"] = uniform / importance;
}

BENCHMARK(environmentSampling)->Name("EnvironmentSampling/sky")->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace tripath::bench
