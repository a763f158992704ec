// A render's memory, part by part (memory_estimate.h).
#include "integrators/memory_estimate.h"

#include <fmt/format.h>

#include <algorithm>

#include "core/byte_size.h"
#include "integrators/light_phase.h"
#include "integrators/metropolis_render.h"
#include "integrators/render.h"

namespace tripath {

uint64_t MemoryEstimate::total() const {
    uint64_t phase[3] = {0, 0, 0};
    for (const MemoryPart& p : parts) phase[static_cast<int>(p.phase)] += p.bytes;
    return phase[0] + std::max(phase[1], phase[2]);
}

void MemoryEstimate::add(std::vector<MemoryPart> more) {
    std::erase_if(more, [](const MemoryPart& p) { return p.bytes == 0; });
    parts.insert(parts.end(), more.begin(), more.end());
    std::stable_sort(parts.begin(), parts.end(), [](const MemoryPart& a, const MemoryPart& b) { return a.bytes > b.bytes; });
}

std::string MemoryEstimate::breakdown() const {
    std::string text;
    for (const MemoryPart& p : parts) text += fmt::format("{}{} {}", text.empty() ? "" : ", ", p.name, bytesText(p.bytes));
    return text;
}

std::vector<MemoryPart> sceneMemory(const Scene& scene) {
    const Scene::Memory m = scene.memory();
    return {{"process", kProcessBytes, {}},
            {"triangles", m.triangles, {}},
            {"textures", m.textures, {}},
            {"environment", m.environment, {}}};
}

namespace {

// What a loop of Markov chains holds: the chains, their splats of one pass and the bootstrap
// (metropolisMemory).
std::vector<MemoryPart> chainMemory(double pixels, const MetropolisSettings& chains, int maxDepth) {
    using enum MemoryPart::Phase;
    const MetropolisMemory m = metropolisMemory(pixels, chains, maxDepth);
    return {{"chains", m.chains, {"chains", "max-depth"}, Rendering},
            {"splats", m.splats, {"width/height"}, Rendering},
            {"bootstrap", m.bootstrap, {"bootstrap"}, Rendering}};
}

// What a light phase holds: a pass's light paths (with the merge search when the method merges)
// and their splats waiting for the end of the pass, from a survey of the first pass's light paths.
std::vector<MemoryPart> lightPhaseMemory(const Scene& scene, const PixelSampleIntegrator& integrator,
                                         const RenderSettings& settings) {
    using enum MemoryPart::Phase;
    const uint64_t first = settings.resume ? settings.resume->nextPass : settings.firstPass;
    const LightPathSurvey survey = LightPhase::survey(scene, integrator, first, settings.streams());
    const double paths = integrator.lightPaths(scene);
    // One light path per pixel unless --light-paths says otherwise.
    std::vector<std::string> fewer{"light-paths"};
    if (!integrator.settings().lightPaths) fewer.insert(fewer.begin(), "width/height");
    return {{"light paths", LightPhase::bytes(paths, survey, integrator.strategies().merges()), fewer, Rendering},
            {"splats", pendingSplatBytes(paths * survey.splats), fewer, Rendering}};
}

}  // namespace

std::vector<MemoryPart> renderMemory(const Scene& scene, const Integrator& integrator, const RenderSettings& settings) {
    using enum MemoryPart::Phase;
    const Camera& cam = scene.camera();
    const double pixels = double(cam.width()) * cam.height();
    FilmLayers layers = settings.layers;
    layers.strategies = integrator.strategies();
    std::vector<std::string> film{"width/height"};
    if (layers.depthImages > 0) film.push_back("depth-images");
    if (layers.strategyLength > 0) film.push_back("strategy-images");
    const uint64_t films = 1 + (settings.resume ? 1 : 0) + (settings.checkpointSeconds > 0 ? 1 : 0);
    std::vector<MemoryPart> parts{
        {"film", static_cast<uint64_t>(films * Film::images(layers) * Film::kBytesPerPixel * pixels), film, Throughout},
        {"image out", static_cast<uint64_t>(kOutputBytesPerPixel * pixels), {"width/height"}, Writing}};
    std::vector<MemoryPart> loop;
    if (const MetropolisSettings* chains = integrator.markovChains())
        loop = chainMemory(pixels, *chains, integrator.settings().walk.maxDepth);
    else if (const PixelSampleIntegrator* samples = integrator.pixelSamples(); samples && samples->hasLightPhase())
        loop = lightPhaseMemory(scene, *samples, settings);
    else if (const std::unique_ptr<PixelSampleIntegrator> largest = integrator.largestPasses(scene))
        loop = lightPhaseMemory(scene, *largest, settings);
    parts.insert(parts.end(), loop.begin(), loop.end());
    return parts;
}

MemoryEstimate estimateMemory(const Scene& scene, const Integrator& integrator, const RenderSettings& settings) {
    MemoryEstimate e;
    e.add(sceneMemory(scene));
    e.add(renderMemory(scene, integrator, settings));
    return e;
}

}  // namespace tripath
