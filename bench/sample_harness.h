// Whole-sample throughput: the one harness samples.cpp and scaling.cpp register benchmarks with.
#pragma once
#include <benchmark/benchmark.h>

#include <string>

namespace tripath::bench {

enum class SampleKind {
    CameraSubpath,  // cameraSubpath() alone
    LightSubpath,   // lightSubpath() alone
    PT,             // PixelSampleIntegrator::sample of pt, lt, bdpt: subpaths, every enabled strategy, MIS
    LT,
    BDPT,
};
const char* sampleKindName(SampleKind kind);

struct SampleSpec {
    std::string sceneKey;  // cachedScene key
    std::string label;     // short scene name for the benchmark name
    SampleKind kind = SampleKind::PT;
    int maxDepth = 8;
    int threads = 2;
};

// Registers "<prefix>/<kind>/<label>/depth:<d>/threads:<n>". Each iteration runs one 64×64 block
// of pixels, one sample each, in a tbb::parallel_for over `threads` workers; time is wall-clock.
// Counters (rates per wall-clock second): samples_per_s, rays_per_s (exact, Embree calls counted)
// and rays_est_per_s (the subpath-vertices-plus-connections estimate); per sample: rays, the
// intersect/occluded split, vertices and connections.
benchmark::internal::Benchmark* registerSampleBenchmark(const std::string& prefix, const SampleSpec& spec);

}  // namespace tripath::bench
