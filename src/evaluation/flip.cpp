// LDR-FLIP and HDR-FLIP (flip.h), written from the papers' descriptions: [1] for the colour and
// feature pipelines of LDR-FLIP, [2] for the exposure range and tone mapping of HDR-FLIP. Every
// 2-D filter of [1] is a product of two 1-D kernels, or (the blue-yellow contrast sensitivity) a
// weighted sum of two such products, so each is applied as passes over rows and then columns:
// O(r) work per pixel rather than O(r²), with the same result as the 2-D kernel.
#include "evaluation/flip.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "core/error.h"

namespace tripath {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// [1]'s colour pipeline: the HyAB distance is raised to q_c, then the first p_c of its range
// (relative to the largest distance in the gamut) is stretched onto [0, p_t] and the rest
// compressed onto [p_t, 1].
constexpr double kQc = 0.7, kPc = 0.4, kPt = 0.95;
// [1]'s feature pipeline: the detectors' width w in degrees (σ = w/2, in pixels w/2 × ppd), and
// the exponent on the normalised feature difference.
constexpr double kFeatureWidth = 0.082, kQf = 0.5;
// [2]'s exposure range: the tone mapped value that the reference's maximum (first exposure) and
// median (last exposure) luminance reach.
constexpr double kExposureTarget = 0.85;

// [2]'s tone mapper, a rational function y = (k0 x² + k1 x + k2) / (k3 x² + k4 x + k5): Narkowicz's
// fit of the ACES filmic curve (2.51, 0.03, 2.43, 0.59, 0.14) with the fit's input scale 0.6 folded
// into the coefficients.
constexpr std::array<double, 6> kAces = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};

// Linear sRGB to CIE XYZ: the sRGB primaries with the D65 white (IEC 61966-2-1). Its middle row is
// the luminance Y; its row sums are the white point every normalisation below divides by.
constexpr double kRgbToXyz[3][3] = {{0.412390799, 0.357584339, 0.180480788},
                                    {0.212639006, 0.715168679, 0.072192315},
                                    {0.019330819, 0.119194780, 0.950532152}};

using Matrix = std::array<std::array<double, 3>, 3>;
using Colour = std::array<double, 3>;

Matrix inverse(const double m[3][3]) {
    Matrix inv;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            // Cofactor of m[j][i], by the cyclic-index rule (no sign bookkeeping needed).
            const int j1 = (j + 1) % 3, j2 = (j + 2) % 3, i1 = (i + 1) % 3, i2 = (i + 2) % 3;
            inv[i][j] = m[j1][i1] * m[j2][i2] - m[j1][i2] * m[j2][i1];
        }
    const double det = m[0][0] * inv[0][0] + m[0][1] * inv[1][0] + m[0][2] * inv[2][0];
    for (auto& row : inv)
        for (double& v : row) v /= det;
    return inv;
}

const Matrix kXyzToRgb = inverse(kRgbToXyz);
const Colour kWhite = {kRgbToXyz[0][0] + kRgbToXyz[0][1] + kRgbToXyz[0][2],
                       kRgbToXyz[1][0] + kRgbToXyz[1][1] + kRgbToXyz[1][2],
                       kRgbToXyz[2][0] + kRgbToXyz[2][1] + kRgbToXyz[2][2]};

// Clipping that lets NaN through (both comparisons are false for NaN).
float clip01(float v) { return v < 0 ? 0.0f : (v > 1 ? 1.0f : v); }
// The larger of a and b, NaN if either is.
float maxOrNaN(float a, float b) { return std::isnan(b) || a < b ? b : a; }

double luminance(const float* rgb) {
    return kRgbToXyz[1][0] * rgb[0] + kRgbToXyz[1][1] * rgb[1] + kRgbToXyz[1][2] * rgb[2];
}

// XYZ relative to the white point.
Colour normalisedXyz(const float* rgb) {
    Colour c;
    for (int i = 0; i < 3; ++i)
        c[i] = (kRgbToXyz[i][0] * rgb[0] + kRgbToXyz[i][1] * rgb[1] + kRgbToXyz[i][2] * rgb[2]) / kWhite[i];
    return c;
}

// [1]'s linearised YCxCz: CIELAB's opponent axes without its cube root, so linear in XYZ and fit
// for filtering. Y = 116 y − 16, Cx = 500 (x − y), Cz = 200 (y − z), with x, y, z = X/Xn, Y/Yn, Z/Zn.
Colour linearRgbToYcxcz(const float* rgb) {
    const Colour n = normalisedXyz(rgb);
    return {116 * n[1] - 16, 500 * (n[0] - n[1]), 200 * (n[1] - n[2])};
}

Colour ycxczToLinearRgb(const Colour& o) {
    const double y = (o[0] + 16) / 116;
    const Colour xyz = {(y + o[1] / 500) * kWhite[0], y * kWhite[1], (y - o[2] / 200) * kWhite[2]};
    Colour rgb;
    for (int i = 0; i < 3; ++i)
        rgb[i] = kXyzToRgb[i][0] * xyz[0] + kXyzToRgb[i][1] * xyz[1] + kXyzToRgb[i][2] * xyz[2];
    return rgb;
}

// CIELAB with [1]'s Hunt adjustment: the chroma axes scaled by 0.01 L, so that dark colours, whose
// chroma one sees less of, differ less.
Colour huntAdjustedLab(const float* rgb) {
    constexpr double delta = 6.0 / 29;
    const Colour n = normalisedXyz(rgb);
    Colour f;
    for (int i = 0; i < 3; ++i)
        f[i] = n[i] > delta * delta * delta ? std::cbrt(n[i]) : n[i] / (3 * delta * delta) + 4.0 / 29;
    const double L = 116 * f[1] - 16;
    return {L, 0.01 * L * 500 * (f[0] - f[1]), 0.01 * L * 200 * (f[1] - f[2])};
}

// [1]'s HyAB distance: city-block in lightness, Euclidean in the chroma plane.
double hyab(const Colour& p, const Colour& q) {
    return std::fabs(p[0] - q[0]) + std::hypot(p[1] - q[1], p[2] - q[2]);
}

// The largest colour distance, after q_c, in the gamut: [1] takes it between green and blue.
double maxColourDistance() {
    const float green[3] = {0, 1, 0}, blue[3] = {0, 0, 1};
    return std::pow(hyab(huntAdjustedLab(green), huntAdjustedLab(blue)), kQc);
}

// [1]'s colour error ΔE_c from the HyAB distance: raise to q_c, then stretch and compress onto [0, 1].
float colourError(double distance) {
    static const double cmax = maxColourDistance();
    const double e = std::pow(distance, kQc), knee = kPc * cmax;
    return float(e < knee ? kPt / knee * e : kPt + (e - knee) / (cmax - knee) * (1 - kPt));
}

// One channel of an image, row-major.
struct Plane {
    int width, height;
    std::vector<float> v;
    Plane(int w, int h) : width(w), height(h), v(std::size_t(w) * std::size_t(h)) {}
    float* row(int y) { return v.data() + std::size_t(y) * std::size_t(width); }
    const float* row(int y) const { return v.data() + std::size_t(y) * std::size_t(width); }
};

// A 1-D kernel of 2r + 1 taps, centre at r. Images are extended by repeating their border pixels.
using Kernel = std::vector<float>;

Plane filterRows(const Plane& in, const Kernel& k) {
    const int r = int(k.size() / 2), w = in.width;
    Plane out(w, in.height);
    std::vector<float> padded(std::size_t(w + 2 * r));
    for (int y = 0; y < in.height; ++y) {
        const float* src = in.row(y);
        for (int i = 0; i < w + 2 * r; ++i) padded[std::size_t(i)] = src[std::clamp(i - r, 0, w - 1)];
        float* dst = out.row(y);
        for (int x = 0; x < w; ++x) {
            float sum = 0;
            for (int j = 0; j <= 2 * r; ++j) sum += k[std::size_t(j)] * padded[std::size_t(x + j)];
            dst[x] = sum;
        }
    }
    return out;
}

Plane filterColumns(const Plane& in, const Kernel& k) {
    const int r = int(k.size() / 2), h = in.height;
    Plane out(in.width, h);
    for (int y = 0; y < h; ++y) {
        float* dst = out.row(y);
        for (int j = 0; j <= 2 * r; ++j) {
            const float* src = in.row(std::clamp(y + j - r, 0, h - 1));
            const float kj = k[std::size_t(j)];
            for (int x = 0; x < in.width; ++x) dst[x] += kj * src[x];
        }
    }
    return out;
}

// [1]'s contrast sensitivity functions in the spatial domain, one per opponent channel, each a sum
// of Gaussians a √(π/b) exp(−π² d² / b) of the distance d in degrees: achromatic, red-green, and
// blue-yellow (two Gaussians).
struct CsfGaussian {
    double a, b;
};
const std::vector<CsfGaussian> kCsf[3] = {{{1, 0.0047}}, {{1, 0.0053}}, {{34.1, 0.04}, {13.5, 0.025}}};
constexpr double kCsfWidestB = 0.04;

// A channel's filter as separable terms: weight, and the 1-D kernel (sum 1) used on rows and columns.
using CsfFilter = std::vector<std::pair<float, Kernel>>;

// The same radius serves every channel: 3 standard deviations of the widest Gaussian, whose
// σ = √(b / 2π²) degrees.
CsfFilter csfFilter(const std::vector<CsfGaussian>& gaussians, double ppd) {
    const int r = int(std::ceil(3 * std::sqrt(kCsfWidestB / (2 * std::numbers::pi * std::numbers::pi)) * ppd));
    CsfFilter filter;
    double total = 0;
    for (const auto& [a, b] : gaussians) {
        Kernel k(std::size_t(2 * r + 1));
        double sum = 0;
        for (int i = -r; i <= r; ++i) {
            const double d = i / ppd;
            sum += k[std::size_t(i + r)] = float(std::exp(-std::numbers::pi * std::numbers::pi * d * d / b));
        }
        for (float& v : k) v = float(v / sum);
        // The 2-D Gaussian's share of the 2-D kernel's sum: amplitude times (1-D sum)².
        const double share = a * std::sqrt(std::numbers::pi / b) * sum * sum;
        filter.emplace_back(float(share), std::move(k));
        total += share;
    }
    for (auto& term : filter) term.first = float(term.first / total);  // the 2-D kernel sums to 1
    return filter;
}

Plane applyCsf(const Plane& in, const CsfFilter& filter) {
    Plane out(in.width, in.height);
    for (const auto& [weight, k] : filter) {
        const Plane term = filterColumns(filterRows(in, k), k);
        for (std::size_t i = 0; i < out.v.size(); ++i) out.v[i] += weight * term.v[i];
    }
    return out;
}

// [1]'s feature detectors: the first (edges) and second (points) derivatives of a Gaussian of
// σ = w/2 × ppd pixels over 3σ, each 2-D kernel the product of the derivative along one axis and the
// Gaussian along the other. The Gaussian is scaled to sum 1 and each derivative's positive and
// negative taps to sum +1 and −1, which is [1]'s normalisation of the 2-D kernel, factor by factor.
struct FeatureKernels {
    Kernel gaussian, edge, point;
};

Kernel normaliseSigns(Kernel k) {
    double positive = 0, negative = 0;
    for (float v : k) (v > 0 ? positive : negative) += v;
    for (float& v : k) v = float(v > 0 ? v / positive : v / -negative);
    return k;
}

FeatureKernels featureKernels(double ppd) {
    const double sigma = 0.5 * kFeatureWidth * ppd;
    const int r = int(std::ceil(3 * sigma));
    FeatureKernels f;
    double sum = 0;
    for (int i = -r; i <= r; ++i) {
        const double g = std::exp(-i * i / (2 * sigma * sigma));
        sum += g;
        f.gaussian.push_back(float(g));
        f.edge.push_back(float(-i * g));
        f.point.push_back(float((i * i / (sigma * sigma) - 1) * g));
    }
    for (float& v : f.gaussian) v = float(v / sum);
    f.edge = normaliseSigns(std::move(f.edge));
    f.point = normaliseSigns(std::move(f.point));
    return f;
}

struct Filters {
    CsfFilter csf[3];
    FeatureKernels features;
    explicit Filters(double ppd)
        : csf{csfFilter(kCsf[0], ppd), csfFilter(kCsf[1], ppd), csfFilter(kCsf[2], ppd)},
          features(featureKernels(ppd)) {}
};

// [1]'s colour pipeline up to the distance: linearised YCxCz, each channel filtered by its contrast
// sensitivity function, back to linear RGB clipped to [0, 1], then Hunt-adjusted CIELAB.
std::array<Plane, 3> perceivedColours(const std::vector<float>& rgb, int w, int h, const Filters& f) {
    std::array<Plane, 3> opponent = {Plane(w, h), Plane(w, h), Plane(w, h)};
    for (std::size_t p = 0; p < opponent[0].v.size(); ++p) {
        const Colour o = linearRgbToYcxcz(&rgb[3 * p]);
        for (int c = 0; c < 3; ++c) opponent[std::size_t(c)].v[p] = float(o[std::size_t(c)]);
    }
    for (int c = 0; c < 3; ++c) opponent[std::size_t(c)] = applyCsf(opponent[std::size_t(c)], f.csf[c]);
    for (std::size_t p = 0; p < opponent[0].v.size(); ++p) {
        const Colour seen = ycxczToLinearRgb({opponent[0].v[p], opponent[1].v[p], opponent[2].v[p]});
        const float clipped[3] = {clip01(float(seen[0])), clip01(float(seen[1])), clip01(float(seen[2]))};
        const Colour lab = huntAdjustedLab(clipped);
        for (int c = 0; c < 3; ++c) opponent[std::size_t(c)].v[p] = float(lab[std::size_t(c)]);
    }
    return opponent;
}

// [1]'s feature pipeline up to the difference: the magnitudes of the edge and point responses
// (each a 2-vector of the x and y kernels) on the luminance relative to white, unfiltered.
struct Features {
    Plane edge, point;
};

Features features(const std::vector<float>& rgb, int w, int h, const FeatureKernels& k) {
    Plane y(w, h);
    for (std::size_t p = 0; p < y.v.size(); ++p) y.v[p] = float(luminance(&rgb[3 * p]) / kWhite[1]);
    const Plane alongX = filterRows(y, k.gaussian);  // smoothed along x, for the y derivatives
    const Plane edgeX = filterColumns(filterRows(y, k.edge), k.gaussian), edgeY = filterColumns(alongX, k.edge);
    const Plane pointX = filterColumns(filterRows(y, k.point), k.gaussian), pointY = filterColumns(alongX, k.point);
    Features f{Plane(w, h), Plane(w, h)};
    for (std::size_t p = 0; p < y.v.size(); ++p) {
        f.edge.v[p] = std::hypot(edgeX.v[p], edgeY.v[p]);
        f.point.v[p] = std::hypot(pointX.v[p], pointY.v[p]);
    }
    return f;
}

// Both terms of LDR-FLIP for interleaved linear RGB in [0, 1] (NaN allowed).
FlipTerms flipTerms(const std::vector<float>& test, const std::vector<float>& reference, int w, int h,
                    const Filters& f) {
    const std::size_t n = std::size_t(w) * std::size_t(h);
    FlipTerms terms{std::vector<float>(n), std::vector<float>(n)};
    {
        const auto t = perceivedColours(test, w, h, f), r = perceivedColours(reference, w, h, f);
        for (std::size_t p = 0; p < n; ++p)
            terms.colour[p] = colourError(hyab({t[0].v[p], t[1].v[p], t[2].v[p]}, {r[0].v[p], r[1].v[p], r[2].v[p]}));
    }
    const Features t = features(test, w, h, f.features), r = features(reference, w, h, f.features);
    for (std::size_t p = 0; p < n; ++p) {
        // ΔE_f = (max(|Δ edge|, |Δ point|) / √2)^q_f, the √2 the largest difference of magnitudes.
        const float difference =
            maxOrNaN(std::fabs(t.edge.v[p] - r.edge.v[p]), std::fabs(t.point.v[p] - r.point.v[p]));
        terms.feature[p] = float(std::pow(difference / std::numbers::sqrt2, kQf));
    }
    return terms;
}

// [1]'s combination: features sharpen the colour error, ΔE = ΔE_c^(1 − ΔE_f).
std::vector<float> combine(const FlipTerms& terms) {
    std::vector<float> e(terms.colour.size());
    for (std::size_t p = 0; p < e.size(); ++p) e[p] = std::pow(terms.colour[p], 1 - terms.feature[p]);
    return e;
}

void checkInputs(const Image& test, const Image& reference, double ppd) {
    if (test.width != reference.width || test.height != reference.height)
        throw InputError(fmt::format("FLIP: cannot compare images of different sizes: {}x{} vs reference {}x{}",
                                     test.width, test.height, reference.width, reference.height));
    if (test.pixelCount() == 0) throw InputError("FLIP: the images are empty");
    if (test.rgb.size() != 3 * test.pixelCount() || reference.rgb.size() != 3 * reference.pixelCount())
        throw InputError("FLIP: a pixel buffer does not match its image's size");
    if (!(ppd > 0 && std::isfinite(ppd)))
        throw InputError(fmt::format("FLIP: pixels per degree must be positive and finite, not {}", ppd));
}

// LDR inputs: non-finite values become NaN (not clipped to a colour), the rest clipped to [0, 1].
std::vector<float> linearFromSrgb(const Image& img) {
    std::vector<float> linear(img.rgb.size());
    for (std::size_t i = 0; i < linear.size(); ++i)
        linear[i] = std::isfinite(img.rgb[i]) ? srgbDecode(clip01(img.rgb[i])) : kNaN;
    return linear;
}

// [2]'s tone mapping of a linear value at exposure scale 2^c, clipped to [0, 1]; NaN if v is not
// finite, 0 if negative. Above x = 1 the ratio is evaluated divided through by x², so that no
// finite input overflows.
float toneMap(float v, double scale) {
    if (!std::isfinite(v)) return kNaN;
    const double x = std::max(0.0, double(v) * scale);
    const auto& k = kAces;
    const double y = x <= 1 ? (k[0] * x * x + k[1] * x + k[2]) / (k[3] * x * x + k[4] * x + k[5])
                            : (k[0] + (k[1] + k[2] / x) / x) / (k[3] + (k[4] + k[5] / x) / x);
    return clip01(float(y));
}

// The input x ≥ 0 that the tone mapper takes to t: the positive root of
// (k0 − t k3) x² + (k1 − t k4) x + (k2 − t k5) = 0 ([2]).
double inverseToneMap(double t) {
    const auto& k = kAces;
    const double a = k[0] - t * k[3], b = k[1] - t * k[4], c = k[2] - t * k[5];
    return (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
}

// The median as [2]'s reference implementation takes it: element ⌊n/2⌋ in sorted order.
double median(std::vector<double> v) {
    const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

}  // namespace

FlipExposures flipExposures(const Image& reference) {
    if (reference.pixelCount() == 0) throw InputError("FLIP: the reference image is empty");
    if (reference.rgb.size() != 3 * reference.pixelCount())
        throw InputError("FLIP: the reference's pixel buffer does not match its size");
    std::vector<double> all, positive;
    for (std::size_t p = 0; p < reference.pixelCount(); ++p) {
        const double y = luminance(&reference.rgb[3 * p]);
        if (!std::isfinite(y)) continue;
        all.push_back(std::max(0.0, y));  // what the tone mapper sees of a negative pixel
        if (y > 0) positive.push_back(y);
    }
    double high = 1, middle = 1;  // an all-black reference: as if its luminance were 1 everywhere
    if (!positive.empty()) {
        high = *std::max_element(positive.begin(), positive.end());
        middle = median(std::move(all));
        if (middle == 0) middle = median(std::move(positive));
    }
    const double x = inverseToneMap(kExposureTarget);
    FlipExposures e;
    e.start = std::log2(x / high);
    e.stop = std::log2(x / middle);
    e.count = std::max(2, int(std::ceil(e.stop - e.start)));
    return e;
}

std::vector<float> hdrFlipMap(const Image& test, const Image& reference, const FlipExposures& exposures,
                              double pixelsPerDegree) {
    checkInputs(test, reference, pixelsPerDegree);
    if (!std::isfinite(exposures.start) || !std::isfinite(exposures.stop) || exposures.count < 1)
        throw InputError(fmt::format("FLIP: exposures must be finite with a count of at least 1, not {} to {} in {}",
                                     exposures.start, exposures.stop, exposures.count));
    const Filters filters(pixelsPerDegree);
    const double step = exposures.count > 1 ? (exposures.stop - exposures.start) / (exposures.count - 1) : 0;
    std::vector<float> flip(test.pixelCount(), 0.0f), t(test.rgb.size()), r(reference.rgb.size());
    for (int i = 0; i < exposures.count; ++i) {
        const double scale = std::exp2(exposures.start + i * step);
        for (std::size_t j = 0; j < t.size(); ++j) {
            t[j] = toneMap(test.rgb[j], scale);
            r[j] = toneMap(reference.rgb[j], scale);
        }
        // [2]: each pixel's error is its largest over the exposures.
        const std::vector<float> e = combine(flipTerms(t, r, test.width, test.height, filters));
        for (std::size_t p = 0; p < flip.size(); ++p) flip[p] = maxOrNaN(flip[p], e[p]);
    }
    return flip;
}

double hdrFlip(const Image& test, const Image& reference, const FlipExposures& exposures, double pixelsPerDegree) {
    const std::vector<float> map = hdrFlipMap(test, reference, exposures, pixelsPerDegree);
    double sum = 0;
    for (float v : map) sum += v;
    return sum / double(map.size());
}

FlipTerms ldrFlipTerms(const Image& testSrgb, const Image& referenceSrgb, double pixelsPerDegree) {
    checkInputs(testSrgb, referenceSrgb, pixelsPerDegree);
    return flipTerms(linearFromSrgb(testSrgb), linearFromSrgb(referenceSrgb), testSrgb.width, testSrgb.height,
                     Filters(pixelsPerDegree));
}

std::vector<float> ldrFlipMap(const Image& testSrgb, const Image& referenceSrgb, double pixelsPerDegree) {
    return combine(ldrFlipTerms(testSrgb, referenceSrgb, pixelsPerDegree));
}

}  // namespace tripath
