// Whole passes of a method timed by Google Benchmark: what integrator_pass/ (integrator_passes.cpp)
// and merging/pass/ (merging.cpp) share.
#pragma once
#include <benchmark/benchmark.h>

#include "bench_scenes.h"
#include "integrators/render.h"

namespace tripath::bench {

// One pass of `integrator` on `scene` (a cached scene: kWidth × kHeight) per iteration, each with
// the next pass index, on `threads` threads; samples_per_s counts its camera samples.
inline void timePasses(benchmark::State& state, const Scene& scene, const Integrator& integrator, int threads) {
    RenderSettings rs;
    rs.spp = 1;
    rs.threads = threads;
    uint64_t samples = 0;
    for (auto _ : state) {
        const RenderResult r = render(scene, integrator, rs);
        benchmark::DoNotOptimize(r.film.width());
        samples += uint64_t(kWidth) * kHeight;
        ++rs.firstPass;
    }
    using C = benchmark::Counter;
    state.counters["samples_per_s"] = C(double(samples), C::kIsRate);
}

}  // namespace tripath::bench
