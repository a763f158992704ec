// What auto chose, as a picture to lay beside its image: each pixel coloured by the classes of
// strategies its tile ran in auto's last stretch of passes (the EXR's auto.* channels,
// integrators/plan_report.h). Red adds the connections, green light tracing, blue the merges, and
// a grey of a quarter the camera walk's own strategies: the camera walk alone is dark grey, every
// class white, light tracing alone pure green.
#pragma once
#include <vector>

#include "image/image.h"

namespace tripath {

// The caption that reads the colours.
extern const char* const kClassMapLegend;

// The picture of `channels` (a render's channels beside R, G, B) for a width × height image; an
// empty image when they hold no auto.* channels.
Image classMap(const std::vector<ExrChannel>& channels, int width, int height);

}  // namespace tripath
