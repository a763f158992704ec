// The target of multiplexed Metropolis light transport (Hachisuka et al. 2014): a point u of
// primary sample space (primary_samples.h) and a path length k give one path and one strategy,
//     C_k(u) = (k + 1) · w_{s,t}(x̄) · f(x̄) / p_{s,t}(x̄),
// where (s, t), s + t = k + 1, is chosen uniformly among the k + 1 connection strategies by u's
// first strategy coordinate, x̄ is the path the walks and the connection of (s, t) draw from u, and
// w is the one MIS weight of docs/design.md §1 among all of them. The walks, the connection and
// the weight are those bdpt runs; only the numbers they read come from u. Since (s, t) is picked
// with probability 1/(k + 1) and the weights of a path sum to one, E_u[C_k(u) · h_j] is the
// length-k part of pixel j's value, h_j being 1 where the path lands in pixel j.
//
// The pdfs are over the whole image: the camera walk draws its raster position uniformly over the
// film, so p_{s,t} of a camera strategy is the per-pixel pdf the camera gives over the P pixels,
// and C is P times the per-pixel estimate of connect(). A t = 1 strategy's connection is already
// an estimate over the image (a splat counts 1/N_L of it per light path: with one light path per
// camera sample, N_L = P, as the MIS context says). Walks play no roulette: a chain's path length
// is fixed, and a path cut short is a proposal of value 0.
#pragma once
#include "paths/connect.h"
#include "paths/primary_samples.h"

namespace tripath {

class Scene;

// What every evaluation of one render shares.
struct MultiplexedTarget {
    const Scene* scene = nullptr;
    MisContext mis;     // every connection strategy, no roulette, N_L = P
    double pixels = 0;  // P
};

// C_k(u) and where it lands.
struct PathSample {
    Spectrum value{0.0f};
    Vec2 raster;     // on the film, in pixels
    Strategy strategy;
    bool weightGuarded = false;  // the connection's MIS weight was guarded to 0 (mis.h)
    // The scalar the chain's stationary density is proportional to.
    float luminance() const { return tripath::luminance(value); }
};

// The walks' scratch subpaths.
struct TargetPaths {
    Subpath light, camera;
};

// The MIS context of the target over a film of `pixels` pixels (no roulette, every connection).
MisContext multiplexedMisContext(MisHeuristic heuristic, double pixels);

// Evaluates C_k at the point `u` holds for its current proposal: a value of 0 where the walks end
// before the strategy's subpaths are whole, where the connection carries nothing, or where a
// weight was guarded (mis.h).
PathSample evaluateTarget(const MultiplexedTarget& target, int k, PrimarySamples& u, TargetPaths& paths);

}  // namespace tripath
