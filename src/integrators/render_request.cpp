#include "integrators/render_request.h"

#include <fmt/format.h>

#include "geometry/embree_isa.h"
#include "core/error.h"
#include "scenes/scene_source.h"
#include "paths/kernels.h"

namespace tripath {

namespace {

// The front ends' names of the heuristics; the path core knows only the enum.
MisHeuristic parseMisHeuristic(const std::string& name) {
    if (name == "balance") return MisHeuristic::Balance;
    if (name == "power") return MisHeuristic::Power;
    if (name == "none") return MisHeuristic::Uniform;
    throw InputError("unknown MIS heuristic '" + name + "' (balance, power or none)");
}

}  // namespace

std::string parameterName(const char* flag, Spelling spelling) {
    if (spelling == Spelling::CommandLine) return std::string("--") + flag;
    std::string name = flag;
    if (name.ends_with("time")) name.replace(name.size() - 4, 4, "seconds");  // Python's budgets are in seconds
    for (char& c : name)
        if (c == '-') c = '_';
    return name;
}

void validate(const RenderRequest& r, Spelling spelling) {
    auto name = [spelling](const char* flag) { return parameterName(flag, spelling); };
    auto fail = [](const std::string& m) { throw InputError(m); };
    // The film keeps 96 bytes a pixel (the block's double RGB and the exact 192-bit totals) plus the
    // output image: 8192² is ~6.7 GiB.
    if (r.width < 1 || r.height < 1 || r.width > 16384 || r.height > 16384 || double(r.width) * r.height > 8192.0 * 8192.0)
        fail(fmt::format("{}/{} must be at least 1 and at most 16384, with at most 8192x8192 pixels (got {}x{})",
                         name("width"), name("height"), r.width, r.height));
    if (r.sppGiven && (r.spp < 1 || r.spp > 1000000))
        fail(fmt::format("{} must be between 1 and 1000000 (got {})", name("spp"), r.spp));
    if (r.timeGiven && !(r.seconds > 0 && r.seconds <= 1e7))
        fail(fmt::format("{} must be a number of seconds above 0 and at most 1e7 (got {})",
                         name("time"), r.seconds));
    if (r.maxDepth < 1 || r.maxDepth > 1024)
        fail(fmt::format("{} must be between 1 and 1024 (got {})", name("max-depth"), r.maxDepth));
    if (r.rrDepth < 0)
        fail(fmt::format("{} must be at least 1, or 0 for the integrator's default (got {})", name("rr-depth"), r.rrDepth));
    if (r.threads < 0 || r.threads > 4096) fail(fmt::format("{} must be between 0 and 4096 (got {})", name("threads"), r.threads));
    if (r.radiusGiven && !(r.merge.radius > 0 && r.merge.radius < 1e30f))
        fail(fmt::format("{} must be a length in world units above 0 (got {})", name("radius"), r.merge.radius));
    if (r.radiusFactorGiven && !(r.merge.radiusFactor > 0 && r.merge.radiusFactor <= 1))
        fail(fmt::format("{} must be above 0 and at most 1 (got {})", name("radius-factor"), r.merge.radiusFactor));
    if (!(r.merge.radiusPixels > 0 && r.merge.radiusPixels <= 1000))
        fail(fmt::format("{} must be above 0 and at most 1000 (got {})", name("radius-pixels"), r.merge.radiusPixels));
    if (r.lightPathsGiven && (r.lightPaths < 1 || r.lightPaths > kMaxLightPaths))
        fail(fmt::format("{} must be between 1 and {} (got {})", name("light-paths"), kMaxLightPaths, r.lightPaths));
    if (!(r.merge.alpha > 0 && r.merge.alpha <= 1))
        fail(fmt::format("{} must be above 0 and at most 1 (got {})", name("alpha"), r.merge.alpha));
    if (r.strategyImages < 0 || r.strategyImages > 16)
        fail(fmt::format("{} must be between 0 (none) and 16 (got {})", name("strategy-images"), r.strategyImages));
    if (r.strategyImages > 0 && (r.integrator == "pt" || r.integrator == "lt"))
        fail(fmt::format("{} needs the integrator bdpt, vcm, bpm or ppm (pt and lt have no (s,t) to separate)",
                         name("strategy-images")));
    parseMisHeuristic(r.mis);
    makeIntegrator(r.integrator, {});
}

int rouletteDepth(const RenderRequest& r, const std::string& integrator) {
    return r.rrDepth > 0 ? r.rrDepth : defaultRouletteDepth(integrator);
}

IntegratorSettings integratorSettings(const RenderRequest& r) {
    IntegratorSettings s;
    s.walk.maxDepth = r.maxDepth;
    s.walk.rrDepth = rouletteDepth(r, r.integrator);
    s.mis = parseMisHeuristic(r.mis);
    s.merge = r.merge;
    s.walk.lightPaths = r.lightPathsGiven ? double(r.lightPaths) : 0.0;
    return s;
}

RenderSettings renderSettings(const RenderRequest& r) {
    RenderSettings s;
    s.seconds = r.seconds;
    s.spp = r.spp > 0 ? r.spp : (r.seconds > 0 ? 0 : 16);
    s.seed = r.seed;
    s.domain = r.domain;
    s.threads = r.threads;
    s.timing = r.stats;
    if (r.depthImages) s.layers.depthImages = r.maxDepth;
    s.layers.strategyLength = r.strategyImages;
    return s;
}

std::unique_ptr<Scene> loadScene(const RenderRequest& r, const WarningSink& warn) {
    return std::make_unique<Scene>(loadSceneDesc(r.scene, r.gltf, warn), r.width, r.height, warn);
}

const char* streamsName(StreamDomain d) { return d == StreamDomain::Reference ? "reference" : "render"; }

Metadata convergenceSettings(const RenderRequest& r, const std::string& integrator) {
    return {{"tripath:scene", r.scene},
            {"tripath:integrator", integrator},
            {"tripath:max-depth", std::to_string(r.maxDepth)},
            {"tripath:rr-depth", std::to_string(rouletteDepth(r, integrator))},
            {"tripath:mis", r.mis}};
}

Metadata renderMetadata(const RenderRequest& r, const Scene& scene, const Integrator& integrator, const RenderResult& result,
                        int ranks) {
    Metadata m{{"tripath:scene", r.scene},
               {"tripath:integrator", integrator.name()},
               {"tripath:spp", std::to_string(result.passes)},
               {"tripath:next-pass", std::to_string(result.nextPass)},
               {"tripath:seconds", fmt::format("{:.3f}", result.seconds)},
               {"tripath:seed", std::to_string(r.seed)},
               {"tripath:streams", streamsName(r.domain)},
               {"tripath:max-depth", std::to_string(r.maxDepth)},
               {"tripath:rr-depth", std::to_string(integrator.settings().walk.rrDepth)},
               {"tripath:mis", r.mis},
               {"tripath:dropped-samples", std::to_string(result.droppedSamples)},
               {"tripath:guarded-weights", std::to_string(result.guardedWeights)},
               {"tripath:version", TRIPATH_VERSION},
               {"tripath:embree", embreeDescription()},
               {"tripath:ranks", std::to_string(ranks)}};
    const Metadata light = lightPhaseMetadata(r, scene, integrator);
    m.insert(m.end(), light.begin(), light.end());
    if (result.interrupted) m.push_back({"tripath:interrupted", interruptionText(result)});
    return m;
}

Metadata lightPhaseMetadata(const RenderRequest& r, const Scene& scene, const Integrator& integrator) {
    Metadata m;
    if (integrator.hasLightPhase())
        m.push_back({"tripath:light-paths-per-pass", fmt::format("{:.0f}", integrator.lightPaths(scene))});
    if (integrator.strategies().merges()) {
        m.push_back({"tripath:radius", fmt::format("{:.9g}", integrator.firstMergeRadius(scene))});
        m.push_back({"tripath:alpha", fmt::format("{:.9g}", r.merge.alpha)});
    }
    return m;
}

}  // namespace tripath
