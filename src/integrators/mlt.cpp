// mlt — multiplexed Metropolis light transport (Hachisuka, Kaplanyan and Dachsbacher 2014) in
// primary sample space (Kelemen et al. 2002).
//
// Markov chains, each over the paths of one length k, move points of primary sample space that
// the walks of bdpt read in place of random numbers; a point also chooses which of the k + 1
// connections (s, t) builds its path, and the chain's target is that connection's MIS-weighted
// contribution times k + 1 (paths/multiplexed_target.h). Chains go where the image is bright
// and stay on paths that independent samples rarely find: light through a gap, caustics seen
// in a mirror. Their noise is correlated and uneven: dark regions converge slowly.
// Parameters: --max-depth, --mis (the weights among the connections), --bootstrap (N, the samples
// that estimate each length's brightness and seed the chains; default 100 000), --chains (default
// 1024, at most one per pixel), --large-step (the probability of a proposal that draws a fresh
// point; default 0.3). --spp counts steps per pixel: a pass takes about one step per pixel,
// spread over the chains; --rr-depth and --light-paths do not apply (the chains' walks play no
// roulette, and every proposal makes one path). Its passes are integrators/metropolis_render.h;
// the design, docs/design.md §1.2.
#include "integrators/metropolis_render.h"

namespace tripath {

class MetropolisLightTransport final : public Integrator {
public:
    using Integrator::Integrator;
    std::string name() const override { return "mlt"; }
    StrategySet strategies() const override { return {}; }
    RenderResult render(const Scene& scene, const RenderSettings& settings) const override {
        return renderMetropolis(scene, *this, settings);
    }
    bool playsRoulette() const override { return false; }
    const MetropolisSettings* markovChains() const override { return &settings().metropolis; }
};

std::unique_ptr<Integrator> makeMetropolis(const IntegratorSettings& s) {
    return std::make_unique<MetropolisLightTransport>(s);
}

}  // namespace tripath
