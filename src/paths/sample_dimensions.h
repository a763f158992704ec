// Where a path's draws lie among a sampler's dimensions (core/sample_stream.h): sets of four, one
// per purpose and vertex, fixed in advance, so that a longer subpath never shifts an earlier
// vertex's numbers and a strategy's numbers do not depend on which others ran. Camera samples and
// light paths are streams of their own: their sets are numbered apart. A point on a surface or a
// direction takes the set's best stratified pair, dimensions 0 and 1 (core/rng.h's DimensionSet).
#pragma once
#include "core/rng.h"

namespace tripath::dimensions {

// A camera sample: set 0 jitters the point in the pixel (2 numbers); each camera vertex z_v,
// v ≥ 1, has a set for its scattering (the BSDF's direction 2, its lobe 1, Russian roulette 1)
// and one for the next-event estimate from it (the emitter 1, then its point 2).
inline constexpr DimensionSet kPixel{0, 0};
constexpr DimensionSet cameraScatter(int v) { return {2 * uint32_t(v) - 1, 0}; }
constexpr DimensionSet nextEvent(int v) { return {2 * uint32_t(v), 3}; }

// A light path: set 0 places its start, the point on the emitter (2) and the direction it emits
// in (2), so that its starts, pass after pass, are stratified in the four dimensions its first hit
// depends on; set 1 chooses the emitter (1) and the emission's lobe (1); each light vertex y_v,
// v ≥ 1, has a set for its scattering (as a camera vertex's).
inline constexpr DimensionSet kEmitterPoint{0, 0};
inline constexpr DimensionSet kEmissionDirection{0, 2};
inline constexpr DimensionSet kEmitterChoice{1, 0};
inline constexpr DimensionSet kEmissionLobe{1, 1};
constexpr DimensionSet lightScatter(int v) { return {uint32_t(v) + 1, 0}; }

}  // namespace tripath::dimensions
