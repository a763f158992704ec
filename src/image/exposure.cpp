// A preview's automatic exposure and the writer that applies it (exposure.h).
#include "image/exposure.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/vec.h"

namespace tripath {

float luminancePercentile(const Image& img, float percentile) {
    std::vector<float> lum;
    lum.reserve(img.pixelCount());
    for (size_t i = 0; i < img.pixelCount(); ++i) {
        const float* p = img.rgb.data() + 3 * i;
        const float l = luminance(Vec3(p[0], p[1], p[2]));
        if (l > 0 && std::isfinite(l)) lum.push_back(l);
    }
    if (lum.empty()) return 0.0f;
    const double rank = std::round(double(percentile) * double(lum.size() - 1));
    const auto k = static_cast<size_t>(std::clamp(rank, 0.0, double(lum.size() - 1)));
    std::nth_element(lum.begin(), lum.begin() + long(k), lum.end());
    return lum[k];
}

float autoExposureStops(const Image& img) {
    const float white = luminancePercentile(img, kAutoExposurePercentile);
    if (!(white > 0)) return 0.0f;
    return float(std::round(-3.0 * std::log2(double(white))) / 3.0);
}

float writePreviewPng(const std::string& path, const Image& img, std::optional<float> exposureStops) {
    const float stops = exposureStops ? *exposureStops : autoExposureStops(img);
    writePng(path, img, stops);
    return stops;
}

}  // namespace tripath
