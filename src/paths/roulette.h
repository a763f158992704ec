// Russian roulette: where a random walk may end, and with which probability it goes on.
//
// A walk plays roulette at each of its vertices from index depth − 1 on (once it holds `depth`
// vertices; index 0, the sensor or the emitter point, never plays). It continues from surface
// vertex v with probability q(v), which depends on v's material alone: a bound on how much the
// BSDF can reflect (the albedo of a Lambertian or mirror surface; 1 for glass, smooth or rough,
// whose tint only colours transmission and whose 1/η² radiance scaling undoes itself on the way
// out; 1 for the rough lobes, whose Fresnel term reaches 1 at grazing angles), capped at
// kMaxContinuation on non-delta surfaces so that even albedo-1 diffuse scenes end their paths.
//
// Because q(v) ignores the direction of travel, a walk from either end that reaches v at walk
// index j continues with the same q(v) whenever j is past the start depth: the pdf of generating
// a vertex includes the continuation factor of the vertex that generated it, for forward and
// reverse pdfs alike, and MIS weighs strategies with the pdfs their walks really have
// (misWeight applies the factor with each generator's index in the walk of that strategy).
#pragma once
#include <algorithm>

#include "paths/vertex.h"

namespace tripath {

inline constexpr float kMaxContinuation = 0.95f;

inline float continuationProbability(const Material& m) {
    const bool albedoBounds = m.type == MaterialType::Lambertian || m.type == MaterialType::Mirror;
    const float bound = albedoBounds ? maxComponent(m.albedo) : 1.0f;
    // Mirrors and glass are exempt from the cap: they never end a path that carries light through
    // them (a caustic seen through a glass sphere crosses it four times; capped at 0.95, each such
    // path would be 1/0.95⁴ brighter and 19 % rarer). Paths between perfect mirrors still end, at
    // --max-depth.
    return std::min(isDelta(m) ? 1.0f : kMaxContinuation, bound);
}

struct Roulette {
    int depth = 3;  // roulette once a walk holds this many vertices (--rr-depth)
    // Probability that a walk goes on from v, its vertex number `index` (0 for its first vertex).
    // v.continuation holds continuationProbability of its material, set when the walk found it.
    float continuation(const Vertex& v, int index) const {
        return index >= 1 && index + 1 >= depth ? v.continuation : 1.0f;
    }
};

}  // namespace tripath
