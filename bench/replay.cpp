// The ceiling on the renderer's own rays. ceiling.cpp casts random rays; a render's
// rays are not random (they start on surfaces, many are short shadow rays, camera rays are
// coherent), so "fraction of the ceiling" is only meaningful for the same rays. Here one pass of
// the production render loop (render(): light phase, camera samples, film) is recorded ray by ray
// through the Embree interposition of ray_count.cpp, and
//   replay/<integrator>/<scene>/depth:<d>/threads:<n>/render  times whole passes of render()
//       (rays_per_s: the passes' rays, from the renderer's own counters, over wall-clock time);
//   replay/<integrator>/<scene>/depth:<d>/threads:<n>/embree  times the recorded rays cast through
//       Embree's functions alone, in the order they were cast, in chunks of kChunk rays spread
//       over the same number of threads.
// The first's rays_per_s over the second's is the share of the ceiling a render reaches; the
// rest of a pass's time is everything a renderer does besides tracing rays.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <memory>

#include "bench_scenes.h"
#include "core/rng.h"
#include "integrators/render.h"

namespace tripath::bench {

namespace {

constexpr int kDepth = 8;        // the depth bench/README.md states its targets at
constexpr size_t kChunk = 4096;  // rays per task in the replay: a few tiles' worth

std::unique_ptr<Integrator> integratorFor(const std::string& name) {
    IntegratorSettings settings;
    settings.walk.maxDepth = kDepth;
    return makeIntegrator(name, settings);
}

// Pass `index` of the production loop on `threads` threads (the Film and the arena are set up
// per call, as a one-pass render does; both are small against a 512² pass).
RenderResult renderPass(const Scene& scene, const Integrator& integrator, uint64_t index, int threads) {
    RenderSettings rs;
    rs.spp = 1;
    rs.firstPass = index;
    rs.threads = threads;
    return render(scene, integrator, rs);
}

void runRender(benchmark::State& state, const std::string& key, const std::string& name, int threads) {
    const Scene& scene = cachedScene(key);
    const auto integrator = integratorFor(name);
    uint64_t rays = 0, samples = 0, index = 0;
    for (auto _ : state) {
        const RenderResult r = renderPass(scene, *integrator, index++, threads);
        rays += r.stats[Event::ClosestHitRays] + r.stats[Event::ShadowRays];
        samples += uint64_t(scene.camera().width()) * scene.camera().height();
    }
    using C = benchmark::Counter;
    state.counters["rays_per_s"] = C(double(rays), C::kIsRate);
    state.counters["samples_per_s"] = C(double(samples), C::kIsRate);
    state.counters["rays_per_sample"] = double(rays) / double(samples);
}

void runEmbree(benchmark::State& state, const std::string& key, const std::string& name, int threads) {
    const Scene& scene = cachedScene(key);
    const auto integrator = integratorFor(name);
    std::vector<RecordedRay> rays;
    setRayRecorder(&rays);
    renderPass(scene, *integrator, 0, 1);  // one thread: the rays in the order one worker casts them
    setRayRecorder(nullptr);
    const size_t chunks = (rays.size() + kChunk - 1) / kChunk;
    std::atomic<uint64_t> hits{0};
    tbb::task_arena& arena = arenaFor(threads);
    for (auto _ : state)
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks, 1), [&](const tbb::blocked_range<size_t>& r) {
                for (size_t c = r.begin(); c < r.end(); ++c) {
                    const size_t first = c * kChunk, n = std::min(kChunk, rays.size() - first);
                    hits.fetch_add(replayEmbree(std::span(rays).subspan(first, n)), std::memory_order_relaxed);
                }
            });
        });
    using C = benchmark::Counter;
    state.counters["rays_per_s"] = C(double(rays.size()) * double(state.iterations()), C::kIsRate);
    state.counters["rays_per_pass"] = double(rays.size());
    state.counters["hit_fraction"] = double(hits.load()) / (double(rays.size()) * double(state.iterations()));
}

// The shadow rays of a pass alone, cast one at a time or in packets of 8 consecutive ones (a
// sample's connections, mostly): what batching a sample's shadow rays could save in Embree.
void runShadowPackets(benchmark::State& state, const std::string& key, const std::string& name, int width) {
    const Scene& scene = cachedScene(key);
    const auto integrator = integratorFor(name);
    std::vector<RecordedRay> rays, shadow;
    setRayRecorder(&rays);
    renderPass(scene, *integrator, 0, 1);
    setRayRecorder(nullptr);
    for (const RecordedRay& r : rays)
        if (r.shadow) shadow.push_back(r);
    uint64_t blocked = 0;
    for (auto _ : state) blocked += replayShadowPackets(shadow, width);
    using C = benchmark::Counter;
    state.counters["rays_per_s"] = C(double(shadow.size()) * double(state.iterations()), C::kIsRate);
    state.counters["blocked_fraction"] = double(blocked) / (double(shadow.size()) * double(state.iterations()));
}

// The camera rays of one pass, in the render loop's order (tile by tile, row by row), cast one at a
// time or in packets of 8 neighbouring pixels: what tracing a camera subpath's first segment in
// coherent packets could save in Embree.
void runCameraPackets(benchmark::State& state, const std::string& key, int width) {
    const Scene& scene = cachedScene(key);
    const Camera& cam = scene.camera();
    // The scene's Embree handle, as the interposition sees it on one recorded ray.
    std::vector<RecordedRay> probe;
    setRayRecorder(&probe);
    scene.intersect(cam.position(), cam.forward());
    setRayRecorder(nullptr);
    std::vector<RecordedRay> rays;
    constexpr int kTile = 16;
    for (int ty = 0; ty < cam.height(); ty += kTile)
        for (int tx = 0; tx < cam.width(); tx += kTile)
            for (int y = ty; y < std::min(ty + kTile, cam.height()); ++y)
                for (int x = tx; x < std::min(tx + kTile, cam.width()); ++x) {
                    Rng rng(1, static_cast<uint64_t>(StreamDomain::CameraSample), uint64_t(y) * cam.width() + x);
                    const float jx = rng.uniform(), jy = rng.uniform();
                    rays.push_back({probe.at(0).scene, cam.position(), cam.direction({x + jx, y + jy}), 0.0f, 3.0e38f, false});
                }
    uint64_t hits = 0;
    for (auto _ : state) hits += replayClosestHitPackets(rays, width, true);
    using C = benchmark::Counter;
    state.counters["rays_per_s"] = C(double(rays.size()) * double(state.iterations()), C::kIsRate);
    state.counters["hit_fraction"] = double(hits) / (double(rays.size()) * double(state.iterations()));
}

// 30 bits of Morton order: 10 per axis of p's place in the box [lo, hi].
uint32_t morton(Vec3 p, Vec3 lo, Vec3 hi) {
    auto spread = [](uint32_t v) {  // bits 0..9 of v to bits 0, 3, 6, ..., 27
        v = (v | (v << 16)) & 0x030000FFu;
        v = (v | (v << 8)) & 0x0300F00Fu;
        v = (v | (v << 4)) & 0x030C30C3u;
        return (v | (v << 2)) & 0x09249249u;
    };
    uint32_t c[3];
    for (int a = 0; a < 3; ++a) {
        const float t = (p[a] - lo[a]) / std::max(hi[a] - lo[a], 1e-20f);
        c[a] = static_cast<uint32_t>(std::clamp(t, 0.0f, 1.0f) * 1023.0f);
    }
    return spread(c[0]) | spread(c[1]) << 1 | spread(c[2]) << 2;
}

// The most a wavefront could gain in Embree. One pass's rays,
// recorded on one thread, are split by kind into queues of kChunk rays in the order they were
// cast (a wavefront's queue of a few tiles' rays); each queue is sorted as a wavefront with ray
// sorting would sort it -- by direction octant, then by the Morton order of the origin in the
// scene's box -- and cast one at a time or in packets of 8 (closest-hit rays with Embree's
// incoherent flag). The sort itself is not timed, and a real wavefront's queues would hold one
// bounce's rays of many more paths, so this bounds the tracing side from above; against
// replay/.../threads:1/embree (the same rays, unsorted, one at a time) it says how far packets
// alone can take a render.
void runWavefrontBound(benchmark::State& state, const std::string& key, const std::string& name, int width) {
    const Scene& scene = cachedScene(key);
    const auto integrator = integratorFor(name);
    std::vector<RecordedRay> rays;
    setRayRecorder(&rays);
    renderPass(scene, *integrator, 0, 1);
    setRayRecorder(nullptr);
    std::vector<RecordedRay> queues[2];  // closest-hit, shadow
    for (const RecordedRay& r : rays) queues[r.shadow].push_back(r);
    const Vec3 lo = scene.boundsMin(), hi = scene.boundsMax();
    auto sortKey = [&](const RecordedRay& r) {
        const uint64_t octant = (r.dir.x < 0) | (r.dir.y < 0) << 1 | (r.dir.z < 0) << 2;
        return octant << 32 | morton(r.origin, lo, hi);
    };
    for (auto& q : queues)
        for (size_t first = 0; first < q.size(); first += kChunk) {
            const auto b = q.begin() + std::ptrdiff_t(first), e = q.begin() + std::ptrdiff_t(std::min(q.size(), first + kChunk));
            std::stable_sort(b, e, [&](const RecordedRay& x, const RecordedRay& y) { return sortKey(x) < sortKey(y); });
        }
    uint64_t hits = 0;
    for (auto _ : state) {
        for (size_t first = 0; first < std::max(queues[0].size(), queues[1].size()); first += kChunk) {
            auto chunk = [&](const std::vector<RecordedRay>& q) {
                return std::span(q).subspan(std::min(first, q.size()), std::min(kChunk, q.size() - std::min(first, q.size())));
            };
            hits += replayClosestHitPackets(chunk(queues[0]), width, false);
            hits += replayShadowPackets(chunk(queues[1]), width);
        }
    }
    using C = benchmark::Counter;
    state.counters["rays_per_s"] = C(double(rays.size()) * double(state.iterations()), C::kIsRate);
    state.counters["shadow_share"] = double(queues[1].size()) / double(rays.size());
    state.counters["hit_fraction"] = double(hits) / (double(rays.size()) * double(state.iterations()));
}

const bool registered = [] {
    for (const auto& [label, key] : sampleScenes())
        for (const char* name : {"pt", "bdpt", "vcm"})
            for (int width : {1, 8})
                benchmark::RegisterBenchmark(
                    (std::string("replay_wavefront/") + name + "/" + label + "/packet:" + std::to_string(width)).c_str(),
                    [key = key, name, width](benchmark::State& st) { runWavefrontBound(st, key, name, width); })
                    ->UseRealTime()
                    ->Unit(benchmark::kMillisecond);
    for (const auto& [label, key] : sampleScenes())
        for (int width : {1, 8})
            benchmark::RegisterBenchmark((std::string("replay_camera/") + label + "/packet:" + std::to_string(width)).c_str(),
                                         [key = key, width](benchmark::State& st) { runCameraPackets(st, key, width); })
                ->UseRealTime()
                ->Unit(benchmark::kMillisecond);
    for (const auto& [label, key] : sampleScenes())
        for (int width : {1, 8})
            benchmark::RegisterBenchmark(
                (std::string("replay_shadow/bdpt/") + label + "/packet:" + std::to_string(width)).c_str(),
                [key = key, width](benchmark::State& st) { runShadowPackets(st, key, "bdpt", width); })
                ->UseRealTime()
                ->Unit(benchmark::kMillisecond);
    for (const auto& [label, key] : sampleScenes())
        for (const char* name : {"pt", "bdpt", "vcm"})
            for (int threads : {1, 2}) {
                const std::string base = std::string("replay/") + name + "/" + label + "/depth:" +
                                         std::to_string(kDepth) + "/threads:" + std::to_string(threads);
                benchmark::RegisterBenchmark((base + "/render").c_str(),
                                             [key = key, name, threads](benchmark::State& st) { runRender(st, key, name, threads); })
                    ->UseRealTime()
                    ->Unit(benchmark::kMillisecond);
                benchmark::RegisterBenchmark((base + "/embree").c_str(),
                                             [key = key, name, threads](benchmark::State& st) { runEmbree(st, key, name, threads); })
                    ->UseRealTime()
                    ->Unit(benchmark::kMillisecond);
            }
    return true;
}();

}  // namespace

}  // namespace tripath::bench
