// auto — efficiency-aware MIS over vcm's strategies (Grittmann, Yazici, Georgiev and Slusallek
// 2022): the method that chooses, while it renders, which of its strategies pay on the scene.
//
// Every pass renders camera samples as vcm's do, with a plan per 16×16 tile of the image
// (pass_plan.h): N_L light paths for the whole pass (none, or a quarter, one or four times
// --light-paths, one per pixel by default), and which classes of strategies each tile runs: the
// camera walk's hits on emitters and next-event estimates, the connections, light tracing's joins
// to the sensor, the merges. Every contribution is weighed by the balance heuristic over the
// classes the tile it lands in runs (classWeight, mis.h): a splat by those of the tile it falls
// in, whichever sample traced it. The first passes run every class with one light path per pixel
// in every tile. The first block of passes after each choice (passes 0-3, 4-7, 8-11, 16-19, …)
// measures, under the plans chosen, the second moment each candidate's estimator would have,
// tile by tile (plan_moments.h); the other blocks render without the measuring's cost. After 4, 8,
// 16, 32, … passes of the render, the team chooses from the totals of every measuring pass so far
// the plans of least relative second moment × cost for the passes up to the next choice
// (plan_choice.h).
//
// Unbiased: a pass's plans depend on the passes before it alone, and every pass weighs the same
// in the image (the film's average), a weight fixed before the pass; within a pass the weights of
// every pixel's strategies sum to one, and each tile's plan samples every path some pass found
// light on there (a plan that cannot is never chosen); the merges keep vcm's radius schedule.
// Deterministic: the moments are exact sums like the film's, the costs come from a survey traced
// from fixed streams, and the choices fall at pass counts, so the plans and the image are the same
// for any thread count and any team of ranks. mlt is not among the plans: its chains are no MIS
// technique.
//
// Parameters: --max-depth, --rr-depth (default 2), --light-paths (the unit of the plans' N_L) and
// vcm's radius schedule (--radius, --radius-factor, --alpha); the weights are the balance
// heuristic's, the estimator whose moments the choice reads, whatever --mis says. The plans of each
// stretch of passes, the candidates' estimates at the last choice and each tile's classes go to the
// EXR's metadata and to --stats. Not yet: checkpoints.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "core/error.h"
#include "integrators/pass_plan.h"
#include "integrators/plan_choice.h"
#include "integrators/plan_moments.h"
#include "integrators/tile_passes.h"

namespace tripath {

namespace {

// The first block of stretch e, the passes between choice e − 1 and choice e: 0, 1, 2, 4, 8, …
uint64_t stretchStart(int e) { return e == 0 ? 0 : uint64_t(1) << (e - 1); }

// What a pass does on this scene (plan_choice.h's PassWork), from the streams of the render's
// first pass: up to 1024 of its camera samples, its light paths' survey, and the merges the
// surveyed camera vertices would make among up to 1024 of its light paths.
PassWork surveyWork(const Scene& scene, const PixelSampleIntegrator& full, const RenderSettings& settings) {
    constexpr uint64_t kSurveyed = 1024;
    PassWork work;
    work.lightVertices = LightPhase::survey(scene, full, settings.firstPass, settings.seed, settings.domain).vertices;
    const Camera& cam = scene.camera();
    const uint64_t pixels = uint64_t(cam.width()) * cam.height(), cameraPaths = std::min(pixels, kSurveyed);
    const double lightPaths = full.lightPaths(scene);
    std::vector<Vec3> queries;
    Subpath path;
    double vertices = 0;
    for (uint64_t i = 0; i < cameraPaths; ++i) {
        const int pixel = static_cast<int>(i * pixels / cameraPaths);
        Rng rng = sampleStream(settings.seed, settings.domain, settings.firstPass, cam, pixel);
        const Vec2 raster = jitteredRaster(rng, pixel, cam.width());
        cameraSubpath(scene, CameraRay(raster), rng, full.settings().walk, WalkPdfs::None, lightPaths, path);
        vertices += double(path.size()) - 1;
        for (size_t v = 1; v < path.size(); ++v)
            if (!path[v].delta && !path[v].atInfinity) queries.push_back(path[v].p);
    }
    work.cameraVertices = vertices / double(cameraPaths);

    const uint64_t traced = std::min<uint64_t>(static_cast<uint64_t>(lightPaths), kSurveyed);
    const float radius = full.mergeRadius(full.firstMergeRadius(scene), settings.firstPass);
    if (traced == 0 || queries.empty() || !(radius > 0)) return work;
    LightStore store;
    store.reset(traced);
    for (uint64_t j = 0; j < traced; ++j) {
        Rng rng = lightPathStream(settings.seed, settings.domain, settings.firstPass, static_cast<uint64_t>(lightPaths), j);
        lightSubpath(scene, rng, full.settings().walk, WalkPdfs::None, path);
        store.chunk(j / LightStore::kPathsPerChunk).append(path);
    }
    std::vector<std::vector<LightVertexSearch::Entry>> mergeable(store.chunks());
    for (size_t c = 0; c < store.chunks(); ++c) LightVertexSearch::mergeable(store.chunk(c), mergeable[c]);
    const LightVertexSearch search(mergeable, radius);
    double found = 0;
    for (size_t q = 0; q < queries.size(); q += LightVertexSearch::kQueriesAtOnce) {
        const size_t n = std::min<size_t>(LightVertexSearch::kQueriesAtOnce, queries.size() - q);
        search.forEachWithin(std::span<const Vec3>(queries.data() + q, n),
                             [&](int, std::span<const Vertex>, int) { ++found; });
    }
    // Per camera vertex that searches (its share of all of them) and per light path of the pass.
    work.mergesPerQuery = found / double(queries.size()) / double(traced);
    return work;
}

// The name of a choice of plans per tile: "N_L=1/px trace+merge" when every tile runs the same
// classes, else the number of tiles that run each set of classes, most first.
std::string choiceName(const std::vector<PassPlan>& tiles, double pixels) {
    std::vector<std::pair<std::string, int>> counts;
    for (const PassPlan& plan : tiles) {
        const std::string name = className(plan);
        auto it = std::find_if(counts.begin(), counts.end(), [&](const auto& c) { return c.first == name; });
        if (it == counts.end())
            counts.push_back({name, 1});
        else
            ++it->second;
    }
    if (counts.size() == 1) return planName(tiles.front(), pixels);
    std::stable_sort(counts.begin(), counts.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
    std::vector<std::string> parts;
    for (const auto& [name, n] : counts) parts.push_back(fmt::format("{} {} tiles", name, n));
    return fmt::format("N_L={:g}/px {}", tiles.front().lightPaths / pixels, fmt::join(parts, ", "));
}

class AutoPasses final : public TilePasses {
public:
    AutoPasses(const Scene& scene, const PixelSampleIntegrator& full, const RenderSettings& settings, uint64_t firstPass)
        : TilePasses(scene, full, settings, firstPass), scene_(scene), settings_(full.settings()),
          pixels_(double(scene.camera().width()) * scene.camera().height()),
          tiles_(size_t(((scene.camera().width() + kTileSize - 1) / kTileSize) *
                        ((scene.camera().height() + kTileSize - 1) / kTileSize))),
          candidates_(candidatePlans(full.lightPaths(scene))),
          everything_(size_t(std::find(candidates_.begin(), candidates_.end(),
                                       PassPlan{full.lightPaths(scene), true, true, true, true}) - candidates_.begin())),
          work_(surveyWork(scene, full, settings)),
          moments_(scene.camera().width(), scene.camera().height(), kTileSize, candidates_.size()) {
        choose(std::vector<size_t>(tiles_, everything_), 0);
    }

    // The stretch's blocks dealt to the ranks in rounds, as TilePasses deals all of them; a rank
    // whose block would lie past the stretch's end waits for the choice.
    std::pair<uint64_t, uint64_t> round(uint64_t round, uint64_t budget) const override {
        const Place p = place(round);
        const uint64_t block = stretchStart(p.stretch) + p.round * ranks() + uint64_t(team_.rank());
        const uint64_t begin = std::min(block, stretchStart(p.stretch + 1)) * kPassesPerBlock;
        const uint64_t end = block < stretchStart(p.stretch + 1) ? begin + kPassesPerBlock : begin;
        return {std::min(budget, begin), std::min(budget, end)};
    }
    bool budgetDone(uint64_t round, uint64_t budget) const override {
        const Place p = place(round);
        const uint64_t blocks = std::min(stretchStart(p.stretch) + (p.round + 1) * ranks(), stretchStart(p.stretch + 1));
        return blocks * kPassesPerBlock >= budget;
    }
    // The first block of each stretch (blocks 0, 1, 2, 4, 8, …) measures; the others render alone.
    void run(uint64_t offset, RenderResult& result) override {
        const uint64_t block = offset / kPassesPerBlock;
        renderer_.run(*chosen_, firstPass_ + offset, result, (block & (block - 1)) == 0 ? &moments_ : nullptr, tilePlans_);
    }
    void endRound(Film& film) override {
        renderer_.endBlock(film);
        moments_.endBlock();
        const Place p = place(roundsDone_++);
        if (p.round + 1 == p.rounds)
            decide(film, stretchStart(p.stretch + 1) * kPassesPerBlock, uint64_t(p.stretch + 1) * kPassesPerBlock);
    }
    void gather(RenderResult& into, Film& mine, uint64_t local, uint64_t localNext, const RenderResult& counts) override {
        TilePasses::gather(into, mine, local, localNext, counts);
        into.plans.stretches.clear();
        for (const auto& [first, name] : stretches_)
            if (first < uint64_t(into.passes)) into.plans.stretches.push_back({first, name});
        into.plans.candidates = estimates_;
        into.plans.tiles.clear();
        for (const PassPlan& plan : tilePlans_) into.plans.tiles.push_back(className(plan));
        into.plans.tilesAcross = (camera_.width() + kTileSize - 1) / kTileSize;
    }

private:
    // Where round `round` falls: its stretch, its index there, and the stretch's rounds.
    struct Place {
        int stretch;
        uint64_t round, rounds;
    };
    Place place(uint64_t round) const {
        for (int e = 0;; ++e) {
            const uint64_t rounds = (stretchStart(e + 1) - stretchStart(e) + ranks() - 1) / ranks();
            if (round < rounds) return {e, round, rounds};
            round -= rounds;
        }
    }

    // The team's choice after `passes` passes, `measured` of them measuring: rank 0 gathers the
    // moments and the film, chooses, and tells the others.
    void decide(Film& film, uint64_t passes, uint64_t measured) {
        const std::span<const uint64_t> words = moments_.totals().words();
        const std::string mine(reinterpret_cast<const char*>(words.data()), words.size_bytes());
        const std::vector<std::string> all = team_.gather(mine);
        std::optional<Film> copy;
        if (team_.size() > 1 && team_.rank() == 0) copy.emplace(film);
        team_.reduce(copy ? *copy : film);
        std::string choice;
        if (team_.rank() == 0) {
            PlanMoments team = moments_;
            for (size_t r = 1; r < all.size(); ++r) {
                ExactSums other(team.totals().size());
                std::memcpy(other.words().data(), all[r].data(), std::min(all[r].size(), other.words().size_bytes()));
                team.totals().add(other);
            }
            const PlanEvidence evidence =
                team.evidence(copy ? *copy : film, static_cast<int>(passes), static_cast<int>(measured));
            const std::vector<std::vector<double>> moments = relativeMoments(evidence);
            const PlanChoice chosen = choosePlans(moments, evidence, candidates_, work_, everything_);
            for (size_t tile : chosen.tiles) choice += std::to_string(tile) + " ";
            report(moments, evidence, chosen);
        }
        team_.broadcast(choice);
        std::vector<size_t> tiles;
        std::istringstream in(choice);
        for (size_t k; in >> k;) tiles.push_back(k);
        choose(tiles, passes);
    }
    // What --stats and the EXR show of a choice: each candidate as if every tile ran it, then the
    // choice itself.
    void report(const std::vector<std::vector<double>>& moments, const PlanEvidence& evidence, const PlanChoice& chosen) {
        estimates_.clear();
        for (size_t k = 0; k < candidates_.size(); ++k) {
            double moment = 0;
            for (double m : moments[k]) moment += m;
            const bool uncovered = std::find(evidence.uncovered[k].begin(), evidence.uncovered[k].end(), true) !=
                                   evidence.uncovered[k].end();
            estimates_.push_back({planName(candidates_[k], pixels_), moment, passCost(candidates_[k], work_, pixels_), uncovered});
        }
        std::vector<PassPlan> plans;
        for (size_t k : chosen.tiles) plans.push_back(candidates_[k]);
        estimates_.push_back({"chosen: " + choiceName(plans, pixels_), chosen.relativeMoment, chosen.cost, false});
    }
    void choose(const std::vector<size_t>& tiles, uint64_t firstPass) {
        tilePlans_.clear();
        for (size_t k : tiles) tilePlans_.push_back(candidates_[k]);
        chosen_ = makePlannedPasses(unionOf(tilePlans_), settings_);
        std::vector<TechniqueSums> factors;
        for (const PassPlan& c : candidates_) factors.push_back(c.factors(chosen_->lightPaths(scene_)));
        moments_.setFactors(std::move(factors));
        stretches_.push_back({firstPass, choiceName(tilePlans_, pixels_)});
    }

    const Scene& scene_;
    const IntegratorSettings settings_;
    const double pixels_;
    const size_t tiles_;
    const std::vector<PassPlan> candidates_;
    const size_t everything_;  // the candidate of every class at one light path per pixel: the first plan
    const PassWork work_;
    PlanMoments moments_;
    std::vector<PassPlan> tilePlans_;                // the choice, per tile
    std::unique_ptr<PixelSampleIntegrator> chosen_;  // the passes of its union
    uint64_t roundsDone_ = 0;
    std::vector<std::pair<uint64_t, std::string>> stretches_;  // (first pass, choice)
    std::vector<PlanEstimate> estimates_;                      // at the last choice, on rank 0
};

class AutoMis final : public Integrator {
public:
    using Integrator::Integrator;
    std::string name() const override { return "auto"; }
    StrategySet strategies() const override { return measuredStrategies(); }
    bool playsRoulette() const override { return true; }
    bool hasLightPhase() const override { return true; }
    // The plan of the most light paths, which runs every class.
    std::unique_ptr<PixelSampleIntegrator> largestPasses(const Scene& scene) const override {
        return makePlannedPasses({4 * unit(scene), true, true, true, true}, settings());
    }
    RenderResult render(const Scene& scene, const RenderSettings& settings) const override {
        if (settings.resume || settings.checkpointSeconds > 0)
            throw InputError("auto does not write or resume checkpoints yet: leave out --checkpoint");
        RenderResult result = startRender(scene, *this, settings);
        const auto full = makePlannedPasses({unit(scene), true, true, true, true}, this->settings());
        AutoPasses passes(scene, *full, settings, settings.firstPass);
        return runPasses(settings, passes, std::move(result));
    }

private:
    // The unit of the plans' N_L: --light-paths, or one per pixel.
    double unit(const Scene& scene) const {
        const Camera& cam = scene.camera();
        return settings().lightPaths ? double(*settings().lightPaths) : double(cam.width()) * cam.height();
    }
};

}  // namespace

std::unique_ptr<Integrator> makeAuto(const IntegratorSettings& s) { return std::make_unique<AutoMis>(s); }

}  // namespace tripath
