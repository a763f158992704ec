// A pass's plan: how many light paths it traces and which classes of strategies (mis.h's
// TechniqueClass) it runs, among vcm's. The plans are auto's candidates: it renders each tile of
// each pass with one, chosen from what the passes before measured.
//
// A pass of a plan measures the whole vcm set (Integrator::measuredStrategies): each contribution
// comes with its path's technique sums, Σ p_i / p per class over vcm's strategies in the pass's
// own constants (N_L and the merge radius), and is weighed by them (classWeight, mis.h). Another
// plan's balance-heuristic denominator for the same path is a recombination of them: a class's
// pdfs scale with its number of samples per camera sample, so the plan's denominator is
// Σ_class factor_class · sums[class], factor_class its count over the measuring pass's
// (factors()). One camera subpath per pixel sample is common to every plan that walks the camera
// (the unidirectional class, factor 1 or 0); a plan with light paths connects each camera
// subpath to one of them (factor 1 or 0); light tracing's joins and the merges' factor η both
// grow as N_L (factor N_L' / N_L or 0).
//
// What that gives (Grittmann et al. 2022, "Efficiency-aware multiple importance sampling"): the
// second moment a plan's balance-heuristic estimator would have in a pixel, ∫ f² / Σ_i n'_i p_i,
// estimated without bias from any pass that samples every path the plan would: each
// contribution F (its weighted value) times f/Σ n' p = U / D' (U its unweighted value, D' the
// plan's denominator) adds F · U / D'. A plan with D' = 0 on a path that contributed cannot
// sample it: it would lose that light.
#pragma once
#include <memory>
#include <span>

#include "integrators/pixel_sample_integrator.h"
#include "integrators/plan_report.h"

namespace tripath {

struct PassPlan {
    double lightPaths = 0;  // N_L; 0: no light phase, and then no other class than the unidirectional
    bool connects = false;     // connections s, t ≥ 2 of each camera subpath with one light subpath
    bool lightTraces = false;  // light tracing's joins to the sensor, t = 1
    bool merges = false;       // merges with the pass's light vertices
    bool unidirectional = true;  // the camera walk's hits on emitters and next-event estimates, s ≤ 1

    bool operator==(const PassPlan&) const = default;
    // The classes it runs, as plan_report.h's ClassBits: the camera walk's alone without light paths.
    uint8_t classes() const;
    // The strategies it enables: those of the classes it runs.
    StrategySet strategies() const;
    // Its number of samples of each class over that of a pass that runs every class with
    // `measuredLightPaths` light paths: the factors its denominator recombines technique sums with.
    TechniqueSums factors(double measuredLightPaths) const;
};

// The plan that runs every class some plan of `plans` runs, with the first's N_L: a pass's plan
// over the image when its tiles run `plans`.
PassPlan unionOf(std::span<const PassPlan> plans);

// The strategies a pass of a plan measures: vcm's.
StrategySet measuredStrategies();

// A method that renders every pass with `plan` (an auto pass): its connections and merges carry
// their technique sums over vcm's strategies, and each is weighed by the classes the plan runs
// where it lands (classWeight, mis.h; tile_passes.h's plans per tile). `settings` give the walks
// and the radius schedule; the plan, N_L. Without `measures`, a pass of one plan in every tile,
// or that splats nowhere: each contribution carries its weight, the balance heuristic over the
// plan's strategies, from the walk's running sums (the same weight, without the technique sums'
// cost).
std::unique_ptr<PixelSampleIntegrator> makePlannedPasses(const PassPlan& plan, const IntegratorSettings& settings,
                                                         bool measures = true);

}  // namespace tripath
