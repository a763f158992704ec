// Whole samples: a camera subpath, a light subpath, and one pt / lt / bdpt sample, on the scenes
// of sampleScenes(), at max-depth 8 (the depth of bench/README.md's targets), on 1 and 2 threads.
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <memory>

#include "bench_scenes.h"
#include "integrators/pixel_sample_integrator.h"
#include "integrators/tile_passes.h"
#include "sample_harness.h"

namespace tripath::bench {

const char* sampleKindName(SampleKind kind) {
    switch (kind) {
        case SampleKind::CameraSubpath: return "camera_subpath";
        case SampleKind::LightSubpath: return "light_subpath";
        case SampleKind::PT: return "pt";
        case SampleKind::LT: return "lt";
        case SampleKind::BDPT: return "bdpt";
    }
    return "?";
}

namespace {

constexpr uint64_t kSeed = 1;

// Sums what an integrator delivers, so the work cannot be optimised away, and counts the
// connections that cast a shadow ray and came back unoccluded (s ≥ 1; s = 0 casts none).
class SummingSink final : public ContributionSink {
public:
    void add(Strategy st, const Connection& c) override {
        sum += luminance(c.weighted());
        if (!st.merge && st.s >= 1) ++shadowConnections;
    }
    double sum = 0;
    uint64_t shadowConnections = 0;
};

struct Worker {
    PathBuffers paths;
    SummingSink sink;
    uint64_t samples = 0, vertices = 0;
    RayCounts rays;
};

// Vertices a walk found with a ray: all but the sensor z0 and the sampled emitter point y0.
uint64_t traced(const Subpath& p) { return p.size() == 0 ? 0 : p.size() - 1; }

void runSamples(benchmark::State& state, const SampleSpec& spec) {
    const Scene& scene = cachedScene(spec.sceneKey);
    IntegratorSettings settings;
    settings.walk.maxDepth = spec.maxDepth;
    settings.mis = MisHeuristic::Power;  // the CLI's default
    std::unique_ptr<Integrator> integrator;
    if (spec.kind == SampleKind::PT || spec.kind == SampleKind::LT || spec.kind == SampleKind::BDPT)
        integrator = makeIntegrator(sampleKindName(spec.kind), settings);
    const PixelSampleIntegrator* method = integrator ? integrator->pixelSamples() : nullptr;

    tbb::enumerable_thread_specific<Worker> workers;
    // lt and bdpt read the light paths of their pass: a light phase for the block's pixels, traced
    // from the render's light-path streams, runs before the block's camera samples (timed with them).
    const bool lightPhase = method && method->hasLightPhase();
    std::vector<Subpath> lightPaths(lightPhase ? kBlockPixels : 0);
    LightStore store;
    const uint64_t pixels = uint64_t(kWidth) * kHeight;
    Pass pass;
    pass.mis.constants = passConstants(double(pixels), 0.0f);  // N_L: one light path per pixel, as rendered
    if (method) pass.mis = method->misContext(pass.mis.constants);
    tbb::task_arena& arena = arenaFor(spec.threads);
    uint64_t iteration = 0;

    auto oneSample = [&](Worker& w, int x, int y, int blockPixel, uint64_t passIndex) {
        const int pixel = y * kWidth + x;
        // The render loop's stream for (pixel, pass), so the samples are the ones a render draws.
        SampleStream rng = sampleStream({kSeed, StreamDomain::CameraSample}, passIndex, scene.camera(), pixel);
        const Vec2 raster = jitteredRaster(rng, pixel, kWidth);
        switch (spec.kind) {
            case SampleKind::CameraSubpath:
                cameraSubpath(scene, raster, rng, settings.walk, WalkPdfs::All, pass.mis.constants.lightPaths, w.paths.camera);
                w.sink.sum += w.paths.camera.vertices.back().beta.x;
                break;
            case SampleKind::LightSubpath:
                lightSubpath(scene, rng, settings.walk, WalkPdfs::All, w.paths.light);
                if (w.paths.light.size() > 0) w.sink.sum += w.paths.light.vertices.back().beta.x;
                break;
            default:
                method->sample(scene, pass, blockPixel, raster, rng, w.paths, w.sink);
                if (lightPhase) w.vertices += traced(lightPaths[blockPixel]);
                break;
        }
        // lt leaves a sensor-only camera subpath, so counting both buffers is right for every kind
        // (the subpath-only kinds never fill the other buffer).
        w.vertices += traced(w.paths.camera) + traced(w.paths.light);
        ++w.samples;
    };

    for (auto _ : state) {
        const int block = blockOfIteration(iteration);
        const int bx = (block % kBlocksX) * kBlock, by = (block / kBlocksX) * kBlock;
        const uint64_t passIndex = iteration / kBlocks;
        arena.execute([&] {
            if (lightPhase) {
                tbb::parallel_for(tbb::blocked_range<int>(0, kBlockPixels, kBlock), [&](const tbb::blocked_range<int>& r) {
                    Worker& w = workers.local();
                    const RayCounts before = threadRayCounts();
                    for (int i = r.begin(); i < r.end(); ++i) {
                        const int pixel = (by + i / kBlock) * kWidth + bx + i % kBlock;
                        Rng rng(kSeed, static_cast<uint64_t>(StreamDomain::LightPath), passIndex * pixels + pixel);
                        lightSubpath(scene, rng, settings.walk, method->strategies().lightWalkPdfs(), lightPaths[i]);
                    }
                    w.rays += threadRayCounts() - before;
                });
                store.reset(lightPaths.size());
                for (size_t i = 0; i < lightPaths.size(); ++i) store.chunk(i / LightStore::kPathsPerChunk).append(lightPaths[i]);
                pass.light = &store;
            }
            tbb::parallel_for(tbb::blocked_range<int>(0, kBlockPixels, kBlock), [&](const tbb::blocked_range<int>& r) {
                Worker& w = workers.local();
                const RayCounts before = threadRayCounts();
                for (int i = r.begin(); i < r.end(); ++i) oneSample(w, bx + i % kBlock, by + i / kBlock, i, passIndex);
                w.rays += threadRayCounts() - before;
            });
        });
        ++iteration;
    }

    uint64_t samples = 0, vertices = 0, shadow = 0;
    RayCounts rays;
    double sum = 0;
    for (const Worker& w : workers) {
        samples += w.samples;
        vertices += w.vertices;
        shadow += w.sink.shadowConnections;
        rays += w.rays;
        sum += w.sink.sum;
    }
    benchmark::DoNotOptimize(sum);
    const double n = static_cast<double>(samples);
    const uint64_t estimate = vertices + shadow;
    using C = benchmark::Counter;
    state.counters["samples_per_s"] = C(n, C::kIsRate);
    state.counters["rays_per_s"] = C(static_cast<double>(rays.total()), C::kIsRate);
    state.counters["rays_est_per_s"] = C(static_cast<double>(estimate), C::kIsRate);
    state.counters["rays_per_sample"] = rays.total() / n;
    state.counters["rays_est_per_sample"] = estimate / n;
    state.counters["isect_per_sample"] = rays.intersect / n;
    state.counters["occl_per_sample"] = rays.occluded / n;
    state.counters["verts_per_sample"] = vertices / n;
    state.counters["conn_per_sample"] = shadow / n;
    state.counters["threads"] = spec.threads;
    // How many threads actually took part: the arena may get fewer workers than it allows.
    state.counters["workers"] = static_cast<double>(workers.size());
}

}  // namespace

benchmark::internal::Benchmark* registerSampleBenchmark(const std::string& prefix, const SampleSpec& spec) {
    const std::string name = prefix + "/" + sampleKindName(spec.kind) + "/" + spec.label +
                             "/depth:" + std::to_string(spec.maxDepth) + "/threads:" + std::to_string(spec.threads);
    // Wall-clock time (the work runs on TBB workers, not only on the benchmark's thread); the
    // process CPU time is recorded too, so cpu_time / real_time shows how many cores we really got.
    return benchmark::RegisterBenchmark(name.c_str(), [spec](benchmark::State& st) { runSamples(st, spec); })
        ->UseRealTime()
        ->MeasureProcessCPUTime()
        ->Unit(benchmark::kMillisecond);
}

namespace {

const bool registered = [] {
    for (const auto& [label, key] : sampleScenes())
        for (SampleKind kind : {SampleKind::CameraSubpath, SampleKind::LightSubpath, SampleKind::PT, SampleKind::LT,
                                SampleKind::BDPT})
            for (int threads : {1, 2}) registerSampleBenchmark("sample", {key, label, kind, 8, threads});
    return true;
}();

}  // namespace

}  // namespace tripath::bench
