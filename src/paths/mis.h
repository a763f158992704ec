// Multiple importance sampling over the strategies an integrator enables (DESIGN.md §1).
//
// A full path x0 … xk can be produced by strategy (s, t): s vertices from the light, t from the
// camera, s + t = k + 1. With p_i the pdf of strategy (i, k+1−i), the balance heuristic weight of
// (s,t) is p_s / Σ_i p_i over the ENABLED strategies that can sample the path. The ratios
// p_i / p_s follow from the per-vertex area pdfs alone: moving one vertex from the camera side to
// the light side multiplies the pdf by pdfRev / pdfFwd of that vertex (Veach §10.2), so
//     p_{s+1} / p_s = pdfFwd-by-light(x_s) / pdfFwd-by-camera(x_s)
// and so on outward. A strategy that would connect at a delta vertex (mirror, glass), or hit a
// point light, has p_i = 0 and drops out; so does every strategy the integrator disabled.
//
// Cost: O(k) per connection. Paths here are short (Russian roulette, max depth), the loop is a few
// multiplies per vertex with no ray casts, and it lets any subset of strategies be enabled, which
// the running-sum form of Georgiev et al. cannot; bench/ measures it against path length.
#pragma once
#include <span>
#include <string>

#include "paths/vertex.h"

namespace tripath {

enum class MisHeuristic { Balance, Power, Uniform };
MisHeuristic parseMisHeuristic(const std::string& name);  // "balance" | "power" | "none"

// The strategies an integrator switches on.
struct StrategySet {
    enum class Kind { PathTracing, LightTracing, Bidirectional };
    Kind kind = Kind::Bidirectional;
    // PT: s = 0 (hit an emitter) and s = 1 (next-event estimation). LT: t = 1 (connect to the
    // sensor). BDPT: every (s, t). t = 0 is impossible with a pinhole and never enabled.
    bool enabled(int s, int t) const {
        if (t < 1) return false;
        switch (kind) {
            case Kind::PathTracing: return s <= 1;
            case Kind::LightTracing: return t == 1;
            case Kind::Bidirectional: return true;
        }
        return false;
    }
};

// Weight of strategy (s, t) for the path light[0..s) + camera[0..t) reversed. The endpoints'
// pdfRev (and their neighbours') must already describe this connection (see connect.cpp).
float misWeight(std::span<const Vertex> light, int s, std::span<const Vertex> camera, int t, MisHeuristic heuristic,
                StrategySet strategies);

}  // namespace tripath
