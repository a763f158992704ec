#include "integrators/plan_choice.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <string_view>

namespace tripath {

namespace {

// What each operation costs, in units where a camera vertex with its next-event estimate (its ray,
// its BSDF sample, an emitter point, a shadow ray, two BSDF values) is 2.5: a light vertex (its
// ray, its BSDF sample, its place in the store) 2.0, a connection (a shadow ray, two BSDF values,
// the weight) 1.5, a join to the sensor 1.0, a merge (a BSDF value and the weight) 1.45. Fitted
// by least squares to the instructions (cachegrind) that pt, lt, bdpt, vcm and bpm spent on
// cornell, veach-mis, lamp-caustic, caustic and degenerate (32², four passes, one thread) against
// their counts of each event (--stats): the fit gives every run's count within 0.8-1.4×, lt's on
// caustic 2×. A merge search and a light vertex's place in the grid did not separate from the
// rest in that fit, nor a camera vertex's step from its next-event estimate: those weights are
// estimates (the step and the estimate taken as alike).
constexpr double kCameraStep = 1.25;
constexpr double kNextEvent = 1.25;
constexpr double kLightVertex = 2.0;
constexpr double kConnection = 1.5;
constexpr double kSensorJoin = 1.0;
constexpr double kMergeSearch = 0.3;
constexpr double kMerge = 1.45;
constexpr double kGridEntry = 0.2;

// At most this many sweeps of the choice over the tiles.
constexpr int kSweeps = 8;

// The work of the light paths a pass of N_L = `lightPaths` shares over the image: their
// vertices, their joins to the sensor if any tile traces, their places in the grid if any merges.
double sharedCost(double lightPaths, bool traces, bool merges, const PassWork& work) {
    return lightPaths * work.lightVertices * (kLightVertex + (traces ? kSensorJoin : 0) + (merges ? kGridEntry : 0));
}

// The work of `pixels` camera samples of `plan`: the camera walk where a class needs it, and the
// classes' own.
double cameraCost(const PassPlan& plan, const PassWork& work, double pixels) {
    const double vertices = pixels * work.cameraVertices;
    double cost = 0;
    if (plan.strategies().walksCamera()) cost += vertices * kCameraStep;
    if (plan.unidirectional) cost += vertices * kNextEvent;
    if (plan.connects && plan.lightPaths > 0) cost += vertices * std::max(0.0, work.lightVertices - 1) * kConnection;
    if (plan.merges) cost += vertices * (kMergeSearch + work.mergesPerQuery * plan.lightPaths * kMerge);
    return cost;
}

// The classes a plan runs, as a count.
int classes(const PassPlan& p) { return std::popcount(p.classes()); }

}  // namespace

std::vector<PassPlan> candidatePlans(double pixels) {
    std::vector<PassPlan> plans{{0, false, false, false, true}};
    for (double perPixel : {0.25, 1.0, 4.0})
        for (int bits = 1; bits < 16; ++bits)
            plans.push_back({std::max(1.0, std::round(perPixel * pixels)), (bits & kConnectClass) != 0,
                             (bits & kTraceClass) != 0, (bits & kMergeClass) != 0, (bits & kCameraWalkClass) != 0});
    return plans;
}

std::string planName(const PassPlan& plan, double pixels) {
    if (plan.lightPaths == 0) return "pt";
    return fmt::format("N_L={:g}/px {}", plan.lightPaths / pixels, classesName(plan.classes()));
}

double passCost(const PassPlan& plan, const PassWork& work, double pixels) {
    return sharedCost(plan.lightPaths, plan.lightTraces, plan.merges, work) + cameraCost(plan, work, pixels);
}

std::vector<std::vector<double>> relativeVariances(const PlanEvidence& e) {
    double pixels = 0;
    for (int n : e.tilePixels) pixels += n;
    std::vector<std::vector<double>> out;
    for (size_t k = 0; k < e.variances.size(); ++k) {
        std::vector<double> tiles;
        for (size_t tile = 0; tile < e.variances[k].size(); ++tile) {
            tiles.push_back(e.variances[k][tile] / pixels);
        }
        out.push_back(std::move(tiles));
    }
    return out;
}

PlanChoice choosePlans(const std::vector<std::vector<double>>& rv, const PlanEvidence& e,
                       const std::vector<PassPlan>& candidates, const PassWork& work, size_t fallback) {
    const size_t tiles = e.tilePixels.size();
    auto tileCost = [&](size_t k, size_t tile) { return cameraCost(candidates[k], work, e.tilePixels[tile]); };
    std::vector<double> levels;
    for (const PassPlan& c : candidates)
        if (std::find(levels.begin(), levels.end(), c.lightPaths) == levels.end()) levels.push_back(c.lightPaths);

    PlanChoice best{std::vector<size_t>(tiles, fallback), 0, 0};
    double bestEfficiency = std::numeric_limits<double>::infinity();
    for (double lightPaths : levels)
        for (bool traces : {false, true}) {
            if (traces && lightPaths == 0) continue;
            std::vector<size_t> options;
            for (size_t k = 0; k < candidates.size(); ++k)
                if (candidates[k].lightPaths == lightPaths && traces == candidates[k].lightTraces) options.push_back(k);
            // Each tile starts with the most classes it may run.
            std::vector<size_t> pick(tiles, candidates.size());
            for (size_t tile = 0; tile < tiles; ++tile)
                for (size_t k : options)
                    if (!e.uncovered[k][tile] && (pick[tile] == candidates.size() || classes(candidates[k]) > classes(candidates[pick[tile]])))
                        pick[tile] = k;
            if (std::find(pick.begin(), pick.end(), candidates.size()) != pick.end()) continue;  // a tile it cannot cover
            double variance = 0, cost = 0;
            int merging = 0;
            for (size_t tile = 0; tile < tiles; ++tile) {
                variance += rv[pick[tile]][tile];
                cost += tileCost(pick[tile], tile);
                merging += candidates[pick[tile]].merges;
            }
            auto efficiency = [&](double v, double c, int merges) {
                return v * (c + sharedCost(lightPaths, traces, merges > 0, work));
            };
            for (int sweep = 0; sweep < kSweeps; ++sweep) {
                bool changed = false;
                for (size_t tile = 0; tile < tiles; ++tile) {
                    const size_t now = pick[tile];
                    size_t then = now;
                    double least = efficiency(variance, cost, merging);
                    for (size_t k : options) {
                        if (e.uncovered[k][tile]) continue;
                        const double v = variance - rv[now][tile] + rv[k][tile], c = cost - tileCost(now, tile) + tileCost(k, tile);
                        const double f = efficiency(v, c, merging - candidates[now].merges + candidates[k].merges);
                        if (f < least) {
                            least = f;
                            then = k;
                        }
                    }
                    if (then == now) continue;
                    variance += rv[then][tile] - rv[now][tile];
                    cost += tileCost(then, tile) - tileCost(now, tile);
                    merging += candidates[then].merges - candidates[now].merges;
                    pick[tile] = then;
                    changed = true;
                }
                if (!changed) break;
            }
            const double f = efficiency(variance, cost, merging);
            if (f < bestEfficiency) {
                bestEfficiency = f;
                best = {pick, variance, cost + sharedCost(lightPaths, traces, merging > 0, work)};
            }
        }
    // Nothing seen yet: every choice is as good, and the plan stays.
    if (!(bestEfficiency > 0) || !std::isfinite(bestEfficiency)) return {std::vector<size_t>(tiles, fallback), 0, 0};
    return best;
}

}  // namespace tripath
