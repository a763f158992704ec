// The film: sums of contributions per pixel, with optional per-path-length (Neumann series term)
// and per-strategy layers. A pixel's value is its sum over the number of passes: a camera sample
// and a splat are both estimates over one sample per pixel per pass (the render loop weighs each
// splat by 1/N_L, N_L the pass's light paths), so one accumulator serves both.
//
// Each sum has two parts: the current block of passes, added in double in the render loop's fixed
// order, and the exact total of the finished blocks (exact_sum.h), to which endBlock() moves it.
// Totals add exactly, so films rendered by different processes combine (add) into the film one
// process would have made, whatever the grouping.
#pragma once
#include <map>
#include <vector>

#include "core/vec.h"
#include "integrators/exact_sum.h"
#include "image/image.h"
#include "paths/connect.h"

namespace tripath {

struct FilmLayers {
    int depthImages = 0;      // > 0: one layer per path length k = 1..depthImages
    int strategyLength = 0;   // > 0: weighted and unweighted layers per strategy with k ≤ strategyLength
    StrategySet strategies;   // the integrator's: layers only for the strategies it enables (set by the render loop)
};

class Film {
public:
    Film(int width, int height, FilmLayers layers = {});

    // The memory a pixel of one image takes: the block's three doubles and three exact totals.
    static constexpr size_t kBytesPerPixel = 3 * (sizeof(double) + sizeof(Fixed192));
    // How many images a film of these layers keeps: the main one, one per depth layer and two
    // (weighted and unweighted) per strategy layer. A film of w × h pixels takes
    // images × w × h × kBytesPerPixel bytes.
    static size_t images(const FilmLayers& layers);

    int width() const { return width_; }
    int height() const { return height_; }
    // Adds a contribution of a strategy to a pixel. Not thread-safe for the same pixel: the
    // render loop gives each pixel to one thread per pass and merges splats in a fixed order.
    void add(int pixel, Strategy strategy, Spectrum weighted, Spectrum unweighted);
    // Adds a contribution of path length k (0: none) straight to the exact totals of the main
    // image and of the depth layer k: sums in no order at all, so whoever adds them (mlt's chains,
    // on any rank and thread) gives the same film. Not thread-safe.
    void addExactly(int pixel, int k, Spectrum value);

    // Adds the current block's sums to the exact totals and clears them (the block's values are
    // already rounded to double; from here on they add exactly). Threads split the work.
    void endBlock();
    // Adds another film's totals (same size and layers, blocks ended) to this one's.
    void add(const Film& other);
    // Every exact total, in a fixed order (main, depth layers, strategy layers): what processes
    // reduce and checkpoints store. The blocks must have been ended.
    std::vector<ExactSums*> totals();
    std::vector<const ExactSums*> totals() const;

    // Sums divided by `passes` (finished blocks and the current one).
    Image image(int passes) const;
    Image depthImage(int k, int passes) const;
    Image strategyImage(Strategy strategy, bool weighted, int passes) const;
    const FilmLayers& layers() const { return layers_; }
    // The strategies that have layers, in order of k, connections before merges, then s.
    std::vector<Strategy> strategies() const;

private:
    // The strategies that get layers, in the order of strategies().
    static std::vector<Strategy> strategyOrder(const FilmLayers& layers);
    struct Sums {
        std::vector<double> block;
        ExactSums total;
        explicit Sums(size_t n) : block(n, 0.0), total(n) {}
    };
    static void addTo(Sums& sums, int pixel, Spectrum v);
    // Every sum, in the order of totals(), for a film or a const film.
    template <class Self>
    static auto sumsOf(Self& film);
    template <class Self>
    static auto totalsOf(Self& film);  // totals() and its const twin
    Image toImage(const Sums& sums, int passes) const;
    int width_, height_;
    FilmLayers layers_;
    Sums main_;
    std::vector<Sums> depth_;                          // index k − 1
    std::map<Strategy, std::pair<Sums, Sums>> strategy_;  // → (weighted, unweighted)
    std::vector<Strategy> order_;
};

}  // namespace tripath
