// bpm — bidirectional photon mapping (Vorba 2011; the merging half of VCM).
//
// At every non-delta camera vertex, merges with every stored light vertex of the pass within the
// merge radius (paths/merge.h); emitters the camera walk hits count through s = 0. MIS weighs the
// merges at the different vertices of a path, and s = 0, against each other: no shadow-ray
// connections at all. Parameters: --max-depth, --rr-depth (default 2), --mis, --radius or
// --radius-factor, --alpha, --light-paths (N_L, one per pixel by default). Biased for a fixed
// radius; consistent for α < 1. Direct light comes from merges alone, so it is noisier than any
// method with next-event estimation.
#include "integrators/pixel_sample_integrator.h"

namespace tripath {

class BidirectionalPhotonMapping final : public PixelSampleIntegrator {
public:
    using PixelSampleIntegrator::PixelSampleIntegrator;
    std::string name() const override { return "bpm"; }
    StrategySet strategies() const override { return {.maxS = 0, .minT = 2, .merging = StrategySet::Merging::EveryVertex}; }
};

std::unique_ptr<Integrator> makeBidirectionalPhotonMapping(const IntegratorSettings& s) {
    return std::make_unique<BidirectionalPhotonMapping>(s);
}

}  // namespace tripath
