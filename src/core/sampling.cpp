#include "core/sampling.h"

#include <algorithm>

namespace tripath {

Distribution1D::Distribution1D(const std::vector<double>& weights) : cdf_(weights.size() + 1, 0.0) {
    for (size_t i = 0; i < weights.size(); ++i) cdf_[i + 1] = cdf_[i] + weights[i];
    total_ = cdf_.back();
    if (total_ > 0)
        for (double& c : cdf_) c /= total_;
    cdf_.back() = 1.0;
}

size_t Distribution1D::sample(float u) const {
    // The first entry whose cdf exceeds u (std::upper_bound's answer), so zero-weight entries are
    // never returned; searched without branches: which way a random u goes is a coin toss the
    // branch predictor loses, and next-event estimation asks at every vertex (bench/README.md).
    const double x = u;
    const double* base = cdf_.data() + 1;
    size_t n = cdf_.size() - 1;
    while (n > 1) {
        const size_t half = n / 2;
        base = base[half] <= x ? base + half : base;
        n -= half;
    }
    const size_t i = static_cast<size_t>(base + (*base <= x) - cdf_.data()) - 1;
    return std::min(i, size() - 1);
}

size_t Distribution1D::sample(float u, float& within) const {
    const size_t i = sample(u);
    const double width = cdf_[i + 1] - cdf_[i];
    within = width > 0 ? static_cast<float>(std::clamp((double(u) - cdf_[i]) / width, 0.0, 1.0)) : 0.5f;
    within = std::min(within, 0x1.fffffep-1f);
    return i;
}

}  // namespace tripath
