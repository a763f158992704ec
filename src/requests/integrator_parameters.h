// The parameters that only some integrators use, each documented here once. The command line's
// --help, Python's render() docstring and the refusal of a parameter that the integrator would
// ignore are all made from this table, and which integrators use a parameter is asked of the
// integrators themselves, so that the help never names one that ignores it.
#pragma once
#include <string>
#include <vector>

#include "requests/render_request.h"

namespace tripath {

struct IntegratorParameter {
    const char* flag;  // "radius-pixels"; Python's keyword is the same with '_'
    const char* kind;  // who uses it, in words ("an integrator that merges"); empty: the list of names says it
    const char* help;  // what it does
    bool (*uses)(const Integrator&);
    bool (*given)(const RenderRequest&);
    std::string (*shownDefault)(const RenderRequest&);  // as --help shows it; empty: none, or the help says it
    bool keyword;  // Python takes it among render()'s keyword options (else as a named argument)
};

const std::vector<IntegratorParameter>& integratorParameters();
// The entry of `flag`; std::logic_error for a flag that is not in the table.
const IntegratorParameter& integratorParameter(const std::string& flag);

// The integrators that use the parameter, in kIntegratorNames' order.
std::vector<std::string> usersOf(const IntegratorParameter& p);
// "vcm, bpm, ppm: <help>": the parameter's help for --help and docstrings.
std::string describe(const IntegratorParameter& p);
// What the parameter needs, for the refusal: "an integrator that merges (vcm, bpm or ppm)", "mlt".
std::string neededBy(const IntegratorParameter& p);

}  // namespace tripath
