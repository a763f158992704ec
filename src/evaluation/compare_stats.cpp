// From runs to what the report shows: mean curves with their spread, and per-method finals.
#include <algorithm>
#include <cmath>
#include <limits>

#include "evaluation/compare.h"

namespace tripath::evaluation {

namespace {

std::vector<const Run*> runsOf(const std::vector<Run>& runs, const std::string& method) {
    std::vector<const Run*> out;
    for (const Run& r : runs)
        if (r.method == method) out.push_back(&r);
    return out;
}

const Checkpoint* at(const Run& r, int target) {
    for (const Checkpoint& c : r.checkpoints)
        if (c.target == target) return &c;
    return nullptr;
}

double mean(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0 : s / v.size();
}

double stddev(const std::vector<double>& v) {
    if (v.size() < 2) return 0;
    const double m = mean(v);
    double s = 0;
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / (v.size() - 1));
}

// Log-log slope of the curve over its last decade of time (from the last point at or before a
// tenth of the final time): about -1 while the error is variance, near 0 once it is bias.
double finalSlope(const Curve& c) {
    const size_t last = c.seconds.size() - 1;
    size_t from = 0;
    for (size_t i = 0; i < last; ++i)
        if (c.seconds[i] <= c.seconds[last] / 10) from = i;
    if (from == last || !(c.relMse[from] > 0) || !(c.relMse[last] > 0)) return 0;
    return std::log(c.relMse[last] / c.relMse[from]) / std::log(c.seconds[last] / c.seconds[from]);
}

// The first time the curve is at or below `level`, interpolated linearly in log-log between the
// checkpoints around it (error curves are close to straight lines there). Never reached:
// extrapolated from the last point with relMSE ∝ 1/time, the rate of an unbiased estimator, as
// long as the curve still falls at a comparable rate; an error that levels off (a method that
// cannot sample some paths, like light tracing seen through a mirror) never gets there.
std::pair<double, bool> timeToReach(const Curve& c, double level) {
    constexpr double never = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < c.relMse.size(); ++i) {
        if (c.relMse[i] > level) continue;
        if (i == 0 || !(c.relMse[i - 1] > c.relMse[i])) return {c.seconds[i], false};
        const double f = std::log(c.relMse[i - 1] / level) / std::log(c.relMse[i - 1] / c.relMse[i]);
        return {c.seconds[i - 1] * std::pow(c.seconds[i] / c.seconds[i - 1], f), false};
    }
    if (c.relMse.empty() || !(level > 0) || finalSlope(c) > -0.5) return {never, true};
    return {c.seconds.back() * c.relMse.back() / level, true};
}

MethodSummary finals(const std::vector<const Run*>& runs) {
    MethodSummary s;
    s.method = runs.front()->method;
    std::vector<double> rel, mse, mae, tail, spp, sec, relVar, rays, flip;
    for (const Run* r : runs) {
        const Checkpoint& f = r->final();
        rel.push_back(f.error.relMse);
        mse.push_back(f.error.mse);
        mae.push_back(f.error.mae);
        tail.push_back(f.error.tailShare);
        spp.push_back(f.spp);
        sec.push_back(f.seconds);
        relVar.push_back(perSampleRelVariance(f.error.relMse, f.spp));
        rays.push_back(double(r->stats[Event::ClosestHitRays] + r->stats[Event::ShadowRays]) / f.seconds);
        flip.push_back(r->flip);
    }
    s.error = {mean(rel), mean(mse), mean(mae), mean(tail)};
    s.relMseStd = stddev(rel);
    s.spp = mean(spp);
    s.seconds = mean(sec);
    s.efficiency = 1 / (s.error.relMse * s.seconds);
    s.relVariance = mean(relVar);
    s.raysPerSecond = mean(rays);
    s.flip = mean(flip);
    return s;
}

}  // namespace

Curve curveOf(const std::vector<Run>& runs, const std::string& method) {
    Curve c{method, {}, {}, {}, {}, {}};
    const auto mine = runsOf(runs, method);
    for (int k = 0; k <= kTargets; ++k) {
        std::vector<double> sec, spp, rel;
        for (const Run* r : mine)
            if (const Checkpoint* cp = at(*r, k)) {
                sec.push_back(cp->seconds);
                spp.push_back(cp->spp);
                rel.push_back(cp->error.relMse);
            }
        if (rel.empty() || rel.size() != mine.size()) continue;  // only where every run has a point
        c.seconds.push_back(mean(sec));
        c.spp.push_back(mean(spp));
        c.relMse.push_back(mean(rel));
        c.low.push_back(*std::min_element(rel.begin(), rel.end()));
        c.high.push_back(*std::max_element(rel.begin(), rel.end()));
    }
    return c;
}

size_t bestMethod(const std::vector<MethodSummary>& s) {
    size_t best = 0;
    for (size_t i = 1; i < s.size(); ++i)
        if (s[i].error.relMse < s[best].error.relMse) best = i;
    return best;
}

std::vector<MethodSummary> summarize(const std::vector<Run>& runs, const std::vector<Curve>& curves) {
    std::vector<MethodSummary> out;
    for (const Curve& c : curves) out.push_back(finals(runsOf(runs, c.method)));
    const double level = out[bestMethod(out)].error.relMse;
    for (size_t i = 0; i < out.size(); ++i)
        std::tie(out[i].timeToBest, out[i].extrapolated) = timeToReach(curves[i], level);
    return out;
}

}  // namespace tripath::evaluation
