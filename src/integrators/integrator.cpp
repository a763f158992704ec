#include "integrators/integrator.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

#include "core/error.h"

namespace tripath {

std::unique_ptr<Integrator> makePathTracer(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeLightTracer(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeBidirectional(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeVertexMerging(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeBidirectionalPhotonMapping(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeProgressivePhotonMapping(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeMetropolis(const IntegratorSettings& s);

std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const IntegratorSettings& settings) {
    if (name == "pt") return makePathTracer(settings);
    if (name == "lt") return makeLightTracer(settings);
    if (name == "bdpt") return makeBidirectional(settings);
    if (name == "vcm") return makeVertexMerging(settings);
    if (name == "bpm") return makeBidirectionalPhotonMapping(settings);
    if (name == "ppm") return makeProgressivePhotonMapping(settings);
    if (name == "mlt") return makeMetropolis(settings);
    throw InputError(fmt::format("unknown integrator '{}' ({})", name.substr(0, 40), fmt::join(kIntegratorNames, ", ")));
}

int defaultRouletteDepth(const std::string& integrator) {
    return makeIntegrator(integrator, {})->hasLightPhase() ? 2 : 3;  // the rule, not a list of names
}

float Integrator::firstMergeRadius(const Scene& scene) const {
    if (!strategies().merges()) return 0.0f;
    const MergeSettings& m = settings_.merge;
    const float sceneRadius = 0.5f * length(scene.boundsMax() - scene.boundsMin());
    float r1 = m.radius;
    if (!(r1 > 0)) r1 = m.radiusFactor * sceneRadius;
    if (!(r1 > 0)) r1 = m.radiusPixels * medianPixelFootprint(scene);
    if (!(r1 > 0)) r1 = kFallbackRadiusFactor * sceneRadius;
    return r1;
}

float Integrator::mergeRadius(float firstRadius, uint64_t index) const {
    return static_cast<float>(firstRadius * std::pow(double(index + 1), 0.5 * (double(settings_.merge.alpha) - 1.0)));
}

double Integrator::lightPaths(const Scene& scene) const {
    const Camera& cam = scene.camera();
    return settings_.lightPaths ? double(*settings_.lightPaths) : double(cam.width()) * cam.height();
}

MisContext Integrator::misContext(const PassConstants& constants) const {
    MisContext mis{settings_.mis, strategies(), Roulette{settings_.walk.rrDepth}, constants};
    mis.runningSums = canUseRunningSums(mis);
    return mis;
}

void Integrator::sample(const Scene& scene, const Pass& pass, int pixel, const CameraRay& ray, Rng& rng, PathBuffers& paths,
                        ContributionSink& sink) const {
    const SubpathView light = pass.light ? pass.light->path(size_t(pixel) % pass.light->paths()) : SubpathView();
    // The light path was likely traced on another core: its lines are requested before the camera walk.
    for (size_t i = 0; i < light.vertices.size_bytes(); i += 64)
        __builtin_prefetch(reinterpret_cast<const char*>(light.vertices.data()) + i);
    for (size_t i = 0; i < light.bsdfs.size_bytes(); i += 64)
        __builtin_prefetch(reinterpret_cast<const char*>(light.bsdfs.data()) + i);
    cameraWalk(scene, pass, ray, rng, paths.camera);
    splatLightPaths(scene, pass, pixel, SubpathView(paths.camera).first(1), rng, sink);
    connectAll(scene, pass, light, paths.camera, 2, rng, sink);
    if (pass.search) mergeAll(scene, pass, paths.camera, sink);
}

void Integrator::splatLightPaths(const Scene& scene, const Pass& pass, int pixel, const SubpathView& sensor, Rng& rng,
                                 ContributionSink& sink) const {
    if (!pass.light || !strategies().enabled(1, 1)) return;
    const size_t pixels = size_t(scene.camera().width()) * scene.camera().height();
    for (size_t j = size_t(pixel); j < pass.light->paths(); j += pixels) connectAll(scene, pass, pass.light->path(j), sensor, 1, rng, sink);
}

void Integrator::cameraWalk(const Scene& scene, const Pass& pass, const CameraRay& ray, Rng& rng, Subpath& camera) const {
    cameraSubpath(scene, ray, rng, settings_.walk, strategies().cameraWalkPdfs(), pass.mis.constants.lightPaths, camera);
    recordRunningSums(camera.vertices, false, pass.mis);
}

}  // namespace tripath
