// An integrator is a choice of subpaths and of strategies over the path core (src/paths).
// Each one lives in its own file with its parameters documented at the top.
#pragma once
#include <memory>
#include <string>

#include "paths/strategies.h"

namespace tripath {

struct IntegratorSettings {
    WalkSettings walk;
    MisHeuristic mis = MisHeuristic::Power;
};

// Per-thread scratch subpaths, reused from sample to sample.
struct PathBuffers {
    Subpath light, camera;
};

// Receives the contributions of one camera sample: (s, t) and the connection; t = 1 connections
// carry the raster position to splat at, the others belong to the sample's own pixel.
class ContributionSink {
public:
    virtual ~ContributionSink() = default;
    virtual void add(int s, int t, const Connection& c) = 0;
};

class Integrator {
public:
    explicit Integrator(IntegratorSettings settings) : settings_(settings) {}
    virtual ~Integrator() = default;
    virtual std::string name() const = 0;
    virtual StrategySet strategies() const = 0;
    // One sample for the pixel at raster position `raster` (already jittered inside the pixel).
    virtual void sample(const Scene& scene, Vec2 raster, Rng& rng, PathBuffers& paths, ContributionSink& sink) const = 0;
    const IntegratorSettings& settings() const { return settings_; }

protected:
    // Runs every enabled strategy over the two subpaths into the sink.
    void connectAll(const Scene& scene, PathBuffers& paths, Rng& rng, ContributionSink& sink) const {
        const MisContext mis{settings_.mis, strategies(), Roulette{settings_.walk.rrDepth}};
        evaluateStrategies(scene, paths.light, paths.camera, rng, settings_.walk.maxDepth, mis,
                           [&](int s, int t, const Connection& c) { sink.add(s, t, c); });
    }

private:
    IntegratorSettings settings_;
};

// "pt", "lt" or "bdpt"; throws InputError for anything else.
std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const IntegratorSettings& settings);

}  // namespace tripath
