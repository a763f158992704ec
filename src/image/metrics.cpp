#include "image/metrics.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geometry/error.h"

namespace tripath {

ErrorMetrics compareImages(const Image& test, const Image& reference, double epsilon) {
    if (test.width != reference.width || test.height != reference.height)
        throw InputError(fmt::format("cannot compare images of different sizes: {}x{} vs reference {}x{}", test.width,
                                     test.height, reference.width, reference.height));
    const std::size_t n = test.rgb.size();
    if (n != reference.rgb.size() || n != 3 * test.pixelCount())
        throw InputError("cannot compare images: pixel buffer does not match the image size");
    if (n == 0) return {0.0, 0.0, 0.0};

    // Accumulate in double: a float sum over millions of samples would lose
    // the small errors of a converged render.
    double rel = 0, sq = 0, abs = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double r = reference.rgb[i];
        const double d = double(test.rgb[i]) - r;
        rel += d * d / (r * r + epsilon);
        sq += d * d;
        abs += std::fabs(d);
    }
    const double inv = 1.0 / double(n);
    return {rel * inv, sq * inv, abs * inv};
}

Image crop(const Image& img, int x, int y, int w, int h) {
    // Written so that no sum can overflow int.
    if (w <= 0 || h <= 0 || x < 0 || y < 0 || x > img.width - w || y > img.height - h)
        throw InputError(
            fmt::format("crop window {}x{} at ({}, {}) is outside the {}x{} image", w, h, x, y, img.width, img.height));
    Image out(w, h);
    for (int row = 0; row < h; ++row) {
        const float* src = img.at(x, y + row);
        std::copy(src, src + 3 * std::size_t(w), out.at(0, row));
    }
    return out;
}

}  // namespace tripath
