// Pass plans (integrators/pass_plan.h): the strategies a plan enables, and the second moment of
// one plan's estimator measured by the passes of another.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "integrators/light_phase.h"
#include "integrators/pass_plan.h"
#include "integrators/plan_moments.h"
#include "scenes/builtin_scenes.h"
#include "support.h"

namespace tripath {
namespace {

// Each plan enables exactly the classes it runs, and needs the camera walk unless it only traces
// light. Fails if a class's switch reaches another class's strategies (checked: the
// unidirectional switch left out of StrategySet::enabled fails it).
TEST(PassPlan, EnablesTheClassesItRuns) {
    for (int bits = 1; bits < 16; ++bits) {
        const PassPlan plan{16, (bits & 2) != 0, (bits & 4) != 0, (bits & 8) != 0, (bits & 1) != 0};
        const StrategySet set = plan.strategies();
        for (int s = 0; s <= 6; ++s)
            for (int t = 1; t <= 6; ++t) {
                if (s + t < 2) continue;
                const bool expected = t == 1 ? plan.lightTraces : s <= 1 ? plan.unidirectional : plan.connects;
                EXPECT_EQ(set.enabled(s, t), expected) << "plan " << bits << " s=" << s << " t=" << t;
            }
        EXPECT_EQ(set.merges(), plan.merges) << "plan " << bits;
        EXPECT_EQ(set.walksCamera(), plan.unidirectional || plan.connects || plan.merges) << "plan " << bits;
    }
}

// Sums, over one pass of a plan measuring vcm's strategies, F · U / D' of every contribution for
// each candidate plan (pass_plan.h): the estimate of Σ_pixels ∫ f² / Σ n' p that the pass makes
// for each candidate.
class MomentSink final : public ContributionSink {
public:
    MomentSink(TechniqueSums own, std::vector<TechniqueSums> factors, double lightPaths)
        : own_(own), factors_(std::move(factors)), splatShare_(1.0 / lightPaths), moments(factors_.size(), 0.0),
          uncovered(factors_.size(), 0) {}
    void add(Strategy st, const Connection& c) override {
        // A splat is one of the pass's N_L estimates of the pixel it lands in (render.cpp's TileSink).
        const double share = !st.merge && st.t == 1 ? splatShare_ : 1.0;
        const float w = classWeight(own_, techniqueClass(st.s, st.t, st.merge), c.techniques).value;
        const double fu = share * w * luminance(c.unweighted) * share * luminance(c.unweighted);
        if (!(fu > 0)) return;
        for (size_t k = 0; k < factors_.size(); ++k) {
            const float d = techniqueDenominator(factors_[k], c.techniques);
            if (d > 0)
                moments[k] += fu / d;
            else
                ++uncovered[k];
        }
    }

private:
    TechniqueSums own_;  // the measuring plan's factors, which weigh its contributions
    std::vector<TechniqueSums> factors_;
    double splatShare_;

public:
    std::vector<double> moments;
    std::vector<int> uncovered;
};

// One pass (of index `pass`) of `plan` over the whole image, measuring the candidates.
MomentSink renderPass(const Scene& scene, const PassPlan& plan, const std::vector<PassPlan>& candidates, uint64_t pass) {
    IntegratorSettings settings;
    settings.mis = MisHeuristic::Power;
    settings.walk = {4, 2};
    settings.merge.alpha = 1;  // one radius for every pass: the candidates' moments are the same integrals in each
    const auto integrator = makePlannedPasses(plan, settings);
    LightPhase phase;
    const Pass p = phase.run(scene, *integrator, pass, 17, StreamDomain::Test);
    std::vector<TechniqueSums> factors;
    for (const PassPlan& c : candidates) factors.push_back(c.factors(p.mis.constants.lightPaths));
    MomentSink sink(plan.factors(p.mis.constants.lightPaths), factors, p.mis.constants.lightPaths);
    PathBuffers paths;
    const Camera& cam = scene.camera();
    const uint64_t pixels = uint64_t(cam.width()) * cam.height();
    for (int pixel = 0; pixel < int(pixels); ++pixel) {
        Rng rng(17, static_cast<uint64_t>(StreamDomain::Test), pass * pixels + uint64_t(pixel));
        const Vec2 raster{pixel % cam.width() + rng.uniform(), pixel / cam.width() + rng.uniform()};
        integrator->sample(scene, p, pixel, CameraRay(raster), rng, paths, sink);
    }
    return sink;
}

// A candidate's second moment, Σ_pixels ∫ f² / Σ n' p, is one number whichever plan measures it:
// every plan here samples every path of the scene (an area light, no delta surface), so the
// passes of each estimate it without bias, and the passes of the candidate itself are the
// reference. Plans of 1/4, 1/2, 1 and 2 light paths per pixel with each class on and off, on
// cornell: the factors must scale light tracing and the merges by N_L' / N_L, count a connection
// once whatever N_L, and drop a class the candidate does not run. Fails if a factor is squared,
// left at 1, or given to the wrong class (checked: light tracing's share squared, and the merges
// left unscaled, each fail it).
TEST(PassPlan, AMomentMeasuredUnderOnePlanIsTheMomentUnderAnother) {
    const Scene scene(builtinScene("cornell"), 12, 12);
    const double pixels = 144;
    const std::vector<PassPlan> plans = {
        {0, false, false, false},                // pt
        {pixels, true, true, true},              // vcm
        {pixels / 4, false, true, false},        // pt and a little light tracing
        {2 * pixels, false, true, true},         // light tracing and merges, no connections
        {pixels / 2, true, false, true},         // connections and merges, no light tracing
        {pixels, true, true, false},             // bdpt
    };
    constexpr int kPasses = 160;
    // runs[m][k]: per pass, the moment of candidate k as plan m measured it.
    std::vector<std::vector<std::vector<double>>> runs(plans.size(), std::vector<std::vector<double>>(plans.size()));
    for (size_t m = 0; m < plans.size(); ++m)
        for (int pass = 0; pass < kPasses; ++pass) {
            const MomentSink sink = renderPass(scene, plans[m], plans, uint64_t(pass) + 1000 * m);
            for (size_t k = 0; k < plans.size(); ++k) {
                EXPECT_EQ(sink.uncovered[k], 0) << "plan " << k << " misses paths plan " << m << " found";
                runs[m][k].push_back(sink.moments[k]);
            }
        }
    test::BlockAgreement agreement;
    for (size_t k = 0; k < plans.size(); ++k)
        for (size_t m = 0; m < plans.size(); ++m)
            if (m != k)
                agreement.compare(runs[m][k], runs[k][k],
                                  "candidate " + std::to_string(k) + " measured by plan " + std::to_string(m));
    agreement.expectNoBias();
}

// A two-pixel tile's moments under candidates `factors` (the first the measuring plan, which runs
// every class), each pixel weighed 1; add() gives a camera sample's contribution as the
// measuring plan weighs it and returns that value.
struct TwoPixelMoments {
    explicit TwoPixelMoments(std::vector<TechniqueSums> factors) : moments(2, 1, 16, factors.size()) {
        moments.setFactors(std::move(factors));
        moments.setRunning({0});
        moments.setWeights({1, 1});
    }
    double add(int pixel, float unweighted, const TechniqueSums& sums, TechniqueClass c) {
        const float weight = classWeight(kEveryClass, c, sums).value;
        moments.add(sample, pixel, Spectrum(weight * unweighted), Spectrum(unweighted), sums, c);
        return weight * unweighted;
    }
    // The evidence after the samples so far, as one measuring pass.
    PlanEvidence evidence() {
        moments.endSample(sample);
        moments.endBlock();
        return moments.evidence(Film(2, 1).image(1), 1);
    }
    static constexpr TechniqueSums kEveryClass{1, 1, 1, 1};
    PlanMoments moments;
    PlanMoments::Sample sample;
};

// For the candidate that is the measuring plan itself, a camera sample adds to the moment the
// square of its estimate, Σ_i X_i squared: its contributions' own moments and their cross terms;
// and the tile's moment leaves out its largest such square. Two contributions to one pixel (a
// next-event estimate, a connection), one to the next pixel, then a pass later one of 10 to the
// first, with sums as a path's technique sums are (the own class's term counts 1). Fails if the
// cross terms are left out (the moment is then 13.0 instead of 21.6, checked), if a sample's sums
// run on into the next pixel's (51.2), or if the largest square is kept (121.6) or the smallest
// left out instead (120.6).
TEST(PassPlan, TheMeasuringPlansMomentIsTheSquareOfEachSamplesEstimateLessTheLargest) {
    TwoPixelMoments tile({TwoPixelMoments::kEveryClass});
    const double a = tile.add(0, 2, {1, 0.5f, 0, 0}, TechniqueClass::Unidirectional);
    const double b = tile.add(0, 4, {0.25f, 1, 0, 0}, TechniqueClass::Connection);
    const double c = tile.add(1, 1, {1, 0, 0, 0}, TechniqueClass::Unidirectional);
    const double d = tile.add(0, 10, {1, 0, 0, 0}, TechniqueClass::Unidirectional);
    const PlanEvidence e = tile.evidence();
    EXPECT_GT(d * d, (a + b) * (a + b));
    EXPECT_NEAR(e.moments[0][0], (a + b) * (a + b) + c * c, 1e-4);
}

// The estimate left out of a tile's moments is the one of the largest square under the plan the
// tile ran, for every candidate alike: a connection that a path-tracing candidate would have had
// to find by next-event estimation (its square 396 there, 3.9 under the running plan) is evidence
// against that candidate, and stays; a next-event estimate of square 100 under both is the
// outlier. Fails if each candidate left out its own largest square (the path-tracing candidate's
// moment is then 100, not 396).
TEST(PassPlan, TheOutlierIsTheRunningPlansAndLeavesEveryCandidate) {
    TwoPixelMoments tile({TwoPixelMoments::kEveryClass, {1, 0, 0, 0}});  // and path tracing alone
    const double connection = tile.add(0, 2, {0.01f, 1, 0, 0}, TechniqueClass::Connection);
    const double nee = tile.add(1, 10, {1, 0, 0, 0}, TechniqueClass::Unidirectional);
    const PlanEvidence e = tile.evidence();
    EXPECT_NEAR(nee, 10, 1e-6);
    EXPECT_NEAR(e.moments[0][0], connection * 2 / 1.01, 1e-3);  // the running plan's: the connection's own
    EXPECT_NEAR(e.moments[1][0], connection * 2 / 0.01, 1e-1);  // path tracing's: F · U / D' with D' = 0.01
}

}  // namespace
}  // namespace tripath
