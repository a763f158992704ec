// The factory that makes a method from its name, and the roulette default that asks it (integrator.h).
#include "integrators/integrator.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.h"

namespace tripath {

std::unique_ptr<Integrator> makePathTracer(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeLightTracer(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeBidirectional(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeVertexMerging(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeBidirectionalPhotonMapping(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeProgressivePhotonMapping(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeMetropolis(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeAuto(const IntegratorSettings& s);

std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const IntegratorSettings& settings) {
    if (name == "pt") return makePathTracer(settings);
    if (name == "lt") return makeLightTracer(settings);
    if (name == "bdpt") return makeBidirectional(settings);
    if (name == "vcm") return makeVertexMerging(settings);
    if (name == "bpm") return makeBidirectionalPhotonMapping(settings);
    if (name == "ppm") return makeProgressivePhotonMapping(settings);
    if (name == "mlt") return makeMetropolis(settings);
    if (name == "auto") return makeAuto(settings);
    throw InputError(fmt::format("unknown integrator '{}' ({})", name.substr(0, 40), fmt::join(kIntegratorNames, ", ")));
}

int defaultRouletteDepth(const std::string& integrator) {
    return makeIntegrator(integrator, {})->hasLightPhase() ? 2 : 3;  // the rule, not a list of names
}

}  // namespace tripath
