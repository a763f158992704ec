// vcm — vertex connection and merging (Georgiev, Křivánek, Davidovič, Slusallek 2012).
//
// Everything bdpt does -- every connection (s, t) of the camera subpath with the pass's light
// subpath of its index (modulo N_L) -- and, at every non-delta camera vertex, a merge with every stored
// light vertex of the pass within the merge radius (paths/merge.h). One MIS weighs connections and
// merges together (paths/mis.h), so merging takes over where connections are poor: caustics seen
// through mirrors or glass (specular-diffuse-specular paths), which no connection can sample.
// Parameters: --max-depth, --rr-depth (default 2), --mis, and the radius schedule --radius or
// --radius-factor with --alpha (integrator.h), --light-paths (N_L per pass; one per pixel by
// default). Biased for a fixed radius (α = 1); consistent for
// α < 1, the bias shrinking with the radius.
#include "integrators/pixel_sample_integrator.h"

namespace tripath {

class VertexConnectionMerging final : public PixelSampleIntegrator {
public:
    using PixelSampleIntegrator::PixelSampleIntegrator;
    std::string name() const override { return "vcm"; }
    StrategySet strategies() const override { return {.merging = StrategySet::Merging::EveryVertex}; }
};

std::unique_ptr<Integrator> makeVertexMerging(const IntegratorSettings& s) {
    return std::make_unique<VertexConnectionMerging>(s);
}

}  // namespace tripath
