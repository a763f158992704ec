// How auto chooses the plans of its next passes (pass_plan.h): the candidates, what a pass of each
// costs, and the choice, tile by tile, from the moments the passes before measured.
//
// A candidate is a number of light paths N_L and the classes a tile runs with them. Its
// efficiency is its relative error times its cost (Grittmann et al. 2022), the error taken as the
// variance of a pixel's estimate per pass, as relMSE takes it. The estimate is the sum of the
// pixel's camera sample's contributions X_i and of the splats that land in it, each weighed by
// the balance heuristic over the candidate's classes. The measuring passes give (plan_moments.h)
// the diagonal of its square, ∫ f² / Σ n'_i p_i, and the cross terms of the camera sample's
// contributions, whose strategies share the camera subpath's throughput: without them the merges
// with many light vertices, and more light paths, look far better than they render. The camera
// sample's squared mean is taken out; the splats, from light paths independent of the camera
// sample and of one another, add only products of means, which the variance leaves out. (The
// second moment itself, the paper's measure, counts each pixel's squared mean in every candidate
// but for the part light tracing carries: on contact every candidate whose camera samples carry
// the mean read 2.3-4.4× its variance, light tracing alone 0.97×.)
// Relative as the benchmark's relMSE is (evaluation/metrics.h): each pixel's share over its
// squared mean plus 0.01 (plan_moments.h), so that a bright pixel does not outvote a dark one,
// nor a black one count infinitely; averaged over the image. Its cost is a pass's work in units
// of a traced ray, from counts a survey of the scene gives before the first pass (traced from
// fixed streams, so that the choice is the same on every run, thread count and rank count): the
// light paths' vertices, their joins to the sensor and their places in the merge grid, shared by
// the image; and each tile's camera vertices, next-event estimates, connections, merge searches
// and merges.
//
// The choice: for each N_L, and with light tracing in every tile or in none, every tile starts
// with every class it may run, then takes in turn, sweep after sweep, the classes that least make
// the image's relative variance times its cost, until no tile changes; the best of those is the
// plan. Light tracing is all tiles' or none's: once the light paths join the sensor, a tile's
// splats cost it nothing, and a tile that dropped them on a variance measured without the rare
// path only they sample well (a caustic seen where the measuring passes found none) showed it as
// a firefly (caustic, 128²: one tile of 64 held 60-74 % of two runs' error). A tile never runs
// classes that cannot sample a path some pass found light on in it: it would lose that light.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "integrators/pass_plan.h"

namespace tripath {

// The relMSE's offset of a pixel's squared mean (evaluation/metrics.h): a black pixel's error
// counts as absolute.
inline constexpr double kRelativeOffset = 1e-2;

// The candidates a tile chooses among, for an image of `pixels` pixels: path tracing alone, and
// with N_L of a quarter, one or four light paths per pixel every non-empty set of classes.
std::vector<PassPlan> candidatePlans(double pixels);

// The plan's name: "N_L=1/px connect+trace+merge", "pt".
std::string planName(const PassPlan& plan, double pixels);

// What a pass does, as counts a survey measured (plan_choice.cpp's relative costs weigh them).
struct PassWork {
    double cameraVertices = 0;  // per camera subpath, the sensor excluded
    double lightVertices = 0;   // per light subpath, y0 included
    double mergesPerQuery = 0;  // light vertices found by a merge search, per light path of the pass
};

// The cost of one pass of `plan` over `pixels` pixels, in traced rays: in every tile alike.
double passCost(const PassPlan& plan, const PassWork& work, double pixels);

// What the choice reads, per tile of the image (in the order the moments were kept): its pixels,
// and per candidate the tile's relative variance per pass (its pixels' shares weighed as
// plan_moments.h says) and whether a pass found light in the tile on a path the candidate cannot
// sample.
struct PlanEvidence {
    std::vector<int> tilePixels;                 // pixels in the tile
    std::vector<std::vector<double>> variances;  // [candidate][tile]: Σ_p V_p / (I_p² + 0.01), per pass
    std::vector<std::vector<bool>> uncovered;    // [candidate][tile]
};

// Each candidate's relative variance per pass in each tile, as its share of the image's
// average ([candidate][tile], see the top of this file).
std::vector<std::vector<double>> relativeVariances(const PlanEvidence& evidence);

// A choice: the candidate of each tile (all of one N_L), and the image's relative variance and
// cost per pass under it.
struct PlanChoice {
    std::vector<size_t> tiles;
    double relativeVariance = 0, cost = 0;
};

// The plans of least relative variance × cost (see the top of this file); `fallback` in every tile
// when no choice samples every path seen.
PlanChoice choosePlans(const std::vector<std::vector<double>>& relativeVariance, const PlanEvidence& evidence,
                       const std::vector<PassPlan>& candidates, const PassWork& work, size_t fallback);

}  // namespace tripath
