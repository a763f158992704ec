// lt — light tracing (particle tracing) with connections to the sensor.
//
// Builds a light subpath only; every vertex of it is connected to the pinhole (strategy t = 1)
// and splatted into the pixel it projects to. One light subpath is traced per camera sample, so a
// pass of N pixels traces N light paths. Parameters: --max-depth, --rr-depth (--mis has nothing to
// weigh: one strategy per path length). Cannot see emitters or paths through delta surfaces
// next to the sensor (a mirror seen directly is black), as it must.
#include "integrators/integrator.h"

namespace tripath {

class LightTracer final : public Integrator {
public:
    using Integrator::Integrator;
    std::string name() const override { return "lt"; }
    StrategySet strategies() const override { return {StrategySet::Kind::LightTracing}; }
    void sample(const Scene& scene, Vec2, Rng& rng, PathBuffers& paths, ContributionSink& sink) const override {
        lightSubpath(scene, rng, settings().walk, strategies().lightWalkPdfs(), paths.light);
        paths.camera.assign(1, sensorVertex(scene));
        connectAll(scene, paths, rng, sink);
    }
};

std::unique_ptr<Integrator> makeLightTracer(const IntegratorSettings& s) { return std::make_unique<LightTracer>(s); }

}  // namespace tripath
