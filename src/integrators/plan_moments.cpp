#include "integrators/plan_moments.h"

namespace tripath {

PlanMoments::PlanMoments(int width, int height, int tileSize, size_t candidates)
    : width_(width), height_(height), tileSize_(tileSize), tilesX_((width + tileSize - 1) / tileSize),
      tiles_(tilesX_ * ((height + tileSize - 1) / tileSize)), candidates_(candidates),
      block_(size_t(tiles_) * candidates * kSums, 0.0), totals_(block_.size()) {}

int PlanMoments::tileOf(int pixel) const {
    return (pixel / width_ / tileSize_) * tilesX_ + (pixel % width_) / tileSize_;
}

void PlanMoments::add(int pixel, Spectrum weighted, Spectrum unweighted, const TechniqueSums& sums) {
    const double f = luminance(weighted), fu = f * double(luminance(unweighted));
    if (!(fu > 0)) return;
    const int tile = tileOf(pixel);
    for (size_t k = 0; k < candidates_; ++k) {
        const float d = planDenominator(factors_[k], sums);
        if (!(d > 0)) {
            block_[sumIndex(tile, k, 1)] += 1;
            continue;
        }
        block_[sumIndex(tile, k, 0)] += fu / d;
        for (int c = 0; c < kTechniqueClasses; ++c)
            block_[sumIndex(tile, k, 2 + size_t(c))] += f * factors_[k][c] * sums[c] / d;
    }
}

void PlanMoments::endBlock() {
    totals_.add(block_, 0, block_.size());
    std::fill(block_.begin(), block_.end(), 0.0);
}

PlanEvidence PlanMoments::evidence(const Film& film, int passes, int measured) const {
    PlanEvidence e;
    e.tileMean.assign(size_t(tiles_), 0.0);
    e.tileMeanSquares.assign(size_t(tiles_), 0.0);
    e.tilePixels.assign(size_t(tiles_), 0);
    const Image image = film.image(passes);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const float* rgb = image.at(x, y);
            const double mean = luminance(Spectrum(rgb[0], rgb[1], rgb[2]));
            const int tile = tileOf(y * width_ + x);
            e.tileMean[size_t(tile)] += mean;
            e.tileMeanSquares[size_t(tile)] += mean * mean;
            ++e.tilePixels[size_t(tile)];
        }
    e.moments.assign(candidates_, std::vector<double>(size_t(tiles_), 0.0));
    e.classMeans.assign(candidates_, std::vector<TechniqueSums>(size_t(tiles_), TechniqueSums{}));
    e.uncovered.assign(candidates_, false);
    for (int tile = 0; tile < tiles_; ++tile)
        for (size_t k = 0; k < candidates_; ++k) {
            e.moments[k][size_t(tile)] = totals_.value(sumIndex(tile, k, 0)) / measured;
            if (totals_.value(sumIndex(tile, k, 1)) > 0) e.uncovered[k] = true;
            for (int c = 0; c < kTechniqueClasses; ++c)
                e.classMeans[k][size_t(tile)][c] =
                    static_cast<float>(totals_.value(sumIndex(tile, k, 2 + size_t(c))) / measured);
        }
    return e;
}

}  // namespace tripath
