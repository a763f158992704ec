// Vertex merging's costs: the light phase that every bidirectional pass runs first (light paths
// traced, stored and indexed), the range query, the merges a vcm sample makes, and whole vcm /
// bpm / ppm passes next to bdpt's, at 512² and at 1920×1080.
//
//   merging/light_phase/<scene>/<W>x<H>   one light phase of vcm at the default radius (2 threads):
//                                         light paths/s, stored vertices per path, store bytes per
//                                         vertex, grid bytes, and the resident set after it
//   merging/query/<scene>                 the range query at camera vertices (1 thread): queries/s,
//                                         light vertices found per query
//   merging/merges/<scene>                every merge of camera subpaths (1 thread), MIS included:
//                                         merges/s, merges per camera subpath
//   pass/<integrator>/<scene>             one whole render pass at 512² (2 threads): samples/s
#include <benchmark/benchmark.h>

#include <memory>

#include "bench_scenes.h"
#include "pass_timing.h"
#include "scenes/builtin_scenes.h"
#include "integrators/light_phase.h"
#include "integrators/render.h"

namespace tripath::bench {

namespace {

constexpr uint64_t kSeed = 1;

std::unique_ptr<Integrator> vcm() { return makeIntegrator("vcm", IntegratorSettings{}); }

// Scenes at sizes other than the cached 512²: built once, kept for the process.
const Scene& sceneAt(const std::string& name, int width, int height) {
    static std::map<std::string, std::unique_ptr<Scene>> scenes;
    auto& s = scenes[name + std::to_string(width) + "x" + std::to_string(height)];
    if (!s) s = std::make_unique<Scene>(builtinScene(name), width, height);
    return *s;
}

void runLightPhase(benchmark::State& state, const std::string& name, int width, int height) {
    const Scene& scene = sceneAt(name, width, height);
    const auto integrator = vcm();
    LightPhase phase;
    uint64_t pass = 0, paths = 0, vertices = 0;
    size_t storeBytes = 0, gridBytes = 0;
    for (auto _ : state) {
        arenaFor(2).execute([&] {
            const Pass p = phase.run(scene, *integrator->pixelSamples(), pass++, {kSeed, StreamDomain::CameraSample});
            paths += p.light->paths();
            vertices += p.light->vertices();
            storeBytes = p.light->bytes();
            gridBytes = p.search->bytes();
        });
    }
    using C = benchmark::Counter;
    state.counters["light_paths_per_s"] = C(double(paths), C::kIsRate);
    state.counters["vertices_per_path"] = double(vertices) / double(paths);
    state.counters["store_bytes_per_vertex"] = double(storeBytes) / (double(vertices) / double(state.iterations()));
    state.counters["store_MiB"] = double(storeBytes) / (1 << 20);
    state.counters["grid_MiB"] = double(gridBytes) / (1 << 20);
    state.counters["rss_MiB"] = double(procStatusKiB("VmRSS")) / 1024;
}

// A pass's light phase and 4096 camera subpaths of vcm at 512², outside the timed region.
struct MergeSetup {
    const Scene& scene;
    std::unique_ptr<Integrator> integrator = vcm();
    LightPhase phase;
    Pass pass;
    std::vector<Subpath> cameras;
    explicit MergeSetup(const std::string& name) : scene(cachedScene(name)) {
        arenaFor(2).execute([&] { pass = phase.run(scene, *integrator->pixelSamples(), 0, {kSeed, StreamDomain::CameraSample}); });
        WalkSettings walk;
        for (uint64_t i = 0; i < 4096; ++i) {
            Rng rng(kSeed, static_cast<uint64_t>(StreamDomain::CameraSample), i * 61);
            const Vec2 raster{rng.uniform() * kWidth, rng.uniform() * kHeight};
            Subpath z;
            cameraSubpath(scene, raster, rng, walk, WalkPdfs::All, pass.mis.constants.lightPaths, z);
            recordRunningSums(z.vertices, false, pass.mis);
            cameras.push_back(std::move(z));
        }
    }
};

void runQuery(benchmark::State& state, const std::string& name) {
    const MergeSetup setup(name);
    std::vector<Vec3> points;
    for (const Subpath& z : setup.cameras)
        for (size_t t = 1; t < z.size(); ++t)
            if (!z[t].delta) points.push_back(z[t].p);
    uint64_t queries = 0, found = 0;
    size_t i = 0;
    for (auto _ : state) {
        setup.pass.search->forEachWithin(points[i], [&](std::span<const Vertex>, int) { ++found; });
        ++queries;
        i = i + 1 == points.size() ? 0 : i + 1;
    }
    using C = benchmark::Counter;
    state.counters["queries_per_s"] = C(double(queries), C::kIsRate);
    state.counters["found_per_query"] = double(found) / double(queries);
}

void runMerges(benchmark::State& state, const std::string& name) {
    const MergeSetup setup(name);
    uint64_t merges = 0, subpaths = 0;
    size_t i = 0;
    double sum = 0;
    for (auto _ : state) {
        evaluateMerges(setup.scene, *setup.pass.search, setup.cameras[i], 16, setup.pass.mis,
                       [&](Strategy, const Connection& c) {
                           sum += c.weighted().x;
                           ++merges;
                       });
        ++subpaths;
        i = i + 1 == setup.cameras.size() ? 0 : i + 1;
    }
    benchmark::DoNotOptimize(sum);
    using C = benchmark::Counter;
    state.counters["merges_per_s"] = C(double(merges), C::kIsRate);
    state.counters["merges_per_subpath"] = double(merges) / double(subpaths);
}

void runPass(benchmark::State& state, const std::string& integratorName, const std::string& name) {
    timePasses(state, cachedScene(name), *makeIntegrator(integratorName, IntegratorSettings{}), 2);
}

const bool registered = [] {
    for (const char* name : {"cornell", "cornell-spheres", "smallvcm-5"}) {
        for (auto [w, h] : {std::pair{512, 512}, std::pair{1920, 1080}})
            benchmark::RegisterBenchmark(
                (std::string("merging/light_phase/") + name + "/" + std::to_string(w) + "x" + std::to_string(h)).c_str(),
                [name = std::string(name), w = w, h = h](benchmark::State& st) { runLightPhase(st, name, w, h); })
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
        benchmark::RegisterBenchmark((std::string("merging/query/") + name).c_str(),
                                     [name = std::string(name)](benchmark::State& st) { runQuery(st, name); });
        benchmark::RegisterBenchmark((std::string("merging/merges/") + name).c_str(),
                                     [name = std::string(name)](benchmark::State& st) { runMerges(st, name); });
        for (const char* integrator : {"bdpt", "vcm", "bpm", "ppm"})
            benchmark::RegisterBenchmark((std::string("pass/") + integrator + "/" + name).c_str(),
                                         [integrator = std::string(integrator), name = std::string(name)](
                                             benchmark::State& st) { runPass(st, integrator, name); })
                ->Unit(benchmark::kMillisecond)
                ->UseRealTime();
    }
    return true;
}();

}  // namespace

}  // namespace tripath::bench
