// lt — light tracing (particle tracing) with connections to the sensor.
//
// Connects every vertex of the pass's light subpaths (the light phase: N_L of them, one per pixel
// by default) to the pinhole (strategy t = 1) and splats it into the pixel it projects to; pixel
// i's sample joins light paths i, i + P, … (P pixels). Parameters: --max-depth, --rr-depth
// (default 2), --light-paths (--mis has nothing to weigh: one strategy per path length). Cannot see
// emitters or paths through delta surfaces next to the sensor (a mirror seen directly is black),
// as it must.
#include "integrators/pixel_sample_integrator.h"

namespace tripath {

class LightTracer final : public PixelSampleIntegrator {
public:
    using PixelSampleIntegrator::PixelSampleIntegrator;
    std::string name() const override { return "lt"; }
    // No strategy with t ≥ 2: each camera sample is the sensor alone and its splats (sample()).
    StrategySet strategies() const override { return {.maxT = 1}; }
};

std::unique_ptr<Integrator> makeLightTracer(const IntegratorSettings& s) { return std::make_unique<LightTracer>(s); }

}  // namespace tripath
