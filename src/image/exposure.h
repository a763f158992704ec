// The exposure of a preview, taken from the image itself: a render's radiance may lie anywhere
// (a model lit by point lights next to its surfaces reads 100 and more, a dim room 0.05), so a
// fixed exposure shows one scene as a white silhouette and another as black. The rule is one
// luminance percentile of the non-black pixels mapped to white: a black background does not
// count, and the brightest 2 % (an emitter, a highlight, a firefly) may clip. The PNG
// previews of `tripath render --png`, `tripath reference --png` and Python's write_png go
// through writePreviewPng; `tripath montage` scales its rows by the same percentile.
#pragma once
#include <optional>
#include <string>

#include "image/image.h"

namespace tripath {

// The `percentile` (in (0, 1]) of the luminance (core/vec.h: Rec. 709 weights) of the image's
// pixels whose luminance is positive and finite: of these n values in increasing order, the one
// at rank round(percentile × (n − 1)), counted from 0. 0 when there are none (a black image).
float luminancePercentile(const Image& img, float percentile);

// The percentile of a preview's automatic exposure: high, yet below the share of the pixels that
// a visible emitter covers (the Cornell box's light: 0.7-1 % of them, at any resolution).
constexpr float kAutoExposurePercentile = 0.98f;

// The exposure in stops that maps luminancePercentile(img, kAutoExposurePercentile) to 1 (white),
// rounded to the nearest third of a stop so that renders of one scene at other sample counts or
// seeds get the same exposure; 0 for a black image.
float autoExposureStops(const Image& img);

// writePng at `exposureStops`, or at autoExposureStops(img) when none is given. Returns the
// exposure used.
float writePreviewPng(const std::string& path, const Image& img, std::optional<float> exposureStops);

}  // namespace tripath
