#include "evaluation/error_map.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.h"

namespace tripath {

namespace {

// The ramp's stops in 8-bit sRGB, evenly spaced in log10 e; interpolated in sRGB, so equal steps
// in log error look like equal steps of colour.
constexpr std::array<std::array<float, 3>, 5> kStops{{{0, 0, 4}, {87, 16, 110}, {188, 55, 84}, {249, 142, 9}, {252, 255, 164}}};

// The map's position of e in [0, 1].
double position(double e) {
    if (!(e > kErrorMapLow)) return 0;  // also 0 and NaN-free inputs below the scale
    return std::min(1.0, std::log10(e / kErrorMapLow) / std::log10(kErrorMapHigh / kErrorMapLow));
}

Rgb colourAt(double t) {
    const double s = t * (kStops.size() - 1);
    const size_t i = std::min(kStops.size() - 2, size_t(s));
    const double f = s - double(i);
    auto mix = [&](int c) { return uint8_t(std::lround(kStops[i][c] + f * (kStops[i + 1][c] - kStops[i][c]))); };
    return fromSrgb(mix(0), mix(1), mix(2));
}

}  // namespace

Rgb errorColour(double e) { return colourAt(std::isnan(e) ? 1.0 : position(e)); }

Image errorMap(const Image& test, const Image& reference, double epsilon) {
    if (test.width != reference.width || test.height != reference.height)
        throw InputError(fmt::format("error map: image is {}x{}, reference {}x{}", test.width, test.height, reference.width,
                                     reference.height));
    Image out(test.width, test.height);
    for (size_t p = 0; p < test.pixelCount(); ++p) {
        double e = 0;
        for (int c = 0; c < 3; ++c) {
            const double d = double(test.rgb[3 * p + c]) - reference.rgb[3 * p + c];
            e += d * d / (double(reference.rgb[3 * p + c]) * reference.rgb[3 * p + c] + epsilon);
        }
        const Rgb col = errorColour(e / 3);
        out.rgb[3 * p] = col.r;
        out.rgb[3 * p + 1] = col.g;
        out.rgb[3 * p + 2] = col.b;
    }
    return out;
}

Sheet errorColourBar(int width, const Theme& theme) {
    constexpr int kMargin = 40;
    const int decades = int(std::lround(std::log10(kErrorMapHigh / kErrorMapLow)));
    std::vector<std::string> ticks;
    for (int d = 0; d <= decades; ++d) ticks.push_back(fmt::format("1e{}", int(std::log10(kErrorMapLow)) + d));
    return colourBar({"relative squared error per pixel, (x - r)^2 / (r^2 + 0.01):", colourAt, ticks, width,
                      std::min(width - 2 * kMargin, 640), kMargin},
                     theme);
}

}  // namespace tripath
