#include "integrators/render.h"

#include <fmt/format.h>
#include <tbb/task_arena.h>

#include "integrators/tile_passes.h"

namespace tripath {

RenderResult& addResumed(RenderResult& r, const RenderResult* resume) {
    if (!resume) return r;
    r.film.add(resume->film);
    r.passes += resume->passes;
    r.seconds += resume->seconds;
    if (r.budgetPasses > 0) r.budgetPasses += resume->passes;
    if (r.budgetSeconds > 0) r.budgetSeconds += resume->seconds;
    r.droppedSamples += resume->droppedSamples;
    r.guardedWeights += resume->guardedWeights;
    return r;
}

MemoryEstimate admitMemory(const Scene& scene, const Integrator& integrator, const RenderSettings& settings) {
    MemoryEstimate estimate = estimateMemory(scene, integrator, settings);
    if (settings.checkMemory)
        together(settings.team ? *settings.team : solo(), [&] { settings.checkMemory(estimate); });
    return estimate;
}

RenderResult startRender(const Scene& scene, const Integrator& integrator, const RenderSettings& settings) {
    const Camera& cam = scene.camera();
    FilmLayers layers = settings.layers;
    layers.strategies = integrator.strategies();
    MemoryEstimate memory = admitMemory(scene, integrator, settings);
    return {.film = Film(cam.width(), cam.height(), layers),
            .budgetPasses = settings.spp,
            .budgetSeconds = settings.seconds,
            .memory = std::move(memory)};
}

RenderResult PixelSampleIntegrator::render(const Scene& scene, const RenderSettings& settings) const {
    RenderResult result = startRender(scene, *this, settings);
    TilePasses passes(scene, *this, settings, settings.resume ? settings.resume->nextPass : settings.firstPass);
    return runPasses(settings, passes, std::move(result));
}

RenderResult render(const Scene& scene, const Integrator& integrator, const RenderSettings& settings) {
    return integrator.render(scene, settings);
}

std::string interruptionText(const RenderResult& r) {
    if (r.budgetSeconds > 0) return fmt::format("after {} passes, {:.2f} s of {:g} s", r.passes, r.seconds, r.budgetSeconds);
    return fmt::format("after {} of {} passes, {:.2f} s", r.passes, r.budgetPasses, r.seconds);
}

void replaySample(const Scene& scene, const PixelSampleIntegrator& integrator, const RenderSettings& settings, uint64_t pass,
                  int pixel, ContributionSink& sink) {
    const Camera& cam = scene.camera();
    LightPhase lightPhase;
    tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        const Pass p = lightPhase.run(scene, integrator, pass, settings.streams());
        PathBuffers paths;
        SampleStream rng = sampleStream(settings.streams(), pass, cam, pixel);
        const Vec2 raster = jitteredRaster(rng, pixel, cam.width());
        integrator.sample(scene, p, pixel, CameraRay(raster), rng, paths, sink);
    });
}

}  // namespace tripath
