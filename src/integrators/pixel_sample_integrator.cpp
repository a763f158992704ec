// What the methods of camera samples share (pixel_sample_integrator.h): the default sample, its
// camera walk and the light paths' splats, and what makes a pass's constants (N_L, the merge
// radius) and MIS context. Their render() is render.cpp's.
#include "integrators/pixel_sample_integrator.h"

#include <cmath>

namespace tripath {

std::unique_ptr<PixelSampleIntegrator> Integrator::largestPasses(const Scene&) const { return nullptr; }

float PixelSampleIntegrator::firstMergeRadius(const Scene& scene) const {
    if (!walkStrategies().merges()) return 0.0f;
    const MergeSettings& m = settings().merge;
    const float sceneRadius = 0.5f * length(scene.boundsMax() - scene.boundsMin());
    float r1 = m.radius;
    if (!(r1 > 0)) r1 = m.radiusFactor * sceneRadius;
    if (!(r1 > 0)) r1 = m.radiusPixels * medianPixelFootprint(scene);
    if (!(r1 > 0)) r1 = kFallbackRadiusFactor * sceneRadius;
    return r1;
}

float PixelSampleIntegrator::mergeRadius(float firstRadius, uint64_t index) const {
    return static_cast<float>(firstRadius * std::pow(double(index + 1), 0.5 * (double(settings().merge.alpha) - 1.0)));
}

double PixelSampleIntegrator::lightPaths(const Scene& scene) const {
    const Camera& cam = scene.camera();
    return settings().lightPaths ? double(*settings().lightPaths) : double(cam.width()) * cam.height();
}

MisContext PixelSampleIntegrator::misContext(const PassConstants& constants) const {
    MisContext mis{settings().mis, strategies(), Roulette{settings().walk.rrDepth}, constants};
    if (const std::optional<StrategySet> measured = measuredStrategies())
        mis.measure = {true, *measured, constants.mergeEta};  // weighed by class: no running sums read
    else
        mis.runningSums = canUseRunningSums(mis);
    return mis;
}

void PixelSampleIntegrator::sample(const Scene& scene, const Pass& pass, int pixel, const CameraRay& ray, SampleStream& rng,
                                   PathBuffers& paths, ContributionSink& sink) const {
    if (!pass.mis.strategies.walksCamera()) {
        sensorSubpath(scene, paths.camera);
        splatLightPaths(scene, pass, pixel, paths.camera, rng, sink);
        return;
    }
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

void PixelSampleIntegrator::splatLightPaths(const Scene& scene, const Pass& pass, int pixel, const SubpathView& sensor,
                                            SampleStream& rng, ContributionSink& sink) const {
    if (!pass.light || !strategies().enabled(1, 1)) return;
    const size_t pixels = size_t(scene.camera().width()) * scene.camera().height();
    for (size_t j = size_t(pixel); j < pass.light->paths(); j += pixels) connectAll(scene, pass, pass.light->path(j), sensor, 1, rng, sink);
}

void PixelSampleIntegrator::cameraWalk(const Scene& scene, const Pass& pass, const CameraRay& ray, SampleStream& rng,
                                       Subpath& camera) const {
    cameraSubpath(scene, ray, rng, settings().walk, walkStrategies().cameraWalkPdfs(), pass.mis.constants.lightPaths, camera);
    recordRunningSums(camera.vertices, false, pass.mis);
}

}  // namespace tripath
