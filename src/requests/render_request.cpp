#include "requests/render_request.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "geometry/embree_isa.h"
#include "core/error.h"
#include "requests/environment_spec.h"
#include "requests/integrator_parameters.h"
#include "requests/memory_check.h"
#include "requests/scene_identity.h"
#include "scenes/scene_source.h"
#include "paths/kernels.h"

namespace tripath {

namespace {

// tripath:environment-scale, when the request has an environment.
Metadata environmentScale(const RenderRequest& r) {
    if (r.environment.empty()) return {};
    return {{"tripath:environment-scale", fmt::format("{:.9g}", r.environmentScale)}};
}

// tripath:rr-depth: the roulette start depth an integrator renders with, or "none" for one whose
// walks play no roulette (mlt's chains).
std::string rouletteText(const Integrator& integrator, int depth) {
    return integrator.playsRoulette() ? std::to_string(depth) : "none";
}

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

std::string outOfRange(const std::string& name, const IntRange& range, const std::string& got) {
    return fmt::format("{} must be between {} and {}{} (got {})", name, range.min, range.max, range.note, got);
}

void validateValues(const RenderRequest& r, Spelling spelling) {
    auto name = [spelling](const char* flag) { return parameterName(flag, spelling); };
    auto fail = [](const std::string& m) { throw InputError(m); };
    auto check = [&](bool given, const char* flag, int64_t value, const IntRange& range) {
        if (given && (value < range.min || uint64_t(value) > range.max)) fail(outOfRange(name(flag), range, std::to_string(value)));
    };
    check(true, "width", r.width, kSizeRange);
    check(true, "height", r.height, kSizeRange);
    check(r.sppGiven, "spp", r.spp, kSppRange);
    if (r.timeGiven && !(r.seconds > 0 && r.seconds <= 1e7))
        fail(fmt::format("{} must be a number of seconds above 0 and at most 1e7 (got {})",
                         name("time"), r.seconds));
    check(true, "max-depth", r.maxDepth, kMaxDepthRange);
    if (r.environmentScaleGiven && !(std::isfinite(r.environmentScale) && r.environmentScale >= 0))
        fail(fmt::format("{} must be a finite number of at least 0 (got {})", name("environment-scale"), r.environmentScale));
    // Leaving the environment out means none; an empty one is a mistake (an unset shell variable),
    // not a way to say none.
    if (r.environmentGiven && r.environment.empty())
        fail(fmt::format("{} is empty: give a map's path or a radiance R,G,B", name("environment")));
    if (r.environmentScaleGiven && r.environment.empty())
        fail(fmt::format("{} scales an environment: give one with {}", name("environment-scale"), name("environment")));
    check(true, "rr-depth", r.rrDepth, kRrDepthRange);
    check(true, "threads", r.threads, kThreadsRange);
    if (r.radiusGiven && !(r.merge.radius > 0 && r.merge.radius < 1e30f))
        fail(fmt::format("{} must be a length in world units above 0 (got {})", name("radius"), r.merge.radius));
    if (r.radiusFactorGiven && !(r.merge.radiusFactor > 0 && r.merge.radiusFactor <= 1))
        fail(fmt::format("{} must be above 0 and at most 1 (got {})", name("radius-factor"), r.merge.radiusFactor));
    if (!(r.merge.radiusPixels > 0 && r.merge.radiusPixels <= 1000))
        fail(fmt::format("{} must be above 0 and at most 1000 (got {})", name("radius-pixels"), r.merge.radiusPixels));
    check(r.lightPathsGiven, "light-paths", r.lightPaths, kLightPathsRange);
    if (!(r.merge.alpha > 0 && r.merge.alpha <= 1))
        fail(fmt::format("{} must be above 0 and at most 1 (got {})", name("alpha"), r.merge.alpha));
    check(true, "strategy-images", r.strategyImages, kStrategyImagesRange);
    check(r.bootstrapGiven, "bootstrap", r.metropolis.bootstrap, kBootstrapRange);
    check(r.chainsGiven, "chains", r.metropolis.chains, kChainsRange);
    if (!(r.metropolis.largeStep >= 0 && r.metropolis.largeStep <= 1))
        fail(fmt::format("{} must be a probability, from 0 to 1 (got {})", name("large-step"), r.metropolis.largeStep));
    parseMisHeuristic(r.mis);
    if (!samplerNamed(r.sampler))
        fail(fmt::format("{} takes sobol or independent (got '{}')", name("sampler"), r.sampler.substr(0, 20)));
}

void requireUsed(const RenderRequest& r, const std::vector<std::string>& integrators, Spelling spelling) {
    for (const IntegratorParameter& p : integratorParameters()) {
        if (!p.given(r)) continue;
        std::vector<std::string> without;
        for (const std::string& name : integrators)
            if (!p.uses(*makeIntegrator(name, {}))) without.push_back(name);
        if (without.size() == integrators.size())
            throw InputError(fmt::format("{} needs {}: {} {}", parameterName(p.flag, spelling), neededBy(p),
                                         fmt::join(without, ", "), without.size() == 1 ? "does not" : "do not"));
    }
}

void validate(const RenderRequest& r, Spelling spelling) {
    validateValues(r, spelling);
    makeIntegrator(r.integrator, {});
    requireUsed(r, {r.integrator}, spelling);
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
    if (r.lightPathsGiven) s.lightPaths = r.lightPaths;
    s.metropolis = r.metropolis;
    return s;
}

RenderSettings renderSettings(const RenderRequest& r, Spelling spelling) {
    RenderSettings s;
    s.seconds = r.seconds;
    s.spp = r.spp > 0 ? r.spp : (r.seconds > 0 ? 0 : 16);
    s.seed = r.seed;
    s.domain = r.domain;
    s.sampler = samplerNamed(r.sampler).value_or(SamplerKind::Sobol);
    s.threads = r.threads;
    s.timing = r.stats;
    if (r.depthImages) s.layers.depthImages = r.maxDepth;
    s.layers.strategyLength = r.strategyImages;
    s.checkMemory = [limit = memoryLimit(r), spelling](const MemoryEstimate& e) { requireMemory(e, limit, spelling); };
    return s;
}

std::unique_ptr<Scene> loadScene(const RenderRequest& r, const WarningSink& warn) {
    SceneDesc desc = loadSceneDesc(r.scene, r.gltf, warn);
    if (!r.environment.empty()) {
        desc.environment = loadEnvironment(r.environment, r.environmentScale, warn);
        desc.sources.push_back({std::filesystem::path(r.environment).filename().string(), desc.environment.hash});
    }
    return std::make_unique<Scene>(std::move(desc), r.width, r.height, warn);
}

const char* streamsName(StreamDomain d) { return d == StreamDomain::Reference ? "reference" : "render"; }

Metadata convergenceSettings(const RenderRequest& r, const Scene& scene, const std::string& integrator) {
    Metadata m{{kSceneFilesKey, sceneFilesText(scene.sources())},
               {"tripath:integrator", integrator},
               {"tripath:max-depth", std::to_string(r.maxDepth)},
               {"tripath:rr-depth", rouletteText(*makeIntegrator(integrator, {}), rouletteDepth(r, integrator))},
               {"tripath:mis", r.mis}};
    const Metadata scale = environmentScale(r);
    m.insert(m.end(), scale.begin(), scale.end());
    return m;
}

Metadata renderMetadata(const RenderRequest& r, const Scene& scene, const Integrator& integrator, const RenderResult& result,
                        int ranks) {
    Metadata m{{"tripath:scene", r.scene},
               {kSceneFilesKey, sceneFilesText(scene.sources())},
               {"tripath:integrator", integrator.name()},
               {"tripath:spp", std::to_string(result.passes)},
               {"tripath:next-pass", std::to_string(result.nextPass)},
               {"tripath:seconds", fmt::format("{:.3f}", result.seconds)},
               {"tripath:seed", std::to_string(r.seed)},
               {"tripath:streams", streamsName(r.domain)},
               {"tripath:max-depth", std::to_string(r.maxDepth)},
               {"tripath:rr-depth", rouletteText(integrator, integrator.settings().walk.rrDepth)},
               {"tripath:mis", r.mis},
               {"tripath:sampler", r.sampler},
               {"tripath:dropped-samples", std::to_string(result.droppedSamples)},
               {"tripath:guarded-weights", std::to_string(result.guardedWeights)},
               {"tripath:version", TRIPATH_VERSION},
               {"tripath:embree", embreeDescription()},
               {"tripath:ranks", std::to_string(ranks)}};
    if (!r.environment.empty()) m.push_back({"tripath:environment", r.environment});
    for (const Metadata& more : {environmentScale(r), lightPhaseMetadata(r, scene, integrator)}) m.insert(m.end(), more.begin(), more.end());
    if (integrator.markovChains()) {
        // Per path length k = 1, 2, …: b_k, the length's chains and their acceptance rate.
        std::vector<std::string> b, chains, acceptance;
        for (const MetropolisLength& l : result.metropolis.lengths) {
            b.push_back(fmt::format("{:.6g}", l.normalisation));
            chains.push_back(std::to_string(l.chains));
            acceptance.push_back(l.steps ? fmt::format("{:.4f}", double(l.accepted) / double(l.steps)) : "-");
        }
        m.push_back({"tripath:mlt-normalisation", fmt::format("{}", fmt::join(b, " "))});
        m.push_back({"tripath:mlt-chains-per-length", fmt::format("{}", fmt::join(chains, " "))});
        m.push_back({"tripath:mlt-acceptance", fmt::format("{}", fmt::join(acceptance, " "))});
    }
    if (!result.plans.stretches.empty()) {
        // auto's plan of each stretch of passes, from its first pass: "0 N_L=1/px connect+trace+merge; 4 pt; …".
        std::vector<std::string> stretches;
        for (const auto& [first, plan] : result.plans.stretches) stretches.push_back(fmt::format("{} {}", first, plan));
        m.push_back({"tripath:auto-plans", fmt::format("{}", fmt::join(stretches, "; "))});
        // The classes each tile ran in the last stretch, a row of tiles per "; ".
        const size_t tilesX = std::max<size_t>(1, result.plans.tilesAcross);
        std::vector<std::string> rows;
        for (size_t t = 0; t < result.plans.tiles.size(); ++t) {
            if (t % tilesX == 0) rows.emplace_back();
            rows.back() += (t % tilesX == 0 ? "" : " ") + classesName(result.plans.tiles[t]);
        }
        m.push_back({"tripath:auto-tiles", fmt::format("{}", fmt::join(rows, "; "))});
    }
    if (result.memory.total() > 0) m.push_back({"tripath:memory-estimate", std::to_string(result.memory.total())});
    if (result.interrupted) m.push_back({"tripath:interrupted", interruptionText(result)});
    return m;
}

Metadata lightPhaseMetadata(const RenderRequest& r, const Scene& scene, const Integrator& integrator) {
    Metadata m;
    if (const PixelSampleIntegrator* samples = integrator.pixelSamples()) {
        if (samples->hasLightPhase())
            m.push_back({"tripath:light-paths-per-pass", fmt::format("{:.0f}", samples->lightPaths(scene))});
        if (samples->strategies().merges()) {
            m.push_back({"tripath:radius", fmt::format("{:.9g}", samples->firstMergeRadius(scene))});
            m.push_back({"tripath:alpha", fmt::format("{:.9g}", r.merge.alpha)});
        }
    }
    if (const MetropolisSettings* ms = integrator.markovChains()) {
        m.push_back({"tripath:bootstrap", std::to_string(ms->bootstrap)});
        m.push_back({"tripath:chains", std::to_string(ms->chains)});
        m.push_back({"tripath:large-step", fmt::format("{:.9g}", ms->largeStep)});
    }
    return m;
}

}  // namespace tripath
