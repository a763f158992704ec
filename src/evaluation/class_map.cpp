#include "evaluation/class_map.h"

#include <algorithm>
#include <array>
#include <string_view>

namespace tripath {

const char* const kClassMapLegend =
    "auto's classes of strategies per 16x16 tile in its last stretch of passes: red adds the connections, green "
    "light tracing, blue the merges, grey the camera walk's own (alone: dark grey; all four: white)";

namespace {

// Each class's channel and the colour it adds.
struct ClassColour {
    std::string_view channel;
    std::array<float, 3> rgb;
};
constexpr std::array<ClassColour, 4> kColours{{{"auto.pt", {0.25f, 0.25f, 0.25f}},
                                               {"auto.connect", {0.75f, 0, 0}},
                                               {"auto.trace", {0, 0.75f, 0}},
                                               {"auto.merge", {0, 0, 0.75f}}}};

}  // namespace

Image classMap(const std::vector<ExrChannel>& channels, int width, int height) {
    const size_t pixels = size_t(width) * size_t(height);
    Image map(width, height);
    bool any = false;
    for (const ClassColour& colour : kColours) {
        const auto c = std::find_if(channels.begin(), channels.end(), [&](const ExrChannel& x) { return x.name == colour.channel; });
        if (c == channels.end() || c->values.size() != pixels) continue;
        any = true;
        for (size_t i = 0; i < pixels; ++i)
            for (int k = 0; k < 3; ++k) map.rgb[3 * i + k] += c->values[i] * colour.rgb[k];
    }
    return any ? map : Image{};
}

}  // namespace tripath
