// Choosing the region a comparison sheet magnifies: where the methods differ most.
#pragma once
#include <vector>

#include "image/draw.h"

namespace tripath {

// The w x h window (tried on a grid of about 32 x 32 positions) where the images' mean relative
// squared errors against the reference (the relMSE of metrics.h, per window) are furthest apart:
// the region that shows best how the methods differ. With a single image, where its error is
// largest. Throws InputError if the sizes differ or the window does not fit.
Region regionOfLargestDifference(const Image& reference, const std::vector<Image>& images, int w, int h,
                                 double epsilon = 0.01);

}  // namespace tripath
