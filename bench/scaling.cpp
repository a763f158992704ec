// How cost grows: pt samples/s against scene size (cornellTessellated, 36 to 1M triangles), pt
// and bdpt against max-depth on cornell, and the resident memory a scene of each size takes.
// All throughput here runs on 2 threads, like the whole-sample targets.
#include <benchmark/benchmark.h>

#include "bench_scenes.h"
#include "sample_harness.h"

namespace tripath::bench {

namespace {

constexpr size_t kSizes[] = {36, 1'000, 10'000, 100'000, 1'000'000};

std::string sizeLabel(size_t n) { return "tess-" + std::to_string(n); }

// One iteration, no timing of interest: the counters carry what the cache measured when it built
// the scene (first use in this process). run.sh also runs this alone in a fresh process, where
// the peak is the scene's and nothing else's.
void runMemory(benchmark::State& state, size_t triangles) {
    const BuildStats& s = buildStats(tessellatedKey(triangles));
    for (auto _ : state) benchmark::DoNotOptimize(&s);
    const double mib = 1.0 / 1024.0;
    state.counters["triangles"] = static_cast<double>(s.triangles);
    state.counters["build_s"] = s.seconds;
    state.counters["rss_before_MiB"] = s.rssBeforeKiB * mib;
    state.counters["rss_after_MiB"] = s.rssAfterKiB * mib;
    state.counters["scene_resident_MiB"] = (s.rssAfterKiB - s.rssBeforeKiB) * mib;
    state.counters["peak_MiB"] = s.peakKiB * mib;  // process high-water mark, reset before the build
    state.counters["peak_reset"] = s.peakWasReset ? 1 : 0;
    state.counters["rss_now_MiB"] = procStatusKiB("VmRSS") * mib;
    state.counters["hwm_now_MiB"] = procStatusKiB("VmHWM") * mib;
}

const bool registered = [] {
    for (size_t n : kSizes)
        registerSampleBenchmark("scaling/triangles", {tessellatedKey(n), sizeLabel(n), SampleKind::PT, 8, 2});
    for (SampleKind kind : {SampleKind::PT, SampleKind::BDPT})
        for (int depth : {4, 8, 16, 32}) registerSampleBenchmark("scaling/depth", {"cornell", "cornell", kind, depth, 2});
    for (size_t n : kSizes)
        benchmark::RegisterBenchmark(("memory/" + sizeLabel(n)).c_str(),
                                     [n](benchmark::State& st) { runMemory(st, n); })
            ->Iterations(1);
    return true;
}();

}  // namespace

}  // namespace tripath::bench
