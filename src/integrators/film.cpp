#include "integrators/film.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cassert>

namespace tripath {

std::vector<Strategy> Film::strategyOrder(const FilmLayers& layers) {
    std::vector<Strategy> order;
    for (int k = 1; k <= layers.strategyLength; ++k) {
        for (int s = 0; s <= k; ++s)  // connections: t ≥ 1
            if (layers.strategies.enabled(s, k + 1 - s)) order.push_back({s, k + 1 - s});
        if (layers.strategies.merges())
            for (int s = 2; s <= k; ++s) order.push_back({s, k + 2 - s, true});  // merges: s, t ≥ 2
    }
    return order;
}

size_t Film::images(const FilmLayers& layers) {
    return 1 + size_t(std::max(0, layers.depthImages)) + 2 * strategyOrder(layers).size();
}

Film::Film(int width, int height, FilmLayers layers)
    : width_(width), height_(height), layers_(layers), main_(3 * size_t(width) * height), order_(strategyOrder(layers)) {
    depth_.assign(std::max(0, layers.depthImages), main_);
    for (const Strategy& st : order_) strategy_.emplace(st, std::make_pair(main_, main_));
}

void Film::addTo(Sums& sums, int pixel, Spectrum v) {
    double* p = sums.block.data() + 3 * size_t(pixel);
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

void Film::addExactly(int pixel, int k, Spectrum value) {
    auto add = [&](Sums& sums) {
        for (int c = 0; c < 3; ++c) sums.total.add(3 * size_t(pixel) + size_t(c), value[c]);
    };
    add(main_);
    if (k >= 1 && k <= static_cast<int>(depth_.size())) add(depth_[k - 1]);
}

template <class Self>
auto Film::sumsOf(Self& film) {
    std::vector<decltype(&film.main_)> out{&film.main_};
    for (auto& d : film.depth_) out.push_back(&d);
    for (const Strategy& st : film.order_) {
        auto& pair = film.strategy_.at(st);
        out.insert(out.end(), {&pair.first, &pair.second});
    }
    return out;
}

template <class Self>
auto Film::totalsOf(Self& film) {
    std::vector<decltype(&film.main_.total)> out;
    for (auto* sums : sumsOf(film)) out.push_back(&sums->total);
    return out;
}

void Film::endBlock() {
    const std::vector<Sums*> all = sumsOf(*this);
    const size_t n = main_.block.size();
    constexpr size_t kChunk = 1 << 14;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, (n + kChunk - 1) / kChunk), [&](const tbb::blocked_range<size_t>& r) {
        const size_t begin = r.begin() * kChunk, end = std::min(n, r.end() * kChunk);
        for (Sums* s : all) {
            s->total.add(s->block, begin, end);
            std::fill(s->block.begin() + begin, s->block.begin() + end, 0.0);
        }
    });
}

std::vector<ExactSums*> Film::totals() { return totalsOf(*this); }
std::vector<const ExactSums*> Film::totals() const { return totalsOf(*this); }

void Film::add(const Film& other) {
    assert(width_ == other.width_ && height_ == other.height_ && order_ == other.order_);
    const std::vector<ExactSums*> mine = totals();
    const std::vector<const ExactSums*> theirs = other.totals();
    for (size_t i = 0; i < mine.size(); ++i) mine[i]->add(*theirs[i]);
}

Image Film::toImage(const Sums& sums, int passes) const {
    Image img(width_, height_);
    const double scale = passes > 0 ? 1.0 / passes : 0.0;
    for (size_t i = 0; i < sums.block.size(); ++i)
        img.rgb[i] = static_cast<float>((sums.total.value(i) + sums.block[i]) * scale);
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
