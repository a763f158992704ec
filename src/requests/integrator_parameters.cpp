// The table of the integrators' own parameters, and the texts made from it.
#include "requests/integrator_parameters.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <stdexcept>

namespace tripath {

namespace {

bool merges(const Integrator& i) { return i.strategies().merges(); }
bool chains(const Integrator& i) { return i.markovChains() != nullptr; }
bool playsRoulette(const Integrator& i) { return i.playsRoulette(); }
bool tracesLightPaths(const Integrator& i) { return i.hasLightPhase(); }
// Every method but mlt draws its paths in the render loop's passes; mlt's chains keep their own
// coordinates.
bool drawsPasses(const Integrator& i) { return i.markovChains() == nullptr; }
// Strategy images add up pixel samples per strategy: lt's one strategy per length, (k, 1), is its
// depth image; a method without pixel samples (mlt's chains weigh each strategy by where they
// wander rather than per pass) has none.
bool hasStrategies(const Integrator& i) { return i.name() != "lt" && i.pixelSamples() != nullptr; }

std::string none(const RenderRequest&) { return ""; }

const std::vector<IntegratorParameter> kParameters{
    {"rr-depth", "an integrator whose walks play Russian roulette",
     "Russian roulette starts once a subpath has this many vertices (default, measured at equal time: 3 for pt, 2 for "
     "the methods with light subpaths; auto's passes without light paths start one vertex later, as pt does; 0 also "
     "means the default)",
     playsRoulette, [](const RenderRequest& r) { return r.rrDepth > 0; }, none, true},
    {"radius", "an integrator that merges", "merge radius of the first pass in world units", merges,
     [](const RenderRequest& r) { return r.radiusGiven; }, none, true},
    {"radius-factor", "an integrator that merges",
     "merge radius of the first pass as a fraction of the scene's bounding-sphere radius", merges,
     [](const RenderRequest& r) { return r.radiusFactorGiven; }, none, true},
    {"radius-pixels", "an integrator that merges",
     "merge radius of the first pass in pixel widths on the surfaces the camera sees (the median over a grid of "
     "pixels); the default when neither radius nor radius-factor is given",
     merges, [](const RenderRequest& r) { return r.radiusPixelsGiven; },
     [](const RenderRequest& r) { return fmt::format("{}", r.merge.radiusPixels); }, true},
    {"alpha", "an integrator that merges",
     "the radius of pass i is r_1 * i^((alpha-1)/2); 1 keeps it fixed (biased), below 1 shrinks it (consistent)", merges,
     [](const RenderRequest& r) { return r.alphaGiven; }, [](const RenderRequest& r) { return fmt::format("{}", r.merge.alpha); },
     true},
    {"sampler", "an integrator of independent passes",
     "what the paths draw their numbers from: sobol (Owen-scrambled Sobol points, four dimensions per vertex and "
     "purpose, stratified over each pixel's passes and each light path's; the default: lower error at equal time "
     "for pt, bdpt, vcm and auto, docs/performance-notes.md) or independent (a random stream per sample; lt gains "
     "nothing from Sobol points but their cost). Both converge to the same image; the EXR records it "
     "(tripath:sampler)",
     drawsPasses, [](const RenderRequest& r) { return r.samplerGiven; },
     [](const RenderRequest& r) { return r.sampler; }, true},
    {"light-paths", "an integrator that traces light paths",
     "light paths traced per pass, N_L (default: one per pixel). Pixel i's camera sample connects with light path "
     "i mod N_L; each light path is joined to the sensor once per pass; splats, MIS weights and the merges' "
     "1/(pi r^2 N_L) count N_L. Converges to the same image, with other noise and cost",
     tracesLightPaths, [](const RenderRequest& r) { return r.lightPathsGiven; }, none, true},
    {"strategy-images", "an integrator with more than one strategy per path length in passes of samples",
     "also write <out>-s<S>-t<T>-weighted.exr and -unweighted.exr for every connection (s,t) the integrator has, of "
     "path length k <= this value (k = s+t-1; pt has (0,k+1) and (1,k)), and <out>-s<S>-t<T>-merge-*.exr for every "
     "merge (k = s+t-2)",
     hasStrategies, [](const RenderRequest& r) { return r.strategyImages > 0; }, none, false},
    {"bootstrap", "",
     "samples that estimate each path length's brightness b_k (which scales its part of the image) and start the "
     "chains, spread evenly over the lengths; written to the EXR with each b_k",
     chains, [](const RenderRequest& r) { return r.bootstrapGiven; },
     [](const RenderRequest& r) { return std::to_string(r.metropolis.bootstrap); }, true},
    {"chains", "",
     "Markov chains, shared among the path lengths in proportion to b_k (at most one per pixel); a pass takes about "
     "one step per pixel, spread over them, so spp counts steps per pixel",
     chains, [](const RenderRequest& r) { return r.chainsGiven; },
     [](const RenderRequest& r) { return std::to_string(r.metropolis.chains); }, true},
    {"large-step", "",
     "probability that a proposal draws a fresh point of primary sample space rather than moving the current one a "
     "little (a Gaussian step of 1/128 per coordinate)",
     chains, [](const RenderRequest& r) { return r.largeStepGiven; },
     [](const RenderRequest& r) { return fmt::format("{}", r.metropolis.largeStep); }, true},
};

}  // namespace

const std::vector<IntegratorParameter>& integratorParameters() { return kParameters; }

const IntegratorParameter& integratorParameter(const std::string& flag) {
    for (const IntegratorParameter& p : kParameters)
        if (p.flag == flag) return p;
    throw std::logic_error("no integrator parameter " + flag);
}

std::vector<std::string> usersOf(const IntegratorParameter& p) {
    std::vector<std::string> users;
    for (const std::string& name : kIntegratorNames)
        if (p.uses(*makeIntegrator(name, {}))) users.push_back(name);
    return users;
}

std::string describe(const IntegratorParameter& p) { return fmt::format("{}: {}", fmt::join(usersOf(p), ", "), p.help); }

std::string neededBy(const IntegratorParameter& p) {
    const std::vector<std::string> users = usersOf(p);
    std::string list = users.back();
    if (users.size() > 1) list = fmt::format("{} or {}", fmt::join(users.begin(), users.end() - 1, ", "), users.back());
    return *p.kind ? fmt::format("{} ({})", p.kind, list) : list;
}

}  // namespace tripath
