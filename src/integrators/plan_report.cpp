#include "integrators/plan_report.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>

namespace tripath {

namespace {

constexpr std::array<std::pair<ClassBit, const char*>, 4> kClasses{
    {{kCameraWalkClass, "pt"}, {kConnectClass, "connect"}, {kTraceClass, "trace"}, {kMergeClass, "merge"}}};

}  // namespace

std::string classesName(uint8_t classes) {
    std::vector<std::string_view> names;
    for (const auto& [bit, name] : kClasses)
        if (classes & bit) names.push_back(name);
    return fmt::format("{}", fmt::join(names, "+"));
}

std::vector<ExrChannel> classChannels(const PlanReport& plans, int width, int height) {
    if (plans.tiles.empty() || plans.tilesAcross <= 0 || plans.tileSize <= 0) return {};
    std::vector<ExrChannel> channels;
    for (const auto& [bit, name] : kClasses) {
        ExrChannel c{fmt::format("auto.{}", name), std::vector<float>(size_t(width) * size_t(height))};
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const size_t tile = size_t(y / plans.tileSize) * size_t(plans.tilesAcross) + size_t(x / plans.tileSize);
                c.values[size_t(y) * size_t(width) + size_t(x)] = tile < plans.tiles.size() && (plans.tiles[tile] & bit) ? 1.0f : 0.0f;
            }
        channels.push_back(std::move(c));
    }
    return channels;
}

}  // namespace tripath
