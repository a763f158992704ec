// FLIP: a perceptual difference map between a render and its reference, per pixel in [0, 1]
// (0: no visible difference, 1: the largest). LDR-FLIP compares display-encoded images [1];
// HDR-FLIP compares linear radiance by tone mapping both images at a range of exposures, running
// LDR-FLIP on each and keeping each pixel's largest error [2]. Why beside relMSE (metrics.h):
// relMSE weighs every pixel's error by its value, FLIP by what a viewer alternating between the
// two images would notice (colour shifts, lost or added edges, fireflies), at a viewing distance.
//
// [1] P. Andersson, J. Nilsson, T. Akenine-Möller, M. Oskarsson, K. Åström, M. D. Fairchild,
//     "FLIP: A Difference Evaluator for Alternating Images", HPG 2020 (Proc. ACM CGIT 3(2)).
// [2] P. Andersson, J. Nilsson, P. Shirley, T. Akenine-Möller, "Visualizing Errors in Rendered
//     High Dynamic Range Images", Eurographics 2021 short papers.
//
// The API, and why it is cut this way:
// - flipExposures(reference) computes the exposure range once, from the reference only, and
//   hdrFlipMap/hdrFlip take it as an argument: every method of a scene is then judged at the same
//   exposures (a range taken from each test image would let a method move its own yardstick).
// - The range follows [2]'s start and stop exposures (the ACES fit reaches 0.85 at the reference's maximum luminance for
//   the first exposure, at its median for the last), except where [2]'s rule breaks: a median of 0,
//   common in renders where more than half the frame is empty background, gives an infinite last
//   exposure. Then the median is taken over the pixels of positive luminance only; a reference
//   with no such pixel (all black) gets the range of a reference of luminance 1 everywhere.
//   Non-finite reference pixels take no part in the range (they show up as NaN in the map).
// - NaN and ±infinity in either image give NaN in the map, within the filters' reach of the pixel
//   (about 10 pixels at the default viewing), and hdrFlip is then NaN: as with the other metrics,
//   a non-finite pixel is a bug to see, not to average away. Negative HDR values are clipped to 0
//   (the tone mapper is defined on [0, ∞)); LDR inputs are clipped to [0, 1].
// - ldrFlipTerms exposes the two terms LDR-FLIP combines, to show which one an error comes from.
//
// Every function throws InputError if the images' sizes differ, an image is empty, the pixel
// buffer does not match the size, pixelsPerDegree is not positive and finite, or the exposures
// are not finite or their count is below 1.
#pragma once
#include <vector>

#include "image/image.h"

namespace tripath {

// Pixels per degree of visual angle of the default viewing of [1]'s experiments: a 0.7 m wide monitor of
// 3840 pixels seen from 0.7 m, ppd = distance × (pixels / width) × π / 180 ≈ 67.02.
constexpr double kFlipPixelsPerDegree = 0.7 * (3840.0 / 0.7) * 3.14159265358979323846 / 180.0;

// The exposure compensations c (the HDR image is scaled by 2^c before tone mapping): `count`
// values evenly spaced from `start` to `stop`, both included; `start` alone when count is 1.
struct FlipExposures {
    double start = 0, stop = 0;
    int count = 2;
};

// [2]'s rule on the reference's luminance (see above for a median of 0): count = max(2, ⌈stop − start⌉).
FlipExposures flipExposures(const Image& reference);

// HDR-FLIP per pixel, row-major width × height values in [0, 1] (or NaN, see above).
std::vector<float> hdrFlipMap(const Image& test, const Image& reference, const FlipExposures& exposures,
                              double pixelsPerDegree = kFlipPixelsPerDegree);

// The mean of hdrFlipMap: the one number per image pair that FLIP's authors pool the map into.
double hdrFlip(const Image& test, const Image& reference, const FlipExposures& exposures,
               double pixelsPerDegree = kFlipPixelsPerDegree);

// LDR-FLIP per pixel, for images whose values are sRGB-encoded in [0, 1] (e.g. read from PNG).
std::vector<float> ldrFlipMap(const Image& testSrgb, const Image& referenceSrgb,
                              double pixelsPerDegree = kFlipPixelsPerDegree);

// The two per-pixel terms of LDR-FLIP, each in [0, 1]: the colour error ΔE_c ([1]'s colour pipeline) and
// the feature error ΔE_f ([1]'s feature pipeline). ldrFlipMap is their combination ΔE_c^(1 − ΔE_f).
struct FlipTerms {
    std::vector<float> colour, feature;
};
FlipTerms ldrFlipTerms(const Image& testSrgb, const Image& referenceSrgb,
                       double pixelsPerDegree = kFlipPixelsPerDegree);

}  // namespace tripath
