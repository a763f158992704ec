#include "integrators/pass_plan.h"

namespace tripath {

StrategySet PassPlan::strategies() const {
    StrategySet set;  // every connection
    if (!lightTraces) set.minT = 2;
    if (!connects) {
        if (lightTraces)
            set.connects = false;
        else
            set.maxS = 1;
    }
    if (merges) set.merging = StrategySet::Merging::EveryVertex;
    set.unidirectional = unidirectional;
    return set;
}

uint8_t PassPlan::classes() const {
    if (lightPaths == 0) return kCameraWalkClass;
    return uint8_t((unidirectional ? kCameraWalkClass : 0) | (connects ? kConnectClass : 0) |
                   (lightTraces ? kTraceClass : 0) | (merges ? kMergeClass : 0));
}

TechniqueSums PassPlan::factors(double measuredLightPaths) const {
    const float share = static_cast<float>(lightPaths / measuredLightPaths);
    TechniqueSums f{};
    f[static_cast<int>(TechniqueClass::Unidirectional)] = unidirectional ? 1.0f : 0.0f;
    f[static_cast<int>(TechniqueClass::Connection)] = connects && lightPaths > 0 ? 1.0f : 0.0f;
    f[static_cast<int>(TechniqueClass::LightTracing)] = lightTraces ? share : 0.0f;
    f[static_cast<int>(TechniqueClass::Merge)] = merges ? share : 0.0f;
    return f;
}

PassPlan unionOf(std::span<const PassPlan> plans) {
    PassPlan u{plans.front().lightPaths, false, false, false, false};
    for (const PassPlan& p : plans) {
        u.connects = u.connects || p.connects;
        u.lightTraces = u.lightTraces || p.lightTraces;
        u.merges = u.merges || p.merges;
        u.unidirectional = u.unidirectional || p.unidirectional;
    }
    return u;
}

StrategySet measuredStrategies() { return {.merging = StrategySet::Merging::EveryVertex}; }

namespace {

class PlannedPasses final : public PixelSampleIntegrator {
public:
    PlannedPasses(const PassPlan& plan, IntegratorSettings settings, bool measures)
        : PixelSampleIntegrator(withLightPaths(settings, plan, measures)), plan_(plan), measures_(measures) {}
    std::string name() const override { return "auto"; }
    StrategySet strategies() const override { return plan_.strategies(); }
    std::optional<StrategySet> measuredStrategies() const override {
        return measures_ ? std::optional(tripath::measuredStrategies()) : std::nullopt;
    }

private:
    // The plan's N_L; a plan without light paths keeps the default N_L of the pass's constants
    // (one per pixel), the unit its technique sums are measured in.
    static IntegratorSettings withLightPaths(IntegratorSettings s, const PassPlan& plan, bool measures) {
        s.lightPaths = plan.lightPaths > 0 ? std::optional<int64_t>(static_cast<int64_t>(plan.lightPaths)) : std::nullopt;
        if (!measures) s.mis = MisHeuristic::Balance;
        return s;
    }
    PassPlan plan_;
    bool measures_;
};

}  // namespace

std::unique_ptr<PixelSampleIntegrator> makePlannedPasses(const PassPlan& plan, const IntegratorSettings& settings,
                                                         bool measures) {
    return std::make_unique<PlannedPasses>(plan, settings, measures);
}

}  // namespace tripath
