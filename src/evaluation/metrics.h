// Error metrics for comparing a render against a reference, as used in the
// convergence tables and by `tripath compare`: relMSE, MSE, MAE, the share of
// the relMSE carried by the worst 0.1 % of pixels, and relMSE x spp.
#pragma once
#include <cstddef>

#include "image/image.h"

namespace tripath {

// Every sum below runs over the n = 3 * pixelCount values (pixels x channels).
// The relative squared error of one pixel p is the sum over its channels c,
//     e_p = sum_c (x_pc - r_pc)^2 / (r_pc^2 + epsilon),
// so relMse = (sum_p e_p) / n, and tailShare is built from the same e_p.
struct ErrorMetrics {
    double relMse;     // mean of (x - r)^2 / (r^2 + epsilon)
    double mse;        // mean of (x - r)^2
    double mae;        // mean of |x - r|
    double tailShare;  // (sum of e_p over the tailPixelCount() pixels of largest e_p) / (sum of all e_p)
};

// Means are over all pixels and all three channels. epsilon keeps relMSE
// finite where the reference is black. Throws InputError if sizes differ.
// NaNs in either image propagate into the result on purpose: a NaN pixel is
// a bug to see, not to average away (tailShare is then NaN too). tailShare is
// 0 when there is no error at all, and lies in [k/N, 1] otherwise (k the tail's
// pixel count, N the image's): the worst k pixels hold at least their count's
// share. Near 1: a few fireflies carry the error; near k/N: the error is even.
ErrorMetrics compareImages(const Image& test, const Image& reference, double epsilon = 0.01);

// relMSE with the tailPixelCount() pixels of largest e_p left out: (sum_p e_p − tail) / (3 (N − k)),
// from the metrics of an image of N pixels (the tail is tailShare of the sum). A mean that a few
// fireflies cannot dominate, reported beside relMSE (not instead of it: fireflies are error too).
double relMseWithoutTail(const ErrorMetrics& m, std::size_t pixels);

// How many pixels "the worst 0.1 %" of an image of `pixels` pixels is:
// ceil(pixels / 1000), so at least 0.1 % of them and at least one pixel
// (1 for up to 1000 pixels, 2 for 1001..2000, 66 for 256 x 256).
std::size_t tailPixelCount(std::size_t pixels);

// relMSE x spp. For an unbiased estimator the expected squared error after N
// independent samples per pixel is the one-sample variance over N, so relMSE x N
// is the per-sample relative variance (averaged over pixels and channels): a
// property of the sampling strategy, not of how long it ran. It means that only
// while the reference's own error is negligible against the render's (otherwise
// it grows with N) and the method has no bias (a bias makes it grow like N).
// Efficiency 1 / (relMSE x seconds) is then (spp / seconds) / (relMSE x spp):
// samples per second over per-sample relative variance.
double perSampleRelVariance(double relMse, double spp);

// The w x h window whose top-left corner is (x, y). Throws InputError unless
// the window lies inside the image and w, h > 0.
Image crop(const Image& img, int x, int y, int w, int h);

}  // namespace tripath
