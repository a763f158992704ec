// ppm — progressive photon mapping (Hachisuka, Ogaki, Jensen 2008), in its per-pass form with a
// shrinking radius (Knaus and Zwicker 2011).
//
// The camera walk follows delta surfaces (mirrors, glass) to its first non-delta vertex and stops
// there; that vertex merges with every stored light vertex of the pass within the merge radius
// (paths/merge.h). Emitters seen directly or through deltas count through s = 0. Each path has
// exactly one strategy, so there is nothing to weigh (--mis has no effect). Parameters:
// --max-depth, --rr-depth (default 2), --radius or --radius-factor, --alpha, --light-paths. Biased
// for a fixed radius; consistent for α < 1. All indirect light comes from the density estimate,
// blur included.
#include "integrators/pixel_sample_integrator.h"

namespace tripath {

class ProgressivePhotonMapping final : public PixelSampleIntegrator {
public:
    explicit ProgressivePhotonMapping(IntegratorSettings s) : PixelSampleIntegrator(firstHit(s)) {}
    std::string name() const override { return "ppm"; }
    StrategySet strategies() const override { return {.maxS = 0, .minT = 2, .merging = StrategySet::Merging::FirstNonDelta}; }

private:
    static IntegratorSettings firstHit(IntegratorSettings s) {
        s.walk.cameraUntilNonDelta = true;
        return s;
    }
};

std::unique_ptr<Integrator> makeProgressivePhotonMapping(const IntegratorSettings& s) {
    return std::make_unique<ProgressivePhotonMapping>(s);
}

}  // namespace tripath
