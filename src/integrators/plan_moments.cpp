#include "integrators/plan_moments.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace tripath {

PlanMoments::PlanMoments(int width, int height, int tileSize, size_t candidates)
    : width_(width), height_(height), tileSize_(tileSize), tilesX_((width + tileSize - 1) / tileSize),
      tiles_(tilesX_ * ((height + tileSize - 1) / tileSize)), candidates_(candidates),
      block_(size_t(tiles_) * candidates * kSums, 0.0), totals_(block_.size()),
      outliers_(size_t(tiles_) * (candidates + 1), 0.0), running_(size_t(tiles_), 0), scratch_(candidates) {}

int PlanMoments::tileOf(int pixel) const {
    return (pixel / width_ / tileSize_) * tilesX_ + (pixel % width_) / tileSize_;
}

void PlanMoments::addSplat(int pixel, Spectrum weighted, Spectrum unweighted, const TechniqueSums& sums) {
    add(nullptr, pixel, weighted, unweighted, sums, TechniqueClass::LightTracing);
}

void PlanMoments::add(Sample& sample, int pixel, Spectrum weighted, Spectrum unweighted, const TechniqueSums& sums,
                      TechniqueClass sampled) {
    if (sample.pixel != pixel) {
        endSample(sample);
        sample.pixel = pixel;
        sample.moment.assign(candidates_, 0.0);
        sample.sum.assign(candidates_, 0.0);
        sample.squares.assign(candidates_, 0.0);
    }
    add(&sample, pixel, weighted, unweighted, sums, sampled);
}

void PlanMoments::add(Sample* sample, int pixel, Spectrum weighted, Spectrum unweighted, const TechniqueSums& sums,
                      TechniqueClass sampled) {
    const double u = luminance(unweighted), fu = double(luminance(weighted)) * u;
    if (!(fu > 0)) return;
    const int tile = tileOf(pixel);
    if (!sample) std::fill(scratch_.begin(), scratch_.end(), 0.0);
    for (size_t k = 0; k < candidates_; ++k) {
        const float d = techniqueDenominator(factors_[k], sums);
        if (!(d > 0)) {
            block_[sumIndex(tile, k, kUncovered)] += 1;
            continue;
        }
        if (!sample) {
            scratch_[k] = weightOf(pixel) * fu / d;
            block_[sumIndex(tile, k, kMoment)] += scratch_[k];
            continue;
        }
        sample->moment[k] += fu / d;
        const double x = u * factors_[k][static_cast<int>(sampled)] / d;
        sample->sum[k] += x;
        sample->squares[k] += x * x;
    }
    if (!sample) offerOutlier(tile, scratch_.data());
}

void PlanMoments::offerOutlier(int tile, const double* squares) {
    keepOutlier(tile, squares[running_[size_t(tile)]], squares);
}

void PlanMoments::keepOutlier(int tile, double key, const double* squares) {
    double* kept = &outliers_[size_t(tile) * (candidates_ + 1)];
    // The larger key; of two equal, the lexicographically larger squares, so that the order the
    // estimates come in does not matter.
    if (key < kept[0] || (key == kept[0] && !std::lexicographical_compare(kept + 1, kept + 1 + candidates_, squares,
                                                                            squares + candidates_)))
        return;
    kept[0] = key;
    std::copy(squares, squares + candidates_, kept + 1);
}

void PlanMoments::endSample(Sample& sample) {
    if (sample.pixel >= 0) {
        const int tile = tileOf(sample.pixel);
        for (size_t k = 0; k < sample.sum.size(); ++k) {
            sample.moment[k] =
                weightOf(sample.pixel) * (sample.moment[k] + sample.sum[k] * sample.sum[k] - sample.squares[k]);
            block_[sumIndex(tile, k, kMoment)] += sample.moment[k];
        }
        offerOutlier(tile, sample.moment.data());
        // The neighbour: the pixel to the left in the tile; the first column's is its right one,
        // whose product is added when that one ends. A neighbour without contributions never
        // ended, and its product is 0.
        const int column = (sample.pixel % width_) % tileSize_;
        if (column > 0 && sample.previous == sample.pixel - 1) {
            addSquaredMean(sample.pixel, sample.previous, sample.sum, sample.previousSum);
            if (column == 1) addSquaredMean(sample.previous, sample.pixel, sample.sum, sample.previousSum);
        }
        sample.previous = sample.pixel;
        std::swap(sample.previousSum, sample.sum);  // the next sample starts its sums afresh
    }
    sample.pixel = -1;
}

void PlanMoments::addSquaredMean(int pixel, int neighbourPixel, const std::vector<double>& sum,
                                 const std::vector<double>& neighbour) {
    const int tile = tileOf(pixel);
    const double weight = std::sqrt(weightOf(pixel) * weightOf(neighbourPixel));
    for (size_t k = 0; k < sum.size(); ++k) block_[sumIndex(tile, k, kSquaredMean)] += weight * sum[k] * neighbour[k];
}

void PlanMoments::setWeights(std::vector<float> weights, std::span<const double> tileScales) {
    if (weights_.empty() && !tileScales.empty())
        for (int tile = 0; tile < tiles_; ++tile) {
            const double scale = tileScales[size_t(tile)];
            for (size_t k = 0; k < candidates_; ++k)
                for (Sum which : {kMoment, kSquaredMean}) {
                    const double value = totals_.value(sumIndex(tile, k, which));
                    totals_.clear(sumIndex(tile, k, which));
                    totals_.add(sumIndex(tile, k, which), value * scale);
                }
            for (size_t i = 0; i <= candidates_; ++i) outliers_[size_t(tile) * (candidates_ + 1) + i] *= scale;
        }
    weights_ = std::move(weights);
}

void PlanMoments::clearTotals() {
    totals_ = ExactSums(totals_.size());
    std::fill(outliers_.begin(), outliers_.end(), 0.0);
}

std::vector<double> PlanMoments::tileScales(const Image& mean) const {
    std::vector<double> sum(size_t(tiles_), 0.0), pixels(size_t(tiles_), 0.0);
    for (int p = 0; p < width_ * height_; ++p) {
        const float* rgb = mean.at(p % width_, p / width_);
        sum[size_t(tileOf(p))] += luminance(Spectrum(rgb[0], rgb[1], rgb[2]));
        pixels[size_t(tileOf(p))] += 1;
    }
    std::vector<double> scales;
    for (int tile = 0; tile < tiles_; ++tile) {
        const double mean = sum[size_t(tile)] / std::max(1.0, pixels[size_t(tile)]);
        scales.push_back(1 / (mean * mean + kRelativeOffset));
    }
    return scales;
}

std::vector<float> PlanMoments::relativeWeights(const Image& mean) {
    std::vector<float> w(size_t(mean.width) * size_t(mean.height));
    for (int y = 0; y < mean.height; ++y)
        for (int x = 0; x < mean.width; ++x) {
            double sum = 0;
            int n = 0;
            for (int v = std::max(0, y - 1); v <= std::min(mean.height - 1, y + 1); ++v)
                for (int u = std::max(0, x - 1); u <= std::min(mean.width - 1, x + 1); ++u, ++n) {
                    const float* rgb = mean.at(u, v);
                    sum += luminance(Spectrum(rgb[0], rgb[1], rgb[2]));
                }
            const double blurred = sum / n;
            w[size_t(y) * size_t(mean.width) + size_t(x)] = float(1 / (blurred * blurred + kRelativeOffset));
        }
    return w;
}

void PlanMoments::endBlock() {
    totals_.add(block_, 0, block_.size());
    std::fill(block_.begin(), block_.end(), 0.0);
}

std::string PlanMoments::state() const {
    const std::span<const uint64_t> words = totals_.words();
    std::string bytes(reinterpret_cast<const char*>(words.data()), words.size_bytes());
    bytes.append(reinterpret_cast<const char*>(outliers_.data()), outliers_.size() * sizeof(double));
    return bytes;
}

void PlanMoments::add(std::string_view state) {
    ExactSums other(totals_.size());
    const std::span<uint64_t> words = other.words();
    std::memcpy(words.data(), state.data(), words.size_bytes());
    totals_.add(other);
    std::vector<double> outliers(outliers_.size());
    std::memcpy(outliers.data(), state.data() + words.size_bytes(), outliers.size() * sizeof(double));
    for (int tile = 0; tile < tiles_; ++tile) {
        const double* other = &outliers[size_t(tile) * (candidates_ + 1)];
        keepOutlier(tile, other[0], other + 1);
    }
}

PlanEvidence PlanMoments::evidence(const Image& mean, int measured) const {
    PlanEvidence e;
    e.tilePixels.assign(size_t(tiles_), 0);
    for (int p = 0; p < width_ * height_; ++p) ++e.tilePixels[size_t(tileOf(p))];
    // Without weights yet, every pixel of a tile weighs as the tile's mean would.
    const std::vector<double> scale = weights_.empty() ? tileScales(mean) : std::vector<double>(size_t(tiles_), 1.0);
    e.variances.assign(candidates_, std::vector<double>(size_t(tiles_), 0.0));
    e.uncovered.assign(candidates_, std::vector<bool>(size_t(tiles_), false));
    for (int tile = 0; tile < tiles_; ++tile)
        for (size_t k = 0; k < candidates_; ++k) {
            const double variance = totals_.value(sumIndex(tile, k, kMoment)) -
                                    outliers_[size_t(tile) * (candidates_ + 1) + 1 + k] -
                                    totals_.value(sumIndex(tile, k, kSquaredMean));
            e.variances[k][size_t(tile)] = scale[size_t(tile)] * std::max(0.0, variance) / measured;
            e.uncovered[k][size_t(tile)] = totals_.value(sumIndex(tile, k, kUncovered)) > 0;
        }
    return e;
}

}  // namespace tripath
