#include "stats_report.h"

#include <fmt/format.h>
#include <sys/resource.h>

#include <cmath>

#include "core/byte_size.h"

namespace tripath::app {

std::string planReport(const PlanReport& plans) {
    if (plans.stretches.empty()) return "";
    std::string out = "  auto's plans, from the pass each starts at:";
    for (const auto& [first, plan] : plans.stretches) out += fmt::format(" {}: {};", first, plan);
    out.back() = '\n';
    if (!plans.tiles.empty() && plans.tilesAcross > 0) {
        // Each tile's classes by their initials: p the camera walk's, c connections, t light
        // tracing, m merges.
        out += fmt::format("  the classes of each {0}x{0} tile in the last stretch (p: pt's, c: connect, t: trace, m: merge):\n",
                           plans.tileSize);
        for (size_t t = 0; t < plans.tiles.size(); ++t) {
            const std::string name = classesName(plans.tiles[t]);
            std::string initials;
            for (size_t i = 0; i < name.size(); ++i)
                if (i == 0 || name[i - 1] == '+') initials += name[i];
            out += fmt::format("{}{:<5}", t % size_t(plans.tilesAcross) == 0 ? "    " : "", initials);
            if ((t + 1) % size_t(plans.tilesAcross) == 0 || t + 1 == plans.tiles.size()) out += "\n";
        }
    }
    if (plans.candidates.empty()) return out;
    out += "  the candidates at the last choice (relative variance per pass, cost per pass in traced rays, their product):\n";
    for (const PlanEstimate& c : plans.candidates)
        out += fmt::format("    {:<34}{:>12.4g}{:>12.4g}{:>12.4g}{}\n", c.plan, c.relativeVariance, c.cost,
                           c.relativeVariance * c.cost, c.uncovered ? "  cannot sample some light" : "");
    return out;
}

std::string statsReport(const RenderResult& r, uint64_t pixels) {
    const StatsSnapshot& s = r.stats;
    const double samples = double(r.passes) * double(pixels);
    const double seconds = r.seconds > 0 ? r.seconds : 1.0;
    std::string out = fmt::format("stats: {} passes x {} pixels = {:.4g} camera samples in {:.2f} s\n", r.passes, pixels,
                                  samples, r.seconds);
    out += fmt::format("  {:<24}{:>16}{:>14}{:>16}\n", "event", "total", "per sample", "per second");
    for (int i = 0; i < kEventCount; ++i) {
        const auto e = static_cast<Event>(i);
        out += fmt::format("  {:<24}{:>16}{:>14.4g}{:>16.4g}\n", eventName(e), s[e], samples > 0 ? s[e] / samples : 0.0,
                           s[e] / seconds);
    }
    const double rays = double(s[Event::ClosestHitRays] + s[Event::ShadowRays]);
    out += fmt::format("  rays of both kinds: {:.4g} per sample, {:.4g} M per second\n", samples > 0 ? rays / samples : 0.0,
                       rays / seconds / 1e6);
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    out += fmt::format("  memory: estimated {} ({}); the process's peak resident memory so far {}\n",
                       bytesText(r.memory.total()), r.memory.breakdown(), bytesText(uint64_t(usage.ru_maxrss) * 1024));
    out += planReport(r.plans);
    uint64_t working = 0;
    for (int i = 0; i < kPhaseCount; ++i)
        if (static_cast<Phase>(i) != Phase::Idle) working += s.phaseSamples[i];
    if (working == 0) return out;
    const uint64_t outside = s.phaseSamples[static_cast<int>(Phase::Idle)];
    out += fmt::format("  outside the phases below (pass set-up, TBB scheduling and waiting): {:.1f} % of the CPU time\n",
                       100.0 * double(outside) / double(working + outside));
    out += fmt::format("  share of the CPU time in each phase of the render loop ({} profiling samples, at most one per ms of "
                       "CPU; a tile's rays, BSDFs, connections and merges are its camera samples' time):\n", working);
    for (int i = 0; i < kPhaseCount; ++i) {
        const auto p = static_cast<Phase>(i);
        if (p == Phase::Idle) continue;
        const double share = double(s.phaseSamples[i]) / double(working);
        out += fmt::format("    {:<40}{:>6.1f} % ± {:.1f}\n", phaseName(p), 100.0 * share,
                           100.0 * std::sqrt(share * (1 - share) / double(working)));
    }
    return out;
}

}  // namespace tripath::app
