#include "integrators/integrator.h"

#include "geometry/error.h"

namespace tripath {

std::unique_ptr<Integrator> makePathTracer(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeLightTracer(const IntegratorSettings& s);
std::unique_ptr<Integrator> makeBidirectional(const IntegratorSettings& s);

std::unique_ptr<Integrator> makeIntegrator(const std::string& name, const IntegratorSettings& settings) {
    if (name == "pt") return makePathTracer(settings);
    if (name == "lt") return makeLightTracer(settings);
    if (name == "bdpt") return makeBidirectional(settings);
    throw InputError("unknown integrator '" + name + "' (pt, lt or bdpt)");
}

}  // namespace tripath
