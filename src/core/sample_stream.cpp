#include "core/sample_stream.h"

namespace tripath {

std::optional<SamplerKind> samplerNamed(const std::string& name) {
    if (name == "independent") return SamplerKind::Independent;
    if (name == "sobol") return SamplerKind::Sobol;
    return std::nullopt;
}

}  // namespace tripath
