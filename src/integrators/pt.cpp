// pt — path tracing with next-event estimation.
//
// Builds a camera subpath only (no light phase). Strategies: s = 0 (the walk hits an emitter)
// and s = 1 (an emitter point sampled at each camera vertex on a surface, t ≥ 2), weighted
// against each other by MIS. No splats: joining an emitter point straight to the sensor (1, 1)
// is light tracing's. Parameters: --max-depth, --rr-depth (default 3), --mis. Cannot sample
// paths that reach a point light by way of a delta surface (point-light caustics): those stay
// black, as they must.
#include "integrators/pixel_sample_integrator.h"

namespace tripath {

class PathTracer final : public PixelSampleIntegrator {
public:
    using PixelSampleIntegrator::PixelSampleIntegrator;
    std::string name() const override { return "pt"; }
    StrategySet strategies() const override { return {.maxS = 1, .minT = 2}; }
};

std::unique_ptr<Integrator> makePathTracer(const IntegratorSettings& s) { return std::make_unique<PathTracer>(s); }

}  // namespace tripath
