// The film: sums of contributions per pixel, in double, with optional per-path-length (Neumann
// series term) and per-strategy layers. A pixel's value is its sum over the number of passes: a
// camera sample and a splat are both estimates over one sample per pixel per pass (a pass traces
// one light path per pixel), so one accumulator serves both.
#pragma once
#include <map>
#include <vector>

#include "geometry/vec.h"
#include "image/image.h"
#include "paths/connect.h"

namespace tripath {

struct FilmLayers {
    int depthImages = 0;      // > 0: one layer per path length k = 1..depthImages
    int strategyLength = 0;   // > 0: weighted and unweighted layers per strategy with k ≤ strategyLength
    bool merges = false;      // the strategy layers include merges (set by the render loop)
};

class Film {
public:
    Film(int width, int height, FilmLayers layers = {});

    int width() const { return width_; }
    int height() const { return height_; }
    // Adds a contribution of a strategy to a pixel. Not thread-safe for the same pixel: the
    // render loop gives each pixel to one thread per pass and merges splats in a fixed order.
    void add(int pixel, Strategy strategy, Spectrum weighted, Spectrum unweighted);

    // Sums divided by `passes`.
    Image image(int passes) const;
    Image depthImage(int k, int passes) const;
    Image strategyImage(Strategy strategy, bool weighted, int passes) const;
    const FilmLayers& layers() const { return layers_; }
    // The strategies that have layers, in order of k, connections before merges, then s.
    std::vector<Strategy> strategies() const;

private:
    using Sums = std::vector<double>;
    static void addTo(Sums& sums, int pixel, Spectrum v);
    Image toImage(const Sums& sums, int passes) const;
    int width_, height_;
    FilmLayers layers_;
    Sums main_;
    std::vector<Sums> depth_;                          // index k − 1
    std::map<Strategy, std::pair<Sums, Sums>> strategy_;  // → (weighted, unweighted)
    std::vector<Strategy> order_;
};

}  // namespace tripath
