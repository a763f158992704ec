// Whole passes of a method timed by Google Benchmark: what integrator_pass/ (integrator_passes.cpp),
// merging/pass/ (merging.cpp) and auto_pass/ (auto_passes.cpp) share.
#pragma once
#include <benchmark/benchmark.h>

#include <string>
#include <utility>

#include "bench_scenes.h"
#include "integrators/render.h"

namespace tripath::bench {

// One pass of `integrator` on `scene` (a cached scene: kWidth × kHeight) per iteration, each with
// the next pass index, on `threads` threads, drawing from `sampler`; samples_per_s counts its
// camera samples.
inline void timePasses(benchmark::State& state, const Scene& scene, const Integrator& integrator, int threads,
                       SamplerKind sampler = SamplerKind::Independent) {
    RenderSettings rs;
    rs.spp = 1;
    rs.threads = threads;
    rs.sampler = sampler;
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

// Registers `run` (a function of the benchmark's state) as `name`: whole passes, in milliseconds
// of the wall clock, with the process's CPU time beside it.
template <class Run>
void registerPasses(const std::string& name, Run run) {
    benchmark::RegisterBenchmark(name.c_str(), std::move(run))
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->MeasureProcessCPUTime();
}

}  // namespace tripath::bench
