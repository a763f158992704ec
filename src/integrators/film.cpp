#include "integrators/film.h"

namespace tripath {

Film::Film(int width, int height, FilmLayers layers)
    : width_(width), height_(height), layers_(layers), main_(3 * size_t(width) * height, 0.0) {
    depth_.assign(std::max(0, layers.depthImages), main_);
    for (int k = 1; k <= layers.strategyLength; ++k) {
        for (int s = 0; s <= k; ++s) order_.push_back({s, k + 1 - s});  // connections: t ≥ 1
        if (layers.merges)
            for (int s = 2; s <= k; ++s) order_.push_back({s, k + 2 - s, true});  // merges: s, t ≥ 2
    }
    for (const Strategy& st : order_) strategy_[st] = {main_, main_};
}

void Film::addTo(Sums& sums, int pixel, Spectrum v) {
    double* p = sums.data() + 3 * size_t(pixel);
    p[0] += v.x;
    p[1] += v.y;
    p[2] += v.z;
}

void Film::add(int pixel, Strategy strategy, Spectrum weighted, Spectrum unweighted) {
    addTo(main_, pixel, weighted);
    const int k = strategy.length();
    if (k >= 1 && k <= static_cast<int>(depth_.size())) addTo(depth_[k - 1], pixel, weighted);
    if (const auto it = strategy_.find(strategy); it != strategy_.end()) {
        addTo(it->second.first, pixel, weighted);
        addTo(it->second.second, pixel, unweighted);
    }
}

Image Film::toImage(const Sums& sums, int passes) const {
    Image img(width_, height_);
    const double scale = passes > 0 ? 1.0 / passes : 0.0;
    for (size_t i = 0; i < sums.size(); ++i) img.rgb[i] = static_cast<float>(sums[i] * scale);
    return img;
}

Image Film::image(int passes) const { return toImage(main_, passes); }
Image Film::depthImage(int k, int passes) const { return toImage(depth_.at(k - 1), passes); }
Image Film::strategyImage(Strategy strategy, bool weighted, int passes) const {
    const auto& sums = strategy_.at(strategy);
    return toImage(weighted ? sums.first : sums.second, passes);
}

std::vector<Strategy> Film::strategies() const { return order_; }

}  // namespace tripath
