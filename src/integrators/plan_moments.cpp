#include "integrators/plan_moments.h"

namespace tripath {

PlanMoments::PlanMoments(int width, int height, int tileSize, size_t candidates)
    : width_(width), height_(height), tileSize_(tileSize), tilesX_((width + tileSize - 1) / tileSize),
      tiles_(tilesX_ * ((height + tileSize - 1) / tileSize)), candidates_(candidates),
      block_(size_t(tiles_) * candidates * kSums, 0.0), totals_(block_.size()) {}

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
        block_[sumIndex(tile, k, 0)] += fu / d;
        if (!sample) continue;
        const double x = u * factors_[k][static_cast<int>(sampled)] / d;
        sample->sum[k] += x;
        sample->squares[k] += x * x;
    }
}

void PlanMoments::endSample(Sample& sample) {
    if (sample.pixel >= 0) {
        const int tile = tileOf(sample.pixel);
        for (size_t k = 0; k < sample.sum.size(); ++k)
            block_[sumIndex(tile, k, 0)] += sample.sum[k] * sample.sum[k] - sample.squares[k];
    }
    sample.pixel = -1;
}

void PlanMoments::endBlock() {
    totals_.add(block_, 0, block_.size());
    std::fill(block_.begin(), block_.end(), 0.0);
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
            e.moments[k][size_t(tile)] = totals_.value(sumIndex(tile, k, 0)) / measured;
            e.uncovered[k][size_t(tile)] = totals_.value(sumIndex(tile, k, 1)) > 0;
        }
    return e;
}

}  // namespace tripath
