// Error metrics of a render against a reference (see metrics.h for the definitions).
#include "evaluation/metrics.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "core/error.h"

namespace tripath {

std::size_t tailPixelCount(std::size_t pixels) { return pixels == 0 ? 0 : (pixels - 1) / 1000 + 1; }

double perSampleRelVariance(double relMse, double spp) { return relMse * spp; }

ErrorMetrics compareImages(const Image& test, const Image& reference, double epsilon) {
    if (test.width != reference.width || test.height != reference.height)
        throw InputError(fmt::format("cannot compare images of different sizes: {}x{} vs reference {}x{}", test.width,
                                     test.height, reference.width, reference.height));
    const std::size_t n = test.rgb.size();
    if (n != reference.rgb.size() || n != 3 * test.pixelCount())
        throw InputError("cannot compare images: pixel buffer does not match the image size");
    if (n == 0) return {0.0, 0.0, 0.0, 0.0};

    // Accumulate in double: a float sum over millions of samples would lose
    // the small errors of a converged render. relMSE is the sum of the
    // per-pixel terms e_p, so it and the tail share use the very same numbers.
    std::vector<double> perPixel(n / 3);
    double rel = 0, sq = 0, abs = 0;
    for (std::size_t p = 0; p < perPixel.size(); ++p) {
        double e = 0;
        for (std::size_t i = 3 * p; i < 3 * p + 3; ++i) {
            const double r = reference.rgb[i];
            const double d = double(test.rgb[i]) - r;
            e += d * d / (r * r + epsilon);
            sq += d * d;
            abs += std::fabs(d);
        }
        perPixel[p] = e;
        rel += e;
    }

    // Every e_p is >= 0, so a finite total means no NaN or infinity among them,
    // and the partial sort below sees a proper ordering.
    double tail = 0;
    if (!std::isfinite(rel)) {
        tail = std::numeric_limits<double>::quiet_NaN();
    } else if (rel > 0) {
        const auto k = std::ptrdiff_t(tailPixelCount(perPixel.size()));
        std::nth_element(perPixel.begin(), perPixel.begin() + (k - 1), perPixel.end(), std::greater<>());
        double worst = 0;
        for (std::ptrdiff_t i = 0; i < k; ++i) worst += perPixel[std::size_t(i)];
        tail = std::min(1.0, worst / rel);  // the two sums add in different orders
    }
    const double inv = 1.0 / double(n);
    return {rel * inv, sq * inv, abs * inv, tail};
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

double relMseWithoutTail(const ErrorMetrics& m, std::size_t pixels) {
    const std::size_t k = tailPixelCount(pixels);
    if (pixels <= k) return 0;
    return m.relMse * (1 - m.tailShare) * double(pixels) / double(pixels - k);
}

}  // namespace tripath
