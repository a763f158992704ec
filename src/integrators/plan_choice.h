// How auto chooses the plan of its next passes (pass_plan.h): the candidates, what a pass of each
// costs, and the choice from the moments the passes before measured.
//
// A candidate's efficiency is its relative variance times its cost (Grittmann et al. 2022). Its
// balance-heuristic estimator's variance in a pixel, per pass, is Σ_t (1/n_t) Var[w_t f / p_t]:
// its second moment ∫ f² / Σ n'_i p_i (measured, pass_plan.h) less Σ_t μ_t² / n_t, μ_t the part
// of the pixel's mean that technique class t takes under the candidate's weights and n_t its
// samples per pixel (N_L / pixels for light tracing, one for the camera walk's strategies and the
// connections; the merges' part is not subtracted, a merge summing over every light vertex within
// its radius), and at least a thousandth of the moment (a difference of two estimates, it can
// come out below 0 where the variance is small). A tile keeps its classes' means; each pixel is
// taken to share them as the tile does, so Σ_p μ_t,p² is the tile's Σ_p I_p² times class t's
// share squared. Relative: over the tile's squared mean, so that a bright tile does not outvote a
// dark one; summed over the render's tiles. Its cost is a pass's work in units of a traced ray,
// from counts a survey of the scene gives before the first pass (traced from fixed streams, so
// that the choice is the same on every run, thread count and rank count): camera and light
// vertices, connections, joins to the sensor, merge searches and merges. A candidate that cannot
// sample a path some pass found light on is never chosen: it would lose that light.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "integrators/pass_plan.h"

namespace tripath {

// The plans auto chooses among, for an image of `pixels` pixels: path tracing alone, and with N_L
// of a quarter, one or four light paths per pixel, every non-empty choice of the other classes.
std::vector<PassPlan> candidatePlans(double pixels);

// The plan's name as the output shows it, e.g. "N_L=1/px connect+trace+merge", "pt".
std::string planName(const PassPlan& plan, double pixels);

// What a pass does, as counts a survey measured (plan_choice.cpp's relative costs weigh them).
struct PassWork {
    double cameraVertices = 0;  // per camera subpath, the sensor excluded
    double lightVertices = 0;   // per light subpath, y0 included
    double mergesPerQuery = 0;  // light vertices found by a merge search, per light path of the pass
};

// The cost of one pass of `plan` over `pixels` pixels, in traced rays.
double passCost(const PassPlan& plan, const PassWork& work, double pixels);

// What the choice reads, per tile of the image (in the order the moments were kept): the sum of
// its pixels' means and of their squares, and per candidate the tile's moment and means by class
// per pass. Also, per candidate, whether any pass found light on a path it cannot sample.
struct PlanEvidence {
    std::vector<double> tileMean;                        // Σ_p I_p over the tile's pixels
    std::vector<double> tileMeanSquares;                 // Σ_p I_p²
    std::vector<int> tilePixels;                         // pixels in the tile
    std::vector<std::vector<double>> moments;            // [candidate][tile]: Σ_p M_p, per pass
    std::vector<std::vector<TechniqueSums>> classMeans;  // [candidate][tile]: Σ_p μ_t,p, per pass
    std::vector<bool> uncovered;                         // [candidate]
};

// A plan's samples of each class per pixel and pass, over an image of `pixels` pixels.
TechniqueSums samplesPerPixel(const PassPlan& plan, double pixels);

// Each candidate's relative variance per pass, summed over the tiles (see the top of this file);
// `samples[k]` is candidate k's samplesPerPixel.
std::vector<double> relativeVariances(const PlanEvidence& evidence, const std::vector<TechniqueSums>& samples);

// The index of the candidate of least relative variance × cost among those that sample every
// path seen; `fallback` when none does or nothing was seen.
size_t choosePlan(const std::vector<double>& relativeVariance, const std::vector<double>& cost,
                  const std::vector<bool>& uncovered, size_t fallback);

}  // namespace tripath
