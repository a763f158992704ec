// An integrator is a choice of subpaths and of strategies over the path core (src/paths), and a
// way to render with them. This file holds what every method has: its settings, the base class
// the front ends see, and the factory. The methods that render passes of camera samples share
// more (pixel_sample_integrator.h). Each method lives in its own file with its parameters
// documented at the top.
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
    std::optional<int64_t> lightPaths;  // N_L, the light paths per pass, as given (PixelSampleIntegrator::lightPaths)
    MisHeuristic mis = MisHeuristic::Power;
    MergeSettings merge;
    MetropolisSettings metropolis;
};

class PixelSampleIntegrator;

// A method: its name, strategies and settings, and its render. How it renders is its own: passes
// of camera samples (pixel_sample_integrator.h: pt, lt, bdpt, vcm, bpm, ppm) or Markov chains
// (mlt: metropolis_render.h). What the front ends need to know of a method -- which parameters
// apply, what the EXR records, what memory it takes, whether a sample can be replayed -- they ask
// through the questions below, which say what the method does rather than which one it is.
class Integrator {
public:
    explicit Integrator(IntegratorSettings settings) : settings_(settings) {}
    virtual ~Integrator() = default;
    virtual std::string name() const = 0;
    virtual StrategySet strategies() const = 0;
    const IntegratorSettings& settings() const { return settings_; }
    // The render: the loop over passes (render_loop.h) with this method's passes.
    virtual RenderResult render(const Scene& scene, const RenderSettings& settings) const = 0;

    // Itself as a method of passes of camera samples, whose pixel samples can be replayed and
    // whose passes run a light phase (light_phase.h); nullptr for a method that renders otherwise.
    virtual const PixelSampleIntegrator* pixelSamples() const { return nullptr; }
    // Passes like the largest it renders, for the memory they take (memory_estimate.h): by
    // default none; auto's plan of the most light paths (a method of pixel samples is its own).
    virtual std::unique_ptr<PixelSampleIntegrator> largestPasses(const Scene& scene) const;
    // Whether its walks play Russian roulette (WalkSettings::rrDepth: --rr-depth applies).
    virtual bool playsRoulette() const = 0;
    // Whether its passes trace and store light subpaths before their camera samples, in a light
    // phase (light_phase.h: --light-paths applies).
    virtual bool hasLightPhase() const { return false; }
    // The settings of the Markov chains it renders with (metropolis_render.h: --bootstrap, --chains
    // and --large-step apply); nullptr for a method without chains.
    virtual const MetropolisSettings* markovChains() const { return nullptr; }

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

inline const std::vector<std::string> kIntegratorNames{"pt", "lt", "bdpt", "vcm", "bpm", "ppm", "mlt", "auto"};

// One of kIntegratorNames; throws InputError for anything else.
std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const IntegratorSettings& settings);

}  // namespace tripath
