// Helpers shared by the physics tests: rendering at low resolution and simple statistics.
#pragma once
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geometry/builtin_scenes.h"
#include "integrators/render.h"

namespace tripath::test {

struct RenderRequest {
    std::string integrator = "pt";
    int width = 16, height = 16;
    int spp = 4;
    uint64_t seed = 1;
    int maxDepth = 16;
    int rrDepth = 3;
    MisHeuristic mis = MisHeuristic::Power;
    int threads = 0;
    FilmLayers layers;
};

inline RenderResult renderDesc(const SceneDesc& desc, const RenderRequest& r) {
    const Scene scene(desc, r.width, r.height);
    IntegratorSettings is;
    is.walk.maxDepth = r.maxDepth;
    is.walk.rrDepth = r.rrDepth;
    is.mis = r.mis;
    const auto integrator = makeIntegrator(r.integrator, is);
    RenderSettings rs;
    rs.spp = r.spp;
    rs.seed = r.seed;
    rs.threads = r.threads;
    rs.layers = r.layers;
    return render(scene, *integrator, rs);
}

// Mean of one channel (or of all three, c = -1) over a block of pixels.
inline double blockMean(const Image& img, int x0, int y0, int w, int h, int c = -1) {
    double sum = 0;
    for (int y = y0; y < y0 + h; ++y)
        for (int x = x0; x < x0 + w; ++x)
            for (int k = 0; k < 3; ++k)
                if (c < 0 || c == k) sum += img.at(x, y)[k];
    return sum / (double(w) * h * (c < 0 ? 3 : 1));
}

// Sample mean and standard error of the mean.
struct MeanError {
    double mean = 0, stderr_ = 0;
};
inline MeanError meanAndError(const std::vector<double>& v) {
    MeanError m;
    for (double x : v) m.mean += x;
    m.mean /= v.size();
    double var = 0;
    for (double x : v) var += (x - m.mean) * (x - m.mean);
    var /= (v.size() - 1);
    m.stderr_ = std::sqrt(var / v.size());
    return m;
}

}  // namespace tripath::test
