#include "integrators/plan_moments.h"

#include <algorithm>
#include <cstring>

namespace tripath {

PlanMoments::PlanMoments(int width, int height, int tileSize, size_t candidates)
    : width_(width), height_(height), tileSize_(tileSize), tilesX_((width + tileSize - 1) / tileSize),
      tiles_(tilesX_ * ((height + tileSize - 1) / tileSize)), candidates_(candidates),
      block_(size_t(tiles_) * candidates * kSums, 0.0), totals_(block_.size()), largest_(size_t(tiles_) * candidates, 0.0) {}

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
    for (size_t k = 0; k < candidates_; ++k) {
        const float d = techniqueDenominator(factors_[k], sums);
        if (!(d > 0)) {
            block_[sumIndex(tile, k, 1)] += 1;
            continue;
        }
        if (!sample) {
            block_[sumIndex(tile, k, 0)] += fu / d;
            largest_[size_t(tile) * candidates_ + k] = std::max(largest_[size_t(tile) * candidates_ + k], fu / d);
            continue;
        }
        sample->moment[k] += fu / d;
        const double x = u * factors_[k][static_cast<int>(sampled)] / d;
        sample->sum[k] += x;
        sample->squares[k] += x * x;
    }
}

void PlanMoments::endSample(Sample& sample) {
    if (sample.pixel >= 0) {
        const int tile = tileOf(sample.pixel);
        for (size_t k = 0; k < sample.sum.size(); ++k) {
            const double square = sample.moment[k] + sample.sum[k] * sample.sum[k] - sample.squares[k];
            block_[sumIndex(tile, k, 0)] += square;
            largest_[size_t(tile) * candidates_ + k] = std::max(largest_[size_t(tile) * candidates_ + k], square);
        }
    }
    sample.pixel = -1;
}

void PlanMoments::endBlock() {
    totals_.add(block_, 0, block_.size());
    std::fill(block_.begin(), block_.end(), 0.0);
}

std::string PlanMoments::state() const {
    const std::span<const uint64_t> words = totals_.words();
    std::string bytes(reinterpret_cast<const char*>(words.data()), words.size_bytes());
    bytes.append(reinterpret_cast<const char*>(largest_.data()), largest_.size() * sizeof(double));
    return bytes;
}

void PlanMoments::add(std::string_view state) {
    ExactSums other(totals_.size());
    const std::span<uint64_t> words = other.words();
    std::memcpy(words.data(), state.data(), words.size_bytes());
    totals_.add(other);
    std::vector<double> largest(largest_.size());
    std::memcpy(largest.data(), state.data() + words.size_bytes(), largest.size() * sizeof(double));
    for (size_t i = 0; i < largest.size(); ++i) largest_[i] = std::max(largest_[i], largest[i]);
}

PlanEvidence PlanMoments::evidence(const Film& film, int passes, int measured) const {
    PlanEvidence e;
    e.tileMean.assign(size_t(tiles_), 0.0);
    e.tilePixels.assign(size_t(tiles_), 0);
    const Image image = film.image(passes);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const float* rgb = image.at(x, y);
            const double mean = luminance(Spectrum(rgb[0], rgb[1], rgb[2]));
            const int tile = tileOf(y * width_ + x);
            e.tileMean[size_t(tile)] += mean;
            ++e.tilePixels[size_t(tile)];
        }
    e.moments.assign(candidates_, std::vector<double>(size_t(tiles_), 0.0));
    e.uncovered.assign(candidates_, std::vector<bool>(size_t(tiles_), false));
    for (int tile = 0; tile < tiles_; ++tile)
        for (size_t k = 0; k < candidates_; ++k) {
            const double moment = totals_.value(sumIndex(tile, k, 0)) - largest_[size_t(tile) * candidates_ + k];
            e.moments[k][size_t(tile)] = std::max(0.0, moment) / measured;
            e.uncovered[k][size_t(tile)] = totals_.value(sumIndex(tile, k, 1)) > 0;
        }
    return e;
}

}  // namespace tripath
