// Pass plans (integrators/pass_plan.h): the strategies a plan enables, and the second moment of
// one plan's estimator measured by the passes of another.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "integrators/light_phase.h"
#include "integrators/pass_plan.h"
#include "integrators/plan_moments.h"
#include "integrators/tile_passes.h"
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
    const Pass p = phase.run(scene, *integrator, pass, {17, StreamDomain::Test});
    std::vector<TechniqueSums> factors;
    for (const PassPlan& c : candidates) factors.push_back(c.factors(p.mis.constants.lightPaths));
    MomentSink sink(plan.factors(p.mis.constants.lightPaths), factors, p.mis.constants.lightPaths);
    PathBuffers paths;
    const Camera& cam = scene.camera();
    const uint64_t pixels = uint64_t(cam.width()) * cam.height();
    for (int pixel = 0; pixel < int(pixels); ++pixel) {
        SampleStream rng = sampleStream({17, StreamDomain::Test}, pass, cam, pixel);
        const Vec2 raster = jitteredRaster(rng, pixel, cam.width());
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

// The moments of a tile one row of `width` pixels high under candidates `factors` (the first the
// measuring plan, which runs every class), each pixel weighed 1; add() gives a camera sample's
// contribution as the measuring plan weighs it and returns that value. Pixels 0 and 2 are not
// neighbours: their samples' products are not taken.
struct RowMoments {
    RowMoments(int width, std::vector<TechniqueSums> factors) : width(width), moments(width, 1, 16, factors.size()) {
        moments.setFactors(std::move(factors));
        moments.setRunning({0});
        moments.setWeights(std::vector<float>(size_t(width), 1.0f));
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
        return moments.evidence(Film(width, 1).image(1), 1);
    }
    static constexpr TechniqueSums kEveryClass{1, 1, 1, 1};
    int width;
    PlanMoments moments;
    PlanMoments::Sample sample;
};

// For the candidate that is the measuring plan itself, a camera sample adds to the moment the
// square of its estimate, Σ_i X_i squared: its contributions' own moments and their cross terms;
// and the tile's moment leaves out its largest such square. Two contributions to one pixel (a
// next-event estimate, a connection), one to pixel 2, then a pass later one of 10 to the first,
// with sums as a path's technique sums are (the own class's term counts 1). Fails if the
// cross terms are left out (the moment is then 13.0 instead of 21.6, checked), if a sample's sums
// run on into the other pixel's (51.2), or if the largest square is kept (121.6) or the smallest
// left out instead (120.6).
TEST(PassPlan, TheMeasuringPlansMomentIsTheSquareOfEachSamplesEstimateLessTheLargest) {
    RowMoments tile(3, {RowMoments::kEveryClass});
    const double a = tile.add(0, 2, {1, 0.5f, 0, 0}, TechniqueClass::Unidirectional);
    const double b = tile.add(0, 4, {0.25f, 1, 0, 0}, TechniqueClass::Connection);
    const double c = tile.add(2, 1, {1, 0, 0, 0}, TechniqueClass::Unidirectional);
    const double d = tile.add(0, 10, {1, 0, 0, 0}, TechniqueClass::Unidirectional);
    const PlanEvidence e = tile.evidence();
    EXPECT_GT(d * d, (a + b) * (a + b));
    EXPECT_NEAR(e.variances[0][0], (a + b) * (a + b) + c * c, 1e-4);
}

// The estimate left out of a tile's moments is the one of the largest square under the plan the
// tile ran, for every candidate alike: a connection that a path-tracing candidate would have had
// to find by next-event estimation (its square 396 there, 3.9 under the running plan) is evidence
// against that candidate, and stays; a next-event estimate of square 100 under both is the
// outlier. Fails if each candidate left out its own largest square (the path-tracing candidate's
// moment is then 100, not 396).
TEST(PassPlan, TheOutlierIsTheRunningPlansAndLeavesEveryCandidate) {
    RowMoments tile(3, {RowMoments::kEveryClass, {1, 0, 0, 0}});  // and path tracing alone
    const double connection = tile.add(0, 2, {0.01f, 1, 0, 0}, TechniqueClass::Connection);
    const double nee = tile.add(2, 10, {1, 0, 0, 0}, TechniqueClass::Unidirectional);
    const PlanEvidence e = tile.evidence();
    EXPECT_NEAR(nee, 10, 1e-6);
    EXPECT_NEAR(e.variances[0][0], connection * 2 / 1.01, 1e-3);  // the running plan's: the connection's own
    EXPECT_NEAR(e.variances[1][0], connection * 2 / 0.01, 1e-1);  // path tracing's: F · U / D' with D' = 0.01
}

// A sample's squared mean is its estimate times its neighbour's: the pixel to its left, or to its
// right in the tile's first column. Pixels 0, 1 and 2 of a row, of estimates a, c and f, leave
// the moment a² + c² + f² − 2ac − cf (the first two each take ac, the third cf); pixel 4, of
// estimate 10 beside a pixel without one, takes no product, and its square is the outlier left
// out. Fails if the first column takes no product (6 instead of 4, checked), or if a pixel takes
// its product with the last pixel that ended rather than with its neighbour (pixel 4 would take
// 30, and the moment fall to 0).
TEST(PassPlan, ASamplesSquaredMeanIsItsProductWithItsNeighbours) {
    RowMoments tile(5, {RowMoments::kEveryClass});
    const double a = tile.add(0, 1, {1, 0, 0, 0}, TechniqueClass::Unidirectional);
    const double c = tile.add(1, 2, {1, 0, 0, 0}, TechniqueClass::Unidirectional);
    const double f = tile.add(2, 3, {1, 0, 0, 0}, TechniqueClass::Unidirectional);
    tile.add(4, 10, {1, 0, 0, 0}, TechniqueClass::Unidirectional);
    const PlanEvidence e = tile.evidence();
    EXPECT_NEAR(e.variances[0][0], a * a + c * c + f * f - 2 * a * c - c * f, 1e-4);
}

// `passes` passes of `plan` in every tile of `scene`, from pass `first` with `seed`, the radius
// the same in each (alpha 1): each pass's luminance per pixel, and when `moments` are given, what
// they measure of their candidates.
std::vector<std::vector<double>> planPasses(const Scene& scene, const PassPlan& plan, int passes, uint64_t first,
                                            uint64_t seed, PlanMoments* moments, Film* film = nullptr) {
    IntegratorSettings is;
    is.walk = {8, 2};
    is.merge.alpha = 1;
    const auto method = makePlannedPasses(plan, is);
    RenderSettings settings;
    settings.seed = seed;
    settings.threads = 2;
    PassRenderer renderer(scene, settings);
    const Camera& cam = scene.camera();
    const std::vector<PassPlan> tiles(size_t(((cam.width() + 15) / 16) * ((cam.height() + 15) / 16)), plan);
    std::vector<std::vector<double>> out;
    for (int pass = 0; pass < passes; ++pass) {
        RenderResult result{.film = Film(cam.width(), cam.height())};
        renderer.run(*method, first + uint64_t(pass), result, moments, tiles);
        renderer.endBlock(result.film);
        if (moments) moments->endBlock();
        if (film) film->add(result.film);
        const Image image = result.film.image(1);
        std::vector<double> lum;
        for (int p = 0; p < cam.width() * cam.height(); ++p) {
            const float* rgb = image.at(p % cam.width(), p / cam.width());
            lum.push_back(luminance(Spectrum(rgb[0], rgb[1], rgb[2])));
        }
        out.push_back(std::move(lum));
    }
    return out;
}

// A candidate's variance as auto reads it (PlanMoments::evidence: per pass, each pixel's share
// weighed by 1 / (I² + 0.01)) from passes of the plan auto starts with, every class at one light
// path per pixel, against the variance of the candidate's own passes pixel by pixel, weighed
// alike: path tracing, connections, bdpt's set, light tracing alone, and path tracing with a
// quarter of the light paths traced to the sensor. On contact (an area light, seen directly:
// pixels 100× their neighbours) and cornell-point (a point light the camera walk cannot hit).
// The estimate errs upward where a pixel's neighbour has another mean, by the share of its
// squared mean the product misses: measured here 0.97-1.10× the passes' own, path tracing's on
// the point light 0.87× with its own passes' standard error 8 %. Each bound is widened by three
// of the own passes' standard errors (from their fourth moments). Fails if the moment is read
// as the variance (2.3-4.4×, checked). The merges' candidates are left out: their samples share
// light paths between a camera vertex's merges and the pixel's splats, which the moments do not
// see (vcm measured 0.8×).
TEST(PassPlan, ACandidatesVarianceIsTheVarianceOfItsOwnPasses) {
    constexpr int kSize = 32, kPasses = 128;
    const double n = kSize * kSize;
    const std::vector<PassPlan> candidates = {
        {n, true, true, true, true},     // the measuring plan: every class
        {0, false, false, false, true},  // pt
        {n, true, false, false, true},   // pt and connections
        {n, true, true, false, true},    // bdpt
        {n, false, true, false, false},  // light tracing
        {n / 4, false, true, false, true},  // pt and a little light tracing
    };
    std::vector<TechniqueSums> factors;
    for (const PassPlan& c : candidates) factors.push_back(c.factors(n));
    for (const char* name : {"contact", "cornell-point"}) {
        const Scene scene(builtinScene(name), kSize, kSize);
        Film means(kSize, kSize);
        planPasses(scene, candidates[0], 32, 0, 5, nullptr, &means);
        const std::vector<float> weights = PlanMoments::relativeWeights(means.image(32));

        PlanMoments moments(kSize, kSize, kTileSize, candidates.size());
        moments.setFactors(factors);
        moments.setRunning(std::vector<size_t>(4, 0));
        moments.setWeights(weights);
        Film film(kSize, kSize);
        planPasses(scene, candidates[0], kPasses, 1000, 6, &moments, &film);
        const PlanEvidence e = moments.evidence(film.image(kPasses), kPasses);
        for (size_t k = 1; k < candidates.size(); ++k) {
            double estimate = 0;
            for (double m : e.variances[k]) estimate += m;
            const std::vector<std::vector<double>> own = planPasses(scene, candidates[k], kPasses, 2000, 7, nullptr);
            // The variance of the own passes, and its standard error from their fourth moments.
            double variance = 0, error = 0;
            for (size_t p = 0; p < size_t(n); ++p) {
                double sum = 0, squares = 0;
                for (const std::vector<double>& pass : own) sum += pass[p], squares += pass[p] * pass[p];
                const double v = (squares - sum * sum / kPasses) / (kPasses - 1), mean = sum / kPasses;
                double m4 = 0;
                for (const std::vector<double>& pass : own) m4 += std::pow(pass[p] - mean, 4) / kPasses;
                variance += weights[p] * v;
                error += double(weights[p]) * weights[p] * (m4 - v * v) / kPasses;
            }
            const double noise = 3 * std::sqrt(error) / variance;
            EXPECT_GT(estimate / variance, 0.9 - noise) << name << ", candidate " << k;
            EXPECT_LT(estimate / variance, 1.25 + noise) << name << ", candidate " << k;
        }
    }
}

}  // namespace
}  // namespace tripath
