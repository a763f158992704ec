// The environment a front end asks for: `--environment FILE|R,G,B` and `--environment-scale S` on
// the command line, `environment=` and `environment_scale=` in Python. A file is an
// equirectangular map that OpenImageIO reads (.exr, .hdr, ...), its values linear radiance in the
// units of the output pixels; three numbers are a constant radiance. The convention that maps a
// direction to a texel is geometry/environment.h's.
#pragma once
#include <string>

#include "geometry/scene_desc.h"
#include "core/warnings.h"

namespace tripath {

// The largest map read: 32768 × 16384 texels (a header that claims more is refused unread).
inline constexpr size_t kMaxEnvironmentTexels = size_t(32768) * 16384;

// The map or constant `spec` names, times `scale`. InputError, one line, for a file that cannot be
// read or is too large (more than `maxTexels`: the fuzz target, whose memory is bounded, takes
// fewer), a non-finite or negative texel or constant, or a scale that is not a finite non-negative
// number; a warning for a map that is not twice as wide as it is high. Its hash is of the texels or
// the constant as read, before the scale.
EnvironmentDesc loadEnvironment(const std::string& spec, float scale, const WarningSink& warn = printWarning,
                                size_t maxTexels = kMaxEnvironmentTexels);

}  // namespace tripath
