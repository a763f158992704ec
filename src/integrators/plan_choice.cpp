#include "integrators/plan_choice.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

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
// rest in that fit: their weights are estimates.
constexpr double kCameraVertex = 2.5;
constexpr double kLightVertex = 2.0;
constexpr double kConnection = 1.5;
constexpr double kSensorJoin = 1.0;
constexpr double kMergeSearch = 0.3;
constexpr double kMerge = 1.45;
constexpr double kGridEntry = 0.2;

// The least variance a tile is taken to have, as a share of its moment: the difference of two
// estimates, it can come out below 0 where the variance is small.
constexpr double kLeastVarianceShare = 1e-3;

// A floor for a tile's squared mean, as a share of the image's: a black tile's variance counts as
// absolute variance against the image's level, not as infinitely relative.
constexpr double kDarkTileFloor = 1e-2;

}  // namespace

std::vector<PassPlan> candidatePlans(double pixels) {
    std::vector<PassPlan> plans{{0, false, false, false}};
    for (double perPixel : {0.25, 1.0, 4.0})
        for (int classes = 1; classes < 8; ++classes)
            plans.push_back({std::max(1.0, std::round(perPixel * pixels)), (classes & 1) != 0, (classes & 2) != 0,
                             (classes & 4) != 0});
    return plans;
}

std::string planName(const PassPlan& plan, double pixels) {
    if (plan.lightPaths == 0) return "pt";
    std::string classes;
    for (const auto& [on, name] : {std::pair{plan.connects, "connect"}, {plan.lightTraces, "trace"}, {plan.merges, "merge"}})
        if (on) classes += (classes.empty() ? "" : "+") + std::string(name);
    return fmt::format("N_L={:g}/px {}", plan.lightPaths / pixels, classes);
}

double passCost(const PassPlan& plan, const PassWork& work, double pixels) {
    const double cameraVertices = pixels * work.cameraVertices;
    const double lightVertices = plan.lightPaths * work.lightVertices;
    double cost = cameraVertices * kCameraVertex + lightVertices * kLightVertex;
    if (plan.connects) cost += cameraVertices * std::max(0.0, work.lightVertices - 1) * kConnection;
    if (plan.lightTraces) cost += lightVertices * kSensorJoin;
    if (plan.merges)
        cost += lightVertices * kGridEntry +
                cameraVertices * (kMergeSearch + work.mergesPerQuery * plan.lightPaths * kMerge);
    return cost;
}

TechniqueSums samplesPerPixel(const PassPlan& plan, double pixels) {
    // A merge's estimate sums over every light vertex within the radius: no single sample's mean
    // to subtract (0 stands for that).
    return {1.0f, 1.0f, static_cast<float>(plan.lightPaths / pixels), 0.0f};
}

std::vector<double> relativeVariances(const PlanEvidence& e, const std::vector<TechniqueSums>& samples) {
    double imageMean = 0, pixels = 0;
    for (size_t tile = 0; tile < e.tileMean.size(); ++tile) {
        imageMean += e.tileMean[tile];
        pixels += e.tilePixels[tile];
    }
    imageMean = pixels > 0 ? imageMean / pixels : 0;
    std::vector<double> out;
    for (size_t k = 0; k < e.moments.size(); ++k) {
        double sum = 0;
        for (size_t tile = 0; tile < e.moments[k].size(); ++tile) {
            const TechniqueSums& means = e.classMeans[k][tile];
            double total = 0, squaredShares = 0;
            for (float m : means) total += m;
            for (int c = 0; c < kTechniqueClasses; ++c)
                if (samples[k][c] > 0 && total > 0) squaredShares += (means[c] / total) * (means[c] / total) / samples[k][c];
            const double n = e.tilePixels[tile], mean = e.tileMean[tile] / n;
            const double variance = std::max(kLeastVarianceShare * e.moments[k][tile],
                                             e.moments[k][tile] - e.tileMeanSquares[tile] * squaredShares);
            sum += variance / (n * std::max(mean * mean, kDarkTileFloor * imageMean * imageMean));
        }
        out.push_back(sum);
    }
    return out;
}

size_t choosePlan(const std::vector<double>& relativeVariance, const std::vector<double>& cost,
                  const std::vector<bool>& uncovered, size_t fallback) {
    size_t best = fallback;
    double bestEfficiency = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < cost.size(); ++k) {
        const double efficiency = relativeVariance[k] * cost[k];
        if (uncovered[k] || !(efficiency < bestEfficiency)) continue;
        best = k;
        bestEfficiency = efficiency;
    }
    return bestEfficiency > 0 ? best : fallback;
}

}  // namespace tripath
