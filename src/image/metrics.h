// Error metrics for comparing a render against a reference, as used in the
// convergence tables.
#pragma once
#include "image/image.h"

namespace tripath {

struct ErrorMetrics {
    double relMse;  // mean of (x - r)^2 / (r^2 + epsilon)
    double mse;     // mean of (x - r)^2
    double mae;     // mean of |x - r|
};

// Means are over all pixels and all three channels. epsilon keeps relMSE
// finite where the reference is black. Throws InputError if sizes differ.
// NaNs in either image propagate into the result on purpose: a NaN pixel is
// a bug to see, not to average away.
ErrorMetrics compareImages(const Image& test, const Image& reference, double epsilon = 0.01);

// The w x h window whose top-left corner is (x, y). Throws InputError unless
// the window lies inside the image and w, h > 0.
Image crop(const Image& img, int x, int y, int w, int h);

}  // namespace tripath
