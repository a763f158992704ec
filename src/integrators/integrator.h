// An integrator is a choice of subpaths and of strategies over the path core (src/paths).
// Each one lives in its own file with its parameters documented at the top.
#pragma once
#include <memory>
#include <optional>
#include <string>

#include "paths/strategies.h"

namespace tripath {

struct RenderSettings;
struct RenderResult;

// Vertex merging's radius schedule (vcm, bpm, ppm): r_i = r_1 · i^((α−1)/2) at the i-th pass
// (i = 1, 2, … over the whole render, a reference's continuation included), so that the radius
// depends on the pass index alone, never on threads or timing.
// r_1 is the first of these that is set: a length in world units; a fraction of the scene's
// bounding-sphere radius; or, by default, a number of pixel widths on the surfaces the camera sees
// (medianPixelFootprint). The default follows the image: it keeps the blur of a merge near a
// pixel at any resolution, and cannot blow up on a scene whose extent dwarfs the view (a
// fraction of a 10 km scene's radius is metres over a 3 mm view, where every camera vertex would
// merge with every light vertex). If the camera sees nothing, kFallbackRadiusFactor applies.
struct MergeSettings {
    float radius = 0;          // r_1 in world units (0: not given)
    float radiusFactor = 0;    // r_1 as a fraction of the scene's bounding-sphere radius (0: not given)
    float radiusPixels = 0.75f;  // r_1 in pixel widths
    float alpha = 0.75f;       // 1: a fixed radius; < 1: shrinking (consistent); in (0, 1]
};
inline constexpr float kFallbackRadiusFactor = 0.003f;

// mlt's parameters (integrators/mlt.cpp).
struct MetropolisSettings {
    int64_t bootstrap = 100000;  // N: bootstrap samples for the normalisation, spread evenly over the path lengths
    int chains = 1024;           // Markov chains over all lengths (at most one per pixel)
    float largeStep = 0.3f;      // probability that a proposal is a large step
};

struct IntegratorSettings {
    WalkSettings walk;
    std::optional<int64_t> lightPaths;  // N_L, the light paths per pass, as given (Integrator::lightPaths)
    MisHeuristic mis = MisHeuristic::Power;
    MergeSettings merge;
    MetropolisSettings metropolis;
};

// Per-thread scratch subpaths, reused from sample to sample.
struct PathBuffers {
    Subpath light, camera;
};

// What every camera sample of one pass shares: the pass's stored light subpaths (its light
// phase, integrators/light_phase.h), the range search over them, and the MIS context with the
// pass's constants (N_L, merge radius and η: pass_constants.h). Read-only while the camera
// samples run.
struct Pass {
    uint64_t index = 0;                         // 0-based, over the whole render
    const LightStore* light = nullptr;          // set when the integrator has a light phase
    const LightVertexSearch* search = nullptr;  // set when it merges
    MisContext mis;
};

// Receives the contributions of one camera sample: the strategy and its result; t = 1
// connections carry the raster position to splat at, the others belong to the sample's own pixel.
class ContributionSink {
public:
    virtual ~ContributionSink() = default;
    virtual void add(Strategy strategy, const Connection& c) = 0;
};

class Integrator {
public:
    explicit Integrator(IntegratorSettings settings) : settings_(settings) {}
    virtual ~Integrator() = default;
    virtual std::string name() const = 0;
    virtual StrategySet strategies() const = 0;
    // The render: the loop over passes (render_loop.h) with this method's passes. By default,
    // passes of camera samples in tiles, each sample by sample() (render.cpp); mlt runs its chains.
    virtual RenderResult render(const Scene& scene, const RenderSettings& settings) const;
    // One sample for pixel `pixel` whose camera ray is `ray` (its raster position already jittered
    // inside the pixel, and its hit found when the render loop traced it in a packet). By default:
    // a camera walk; the splats of the pass's light paths that fall to this pixel's sample
    // (splatLightPaths); every enabled connection with t ≥ 2 with light path number pixel mod N_L
    // (an empty one without a light phase); and every merge with the pass's light vertices if
    // the integrator merges. What an integrator estimates is then its strategy set and its
    // settings; lt, which has no camera walk, overrides this.
    virtual void sample(const Scene& scene, const Pass& pass, int pixel, const CameraRay& ray, Rng& rng, PathBuffers& paths,
                        ContributionSink& sink) const;
    // Whether sample() traces the camera ray it is given (lt does not): the render loop then traces
    // neighbouring pixels' camera rays together.
    virtual bool tracesCameraRays() const { return true; }
    // Whether it renders with Markov chains (mlt: integrators/metropolis_render.h, its render())
    // rather than in passes of camera samples; sample() is then never called.
    virtual bool runsChains() const { return false; }
    const IntegratorSettings& settings() const { return settings_; }

    // Whether passes trace and store light subpaths first: for any strategy with s ≥ 2 or a merge.
    bool hasLightPhase() const { return !runsChains() && (strategies().merges() || strategies().maxS >= 2); }
    // N_L, the light paths each pass traces when it has a light phase: the settings' count, or one
    // per pixel. The one place that number is decided; the light phase puts it in the pass's
    // constants (pass_constants.h), which every kernel then reads.
    double lightPaths(const Scene& scene) const;
    // The first pass's merge radius r_1 (0 when the integrator does not merge). It may trace a
    // few hundred rays (the default measures pixels): compute it once per render.
    float firstMergeRadius(const Scene& scene) const;
    // The radius of 0-based pass `index` given r_1: the schedule r_1 · (index + 1)^((α−1)/2).
    float mergeRadius(float firstRadius, uint64_t index) const;
    // The MIS context of a pass with these constants.
    MisContext misContext(const PassConstants& constants) const;

protected:
    // The sample's camera subpath along `ray`, with the MIS running sums of
    // the pass's context where it keeps them.
    void cameraWalk(const Scene& scene, const Pass& pass, const CameraRay& ray, Rng& rng, Subpath& camera) const;
    // Runs every enabled connection with t ≥ firstT over the two subpaths into the sink.
    void connectAll(const Scene& scene, const Pass& pass, const SubpathView& light, const SubpathView& camera, int firstT,
                    Rng& rng, ContributionSink& sink) const {
        evaluateStrategies(scene, light, camera, firstT, rng, settings_.walk.maxDepth, pass.mis,
                           [&](Strategy st, const Connection& c) { sink.add(st, c); });
    }
    // The t = 1 connections (light tracing's splats) of the pass's light paths j = pixel,
    // pixel + P, pixel + 2P, … below N_L, P being the pixel count: every light path is joined to
    // the sensor `sensor` once per pass, whatever N_L, in the order of the pixels' samples (so the
    // film's sums do not depend on threads). Each draws what it needs from the pixel's stream.
    void splatLightPaths(const Scene& scene, const Pass& pass, int pixel, const SubpathView& sensor, Rng& rng,
                         ContributionSink& sink) const;
    // Runs every merge of the camera subpath with the pass's light vertices into the sink.
    void mergeAll(const Scene& scene, const Pass& pass, const Subpath& camera, ContributionSink& sink) const {
        evaluateMerges(scene, *pass.search, camera, settings_.walk.maxDepth, pass.mis,
                       [&](Strategy st, const Connection& c) { sink.add(st, c); });
    }

private:
    IntegratorSettings settings_;
};

// Where Russian roulette starts (WalkSettings::rrDepth) when the front end is not told, for the
// integrator of that name, decided by whether it has light subpaths; chosen by efficiency at equal
// time (bench/README.md, "Roulette start depth per integrator"). Without them (pt), the 3rd
// vertex: ending a camera path at its first hit loses the next-event estimates of the vertices it
// would have reached. With them, the 2nd (the first surface vertex of either subpath): the light
// subpaths carry that light too, and shorter subpaths cut the connections per sample.
int defaultRouletteDepth(const std::string& integrator);

inline const std::vector<std::string> kIntegratorNames{"pt", "lt", "bdpt", "vcm", "bpm", "ppm", "mlt"};

// One of kIntegratorNames; throws InputError for anything else.
std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const IntegratorSettings& settings);

}  // namespace tripath
