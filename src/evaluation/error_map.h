// Where the error is: each pixel's relative squared error against the reference as a false colour
// on a log scale, and the colour bar that reads it. The error is the per-pixel term of relMSE
// (metrics.h), averaged over the channels: e_p = (1/3) Σ_c (x_pc − r_pc)² / (r_pc² + ε), so a map
// shows where a method's relMSE comes from (fireflies as isolated bright dots, a bias as a region).
#pragma once
#include <string>

#include "evaluation/sheet.h"
#include "image/draw.h"
#include "image/image.h"

namespace tripath {

// The scale: errors at or below kErrorMapLow get its colour (dark), at or above kErrorMapHigh the
// brightest; log-linear in between.
constexpr double kErrorMapLow = 1e-4, kErrorMapHigh = 10;

// The colour of relative squared error e: a ramp from near-black through purple and orange to
// pale yellow, brighter for larger e, so it reads in grey too.
Rgb errorColour(double e);

// Per-pixel false-colour map of test against reference (same size, else InputError).
Image errorMap(const Image& test, const Image& reference, double epsilon = 0.01);

// A horizontal colour bar `width` pixels wide with the decades labelled, titled
// "relative squared error per pixel": to print under error maps.
Sheet errorColourBar(int width, const Theme& theme = kDarkTheme);

}  // namespace tripath
