// The ceiling: raw Embree throughput through the renderer's own ray API (Scene::intersect and
// Scene::unoccluded) with incoherent random rays, on the scenes the whole samples run on, in the
// same harness shape (TBB arena of 1 or 2 workers, wall-clock time). Whatever a sample does besides
// casting rays shows up as the gap between these rays/s and the whole-sample rays/s.
//
// Rays: origins uniform in the scene's bounding box; closest-hit rays go in uniform directions,
// shadow rays join two such points (free points: no surface offset). Path rays are not quite like
// these (they start on surfaces, and their lengths follow the scene), so the ceiling is a
// reference, not a bound; the README compares against the mix of the two kinds a sample casts.
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <benchmark/benchmark.h>

#include "bench_scenes.h"
#include "core/rng.h"
#include "core/sampling.h"

namespace tripath::bench {

namespace {

enum class RayKind { Intersect, Occluded };

constexpr int kRaysPerIteration = 16384;
constexpr int kChunk = 256;

struct Worker {
    uint64_t rays = 0, hits = 0;
};

void runCeiling(benchmark::State& state, const std::string& key, RayKind kind, int threads) {
    const Scene& scene = cachedScene(key);
    const Vec3 lo = scene.boundsMin(), extent = scene.boundsMax() - scene.boundsMin();
    tbb::enumerable_thread_specific<Worker> workers;
    tbb::task_arena& arena = arenaFor(threads);
    uint64_t iteration = 0;

    for (auto _ : state) {
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<int>(0, kRaysPerIteration, kChunk), [&](const tbb::blocked_range<int>& r) {
                Worker& w = workers.local();
                // One stream per chunk, drawn from sequentially: a handful of PCG steps per ray.
                Rng rng(1, static_cast<uint64_t>(StreamDomain::Test), iteration * kRaysPerIteration + r.begin());
                auto point = [&] {
                    const float a = rng.uniform(), b = rng.uniform(), c = rng.uniform();
                    return lo + extent * Vec3(a, b, c);
                };
                for (int i = r.begin(); i < r.end(); ++i) {
                    const Vec3 origin = point();
                    if (kind == RayKind::Intersect) {
                        const float u = rng.uniform(), v = rng.uniform();
                        w.hits += scene.intersect(origin, sampleUniformSphere({u, v})).has_value();
                    } else {
                        const Vec3 target = point();
                        w.hits += !scene.unoccluded(origin, Vec3(0.0f), target, Vec3(0.0f));
                    }
                }
                w.rays += static_cast<uint64_t>(r.size());
            });
        });
        ++iteration;
    }

    uint64_t rays = 0, hits = 0;
    for (const Worker& w : workers) {
        rays += w.rays;
        hits += w.hits;
    }
    using C = benchmark::Counter;
    state.counters["rays_per_s"] = C(static_cast<double>(rays), C::kIsRate);
    state.counters["hit_fraction"] = rays ? double(hits) / double(rays) : 0.0;
    state.counters["threads"] = threads;
    state.counters["workers"] = static_cast<double>(workers.size());
}

const bool registered = [] {
    for (const auto& [label, key] : sampleScenes())
        for (RayKind kind : {RayKind::Intersect, RayKind::Occluded})
            for (int threads : {1, 2}) {
                const std::string name = std::string("ceiling/") + (kind == RayKind::Intersect ? "intersect" : "occluded") +
                                         "/" + label + "/threads:" + std::to_string(threads);
                benchmark::RegisterBenchmark(name.c_str(),
                                             [key, kind, threads](benchmark::State& st) { runCeiling(st, key, kind, threads); })
                    ->UseRealTime()
                    ->MeasureProcessCPUTime()
                    ->Unit(benchmark::kMillisecond);
            }
    return true;
}();

}  // namespace

}  // namespace tripath::bench
