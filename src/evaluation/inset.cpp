#include "evaluation/inset.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "core/error.h"

namespace tripath {

namespace {

// Summed-area table of the per-pixel relative squared error (three channels added): any
// window's total in four look-ups.
class ErrorTable {
public:
    ErrorTable(const Image& img, const Image& ref, double epsilon) : w_(img.width + 1), sums_(size_t(w_) * (img.height + 1)) {
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                double e = 0;
                for (int c = 0; c < 3; ++c) {
                    const double r = ref.at(x, y)[c], d = img.at(x, y)[c] - r;
                    e += d * d / (r * r + epsilon);
                }
                // A NaN pixel would poison every window that contains it; counted as huge instead.
                if (!(e == e)) e = 1e30;
                at(x + 1, y + 1) = e + at(x, y + 1) + at(x + 1, y) - at(x, y);
            }
    }
    double window(int x, int y, int w, int h) const { return at(x + w, y + h) - at(x, y + h) - at(x + w, y) + at(x, y); }

private:
    double& at(int x, int y) { return sums_[size_t(y) * w_ + x]; }
    double at(int x, int y) const { return sums_[size_t(y) * w_ + x]; }
    int w_;
    std::vector<double> sums_;
};

}  // namespace

Region regionOfLargestDifference(const Image& reference, const std::vector<Image>& images, int w, int h,
                                 double epsilon) {
    if (w <= 0 || h <= 0 || w > reference.width || h > reference.height)
        throw InputError(fmt::format("inset window {}x{} does not fit the {}x{} image", w, h, reference.width,
                                     reference.height));
    std::vector<ErrorTable> tables;
    for (const Image& img : images) {
        if (img.width != reference.width || img.height != reference.height)
            throw InputError(fmt::format("cannot compare a {}x{} image with a {}x{} reference", img.width, img.height,
                                         reference.width, reference.height));
        tables.emplace_back(img, reference, epsilon);
    }
    const int stepX = std::max(1, (reference.width - w) / 32), stepY = std::max(1, (reference.height - h) / 32);
    Region best{(reference.width - w) / 2, (reference.height - h) / 2, w, h};
    double bestScore = -std::numeric_limits<double>::infinity();
    for (int y = 0; y <= reference.height - h; y += stepY)
        for (int x = 0; x <= reference.width - w; x += stepX) {
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (const ErrorTable& t : tables) {
                const double e = t.window(x, y, w, h);
                lo = std::min(lo, e);
                hi = std::max(hi, e);
            }
            const double score = tables.size() > 1 ? hi - lo : hi;
            if (score > bestScore) {
                bestScore = score;
                best = {x, y, w, h};
            }
        }
    return best;
}

}  // namespace tripath
