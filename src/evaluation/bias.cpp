#include "evaluation/bias.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.h"

namespace tripath {

namespace {

struct MeanVar {
    double mean = 0, var = 0;  // var: unbiased sample variance
};

MeanVar meanVar(const std::vector<double>& v) {
    MeanVar m;
    for (double x : v) m.mean += x;
    m.mean /= double(v.size());
    for (double x : v) m.var += (x - m.mean) * (x - m.mean);
    m.var /= double(v.size() - 1);
    return m;
}

// The continued fraction of the regularised incomplete beta function I_x(a, b), evaluated by
// the modified Lentz method; converges quickly for x < (a + 1) / (a + b + 2).
double betaContinuedFraction(double a, double b, double x) {
    constexpr double kTiny = 1e-300, kEps = 1e-15;
    double c = 1, d = 1 - (a + b) * x / (a + 1);
    if (std::abs(d) < kTiny) d = kTiny;
    d = 1 / d;
    double h = d;
    for (int m = 1; m <= 500; ++m) {
        const double m2 = 2.0 * m;
        // Even step: d_{2m} = m (b − m) x / ((a + 2m − 1)(a + 2m)).
        double num = m * (b - m) * x / ((a + m2 - 1) * (a + m2));
        d = 1 + num * d;
        c = 1 + num / c;
        d = 1 / (std::abs(d) < kTiny ? kTiny : d);
        c = std::abs(c) < kTiny ? kTiny : c;
        h *= d * c;
        // Odd step: d_{2m+1} = −(a + m)(a + b + m) x / ((a + 2m)(a + 2m + 1)).
        num = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1));
        d = 1 + num * d;
        c = 1 + num / c;
        d = 1 / (std::abs(d) < kTiny ? kTiny : d);
        c = std::abs(c) < kTiny ? kTiny : c;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1) < kEps) break;
    }
    return h;
}

// I_x(a, b) = x^a (1 − x)^b / (a B(a, b)) · continued fraction, using the symmetry
// I_x(a, b) = 1 − I_{1−x}(b, a) where the fraction would converge slowly.
double regularizedIncompleteBeta(double a, double b, double x) {
    if (x <= 0) return 0;
    if (x >= 1) return 1;
    const double logFront = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
    if (x < (a + 1) / (a + b + 2)) return std::exp(logFront) * betaContinuedFraction(a, b, x) / a;
    return 1 - std::exp(logFront) * betaContinuedFraction(b, a, 1 - x) / b;
}

}  // namespace

double studentTwoSidedP(double t, double dof) {
    if (!std::isfinite(t)) return 0;
    // P(|T| ≥ |t|) = I_{ν/(ν + t²)}(ν/2, 1/2).
    return regularizedIncompleteBeta(dof / 2, 0.5, dof / (dof + t * t));
}

WelchTest welchTest(const std::vector<double>& a, const std::vector<double>& b) {
    if (a.size() < 2 || b.size() < 2) throw InputError("Welch's t-test needs at least two runs of each");
    const MeanVar ma = meanVar(a), mb = meanVar(b);
    const double sa = ma.var / double(a.size()), sb = mb.var / double(b.size());
    WelchTest w;
    if (sa + sb == 0) {
        w.p = ma.mean == mb.mean ? 1 : 0;
        w.t = ma.mean == mb.mean ? 0 : INFINITY;
        return w;
    }
    w.t = (ma.mean - mb.mean) / std::sqrt(sa + sb);
    w.dof = (sa + sb) * (sa + sb) / (sa * sa / double(a.size() - 1) + sb * sb / double(b.size() - 1));
    w.p = studentTwoSidedP(w.t, w.dof);
    return w;
}

std::vector<bool> holmSignificant(const std::vector<double>& p, double alpha) {
    std::vector<size_t> order(p.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](size_t i, size_t j) { return p[i] < p[j]; });
    std::vector<bool> significant(p.size(), false);
    // The k-th smallest p-value (from 0) is tested at alpha / (m − k); the first that fails stops it.
    for (size_t k = 0; k < order.size(); ++k) {
        if (!(p[order[k]] <= alpha / double(order.size() - k))) break;
        significant[order[k]] = true;
    }
    return significant;
}

int BiasMap::count() const { return int(std::count(biased.begin(), biased.end(), true)); }

BiasMap biasMap(const std::vector<Image>& runs, const std::vector<Image>& referenceRuns, int blockSize, double alpha) {
    if (runs.size() < 2 || referenceRuns.size() < 2) throw InputError("a bias map needs at least two runs of each method");
    if (blockSize < 1) throw InputError("a bias map needs blocks of at least one pixel");
    const int width = runs[0].width, height = runs[0].height;
    for (const auto* set : {&runs, &referenceRuns})
        for (const Image& img : *set)
            if (img.width != width || img.height != height)
                throw InputError(fmt::format("bias map: a run is {}x{}, another {}x{}", img.width, img.height, width, height));
    BiasMap map;
    map.blockSize = blockSize;
    map.alpha = alpha;
    map.blocksX = (width + blockSize - 1) / blockSize;
    map.blocksY = (height + blockSize - 1) / blockSize;
    auto blockLuminance = [&](const Image& img, int bx, int by) {
        double sum = 0;
        int n = 0;
        for (int y = by * blockSize; y < std::min(height, (by + 1) * blockSize); ++y)
            for (int x = bx * blockSize; x < std::min(width, (bx + 1) * blockSize); ++x, ++n) {
                const float* p = &img.rgb[3 * (size_t(y) * width + x)];
                sum += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
            }
        return sum / n;
    };
    std::vector<double> p;
    for (int by = 0; by < map.blocksY; ++by)
        for (int bx = 0; bx < map.blocksX; ++bx) {
            std::vector<double> a, b;
            for (const Image& img : runs) a.push_back(blockLuminance(img, bx, by));
            for (const Image& img : referenceRuns) b.push_back(blockLuminance(img, bx, by));
            map.tests.push_back(welchTest(a, b));
            p.push_back(map.tests.back().p);
        }
    map.biased = holmSignificant(p, alpha);
    return map;
}

}  // namespace tripath
