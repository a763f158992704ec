#include "geometry/sampling.h"

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
    // First entry whose cdf exceeds u; zero-weight entries are never returned.
    const auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), static_cast<double>(u));
    const size_t i = static_cast<size_t>(it - cdf_.begin()) - 1;
    return std::min(i, size() - 1);
}

}  // namespace tripath
