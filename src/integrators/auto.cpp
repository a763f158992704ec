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
// measures, under the plans chosen, the variance each candidate's estimator would have, tile by
// tile (plan_moments.h), each pixel's share weighed by 1 / (I² + 0.01) with I its mean in a
// blurred image of the passes before, as relMSE weighs its error; the other blocks render without
// the measuring's cost (and, where every tile runs the same plan or none traces light to the
// sensor, without the technique sums: the running sums' balance weights are the same). After 4,
// 8, 16, 32, … passes of the render, the team chooses from the totals of every measuring pass so
// far (those before the first weights turned relative tile by tile) the plans of least relative
// variance × cost for the passes up to the next choice (plan_choice.h).
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
// Parameters: --max-depth, --rr-depth (default 2; one vertex later in passes without light paths,
// as pt's default is one later than the light-path methods', for the reason integrator.h gives),
// --light-paths (the unit of the plans' N_L) and vcm's radius schedule (--radius, --radius-factor,
// --alpha); the weights are the balance heuristic's, the estimator whose moments the choice reads,
// whatever --mis says. The plans of each stretch of passes, the candidates' estimates at the last
// choice and each tile's classes go to the EXR's metadata and to --stats. A checkpoint keeps the
// moments, the plans and where the schedule is (AutoState), so that a resumed render chooses as
// the uninterrupted one.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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
    work.lightVertices = LightPhase::survey(scene, full, settings.firstPass, settings.streams()).vertices;
    const Camera& cam = scene.camera();
    const uint64_t pixels = uint64_t(cam.width()) * cam.height(), cameraPaths = std::min(pixels, kSurveyed);
    const double lightPaths = full.lightPaths(scene);
    std::vector<Vec3> queries;
    Subpath path;
    double vertices = 0;
    for (uint64_t i = 0; i < cameraPaths; ++i) {
        const int pixel = static_cast<int>(i * pixels / cameraPaths);
        SampleStream rng = sampleStream(settings.streams(), settings.firstPass, cam, pixel);
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
        SampleStream rng = lightPathStream(settings.streams(), settings.firstPass, static_cast<uint64_t>(lightPaths), j);
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
        const std::string name = classesName(plan.classes());
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

// What a checkpoint keeps of auto to choose as the uninterrupted render would: the render's first
// pass (a continued reference's next passes come after it), the blocks done (the passes are
// contiguous at a checkpoint, render.h), the passes that measured, the plans of each stretch so
// far, the current choice, the last choice's estimates (for the report), the moments' totals and
// the pixels' weights in them. Text lines, the doubles in hexadecimal, then the moments' bytes and
// the weights'.
struct AutoState {
    uint64_t first = 0;  // the render's first pass
    uint64_t blocks = 0, measured = 0;
    std::vector<std::pair<uint64_t, std::string>> stretches;
    std::vector<size_t> tiles;
    std::vector<PlanEstimate> estimates;
    std::string moments;
    std::vector<float> weights;

    std::string write() const {
        std::string out = fmt::format("{} {} {} {} {} {} {}\n", first, blocks, measured, stretches.size(),
                                      estimates.size(), moments.size(), weights.size());
        for (const auto& [first, name] : stretches) out += fmt::format("{} {}\n", first, name);
        out += fmt::format("{}\n", fmt::join(tiles, " "));
        for (const PlanEstimate& e : estimates)
            out += fmt::format("{:a} {:a} {:d} {}\n", e.relativeVariance, e.cost, e.uncovered, e.plan);
        out += moments;
        return out.append(reinterpret_cast<const char*>(weights.data()), weights.size() * sizeof(float));
    }
    // A checkpoint's state, from rank 0 to every rank of `team`, for a render resumed at pass
    // `nextPass`.
    static AutoState read(std::string bytes, Team& team, uint64_t nextPass) {
        team.broadcast(bytes);
        auto damaged = [] { return InputError("a checkpoint's state of auto is damaged (remove it to start afresh)"); };
        AutoState state;
        std::istringstream in(bytes);
        size_t stretches = 0, estimates = 0, moments = 0, weights = 0;
        if (!(in >> state.first >> state.blocks >> state.measured >> stretches >> estimates >> moments >> weights) ||
            state.first > nextPass || state.blocks > kMaxFirstPass / kPassesPerBlock || stretches > bytes.size() ||
            estimates > bytes.size() || moments > bytes.size() || weights > bytes.size())
            throw damaged();
        std::string line;
        std::getline(in, line);
        for (size_t i = 0; i < stretches; ++i) {
            uint64_t first = 0;
            if (!(in >> first) || !std::getline(in, line) || line.empty()) throw damaged();
            state.stretches.push_back({first, line.substr(1)});
        }
        if (!std::getline(in, line)) throw damaged();
        std::istringstream tiles(line);
        for (size_t k; tiles >> k;) state.tiles.push_back(k);
        for (size_t i = 0; i < estimates; ++i) {
            PlanEstimate e;
            if (!std::getline(in, line)) throw damaged();
            char* rest = nullptr;
            e.relativeVariance = std::strtod(line.c_str(), &rest);
            e.cost = std::strtod(rest, &rest);
            int uncovered = 0, used = 0;
            if (std::sscanf(rest, " %d %n", &uncovered, &used) != 1) throw damaged();
            e.uncovered = uncovered != 0;
            e.plan = std::string(rest + used);
            state.estimates.push_back(std::move(e));
        }
        const auto at = static_cast<size_t>(in.tellg());
        if (in.fail() || bytes.size() - at != moments + weights * sizeof(float)) throw damaged();
        state.moments = bytes.substr(at, moments);
        state.weights.resize(weights);
        if (weights > 0) std::memcpy(state.weights.data(), bytes.data() + at + moments, weights * sizeof(float));
        return state;
    }
};

class AutoPasses final : public TilePasses {
public:
    // Resumed from `state` when given, with the render it went on from (`settings.resume`);
    // `settings.firstPass` is the first pass of the render as it was started.
    AutoPasses(const Scene& scene, const PixelSampleIntegrator& full, const RenderSettings& settings,
               std::optional<AutoState> state)
        : TilePasses(scene, full, settings, settings.firstPass), scene_(scene), settings_(full.settings()),
          pixels_(double(scene.camera().width()) * scene.camera().height()),
          tiles_(size_t(((scene.camera().width() + kTileSize - 1) / kTileSize) *
                        ((scene.camera().height() + kTileSize - 1) / kTileSize))),
          candidates_(candidatePlans(full.lightPaths(scene))),
          everything_(size_t(std::find(candidates_.begin(), candidates_.end(),
                                       PassPlan{full.lightPaths(scene), true, true, true, true}) - candidates_.begin())),
          work_(surveyWork(scene, full, settings)),
          moments_(scene.camera().width(), scene.camera().height(), kTileSize, candidates_.size()),
          resumed_(settings.resume) {
        if (!state) {
            choose(std::vector<size_t>(tiles_, everything_), 0);
            return;
        }
        const bool fits = state->tiles.size() == tiles_ &&
                          std::none_of(state->tiles.begin(), state->tiles.end(), [&](size_t k) { return k >= candidates_.size(); }) &&
                          (state->estimates.empty() || state->estimates.size() == candidates_.size() + 1) &&
                          state->moments.size() == moments_.stateSize() &&
                          (state->weights.empty() || state->weights.size() == size_t(camera_.width()) * camera_.height());
        if (!fits) throw InputError("a checkpoint's state of auto is damaged (remove it to start afresh)");
        blocks_ = resumedBlocks_ = state->blocks;
        resumedMeasured_ = state->measured;
        if (!state->weights.empty()) moments_.setWeights(std::move(state->weights));
        if (team_.rank() == 0) {
            moments_.add(state->moments);
            estimates_ = std::move(state->estimates);
        }
        choose(state->tiles, 0);
        stretches_ = std::move(state->stretches);
    }

    // The stretch's blocks from the team's next, one a rank; a rank whose block would lie past the
    // stretch's end waits for the choice. Offsets count from the render's first pass.
    std::pair<uint64_t, uint64_t> round(uint64_t, uint64_t budget) const override {
        const uint64_t block = blocks_ + uint64_t(team_.rank());
        const uint64_t begin = std::min(block, stretchEnd()) * kPassesPerBlock;
        const uint64_t end = block < stretchEnd() ? begin + kPassesPerBlock : begin;
        const uint64_t last = budget == UINT64_MAX ? budget : budget + resumedBlocks_ * kPassesPerBlock;
        return {std::min(last, begin), std::min(last, end)};
    }
    bool budgetDone(uint64_t, uint64_t budget) const override {
        return (blocks_ - resumedBlocks_) * kPassesPerBlock >= budget;
    }
    // The first block of each stretch (blocks 0, 1, 2, 4, 8, …) measures; the others render alone.
    void run(uint64_t offset, RenderResult& result) override {
        const uint64_t block = offset / kPassesPerBlock;
        const bool measures = (block & (block - 1)) == 0;
        measured_ += measures;
        ++rendered_;
        const PixelSampleIntegrator& passes = measures || !unmeasured_ ? *chosen_ : *unmeasured_;
        renderer_.run(passes, firstPass_ + offset, result, measures ? &moments_ : nullptr, tilePlans_);
    }
    // A stretch's first round chooses its plans from every pass before it.
    void beginRound(Film& film) override {
        if (blocks_ > 0 && blocks_ == stretchStart(stretchOf(blocks_)) && stretches_.back().first < blocks_ * kPassesPerBlock)
            decide(film, blocks_ * kPassesPerBlock);
    }
    void endRound(Film& film) override {
        renderer_.endBlock(film);
        moments_.endBlock();
        blocks_ = std::min(blocks_ + ranks(), stretchEnd());
    }
    void gather(RenderResult& into, Film& mine, uint64_t local, uint64_t localNext, const RenderResult& counts) override {
        const std::vector<std::string> all = team_.gather(moments_.state());
        const uint64_t measured = teamPasses()[1];
        TilePasses::gather(into, mine, local, localNext, counts);
        if (team_.rank() != 0) return;
        PlanMoments team = moments_;
        for (size_t r = 1; r < all.size(); ++r) team.add(all[r]);
        into.methodState =
            AutoState{firstPass_, blocks_, measured, stretches_, choice_, estimates_, team.state(), moments_.weights()}.write();
        into.plans.stretches.clear();
        for (const auto& [first, name] : stretches_)
            if (first < uint64_t(into.passes) + (resumed_ ? uint64_t(resumed_->passes) : 0))
                into.plans.stretches.push_back({first, name});
        into.plans.candidates = estimates_;
        into.plans.tiles.clear();
        for (const PassPlan& plan : tilePlans_) into.plans.tiles.push_back(plan.classes());
        into.plans.tilesAcross = (camera_.width() + kTileSize - 1) / kTileSize;
        into.plans.tileSize = kTileSize;
    }

private:
    // The stretch block `block` is in, and one past the last block of the team's next block's.
    static int stretchOf(uint64_t block) {
        int e = 0;
        while (stretchStart(e + 1) <= block) ++e;
        return e;
    }
    uint64_t stretchEnd() const { return stretchStart(stretchOf(blocks_) + 1); }
    // The passes rendered and those that measured, over the team and the render it resumed
    // (collective).
    std::array<uint64_t, 2> teamPasses() {
        std::array<uint64_t, 2> passes{rendered_, measured_};
        team_.sum(passes);
        return {passes[0] + (resumed_ ? uint64_t(resumed_->passes) : 0), passes[1] + resumedMeasured_};
    }

    // The team's choice for the stretch from pass `next` on: rank 0 gathers the moments and the
    // film (with the render it resumed), chooses, and tells the others; it keeps the team's
    // moments from then on, and the others start theirs afresh.
    void decide(Film& film, uint64_t next) {
        const std::vector<std::string> all = team_.gather(moments_.state());
        const auto [passes, measured] = teamPasses();
        std::optional<Film> copy;
        if ((team_.size() > 1 || resumed_) && team_.rank() == 0) copy.emplace(film);
        team_.reduce(copy ? *copy : film);
        std::string choice, weights;
        std::vector<double> scales;
        if (team_.rank() == 0) {
            if (resumed_) copy->add(resumed_->film);
            PlanMoments team = moments_;
            for (size_t r = 1; r < all.size(); ++r) team.add(all[r]);
            const Image mean = (copy ? *copy : film).image(static_cast<int>(passes));
            const PlanEvidence evidence = team.evidence(mean, static_cast<int>(measured));
            const std::vector<std::vector<double>> variances = relativeVariances(evidence);
            const PlanChoice chosen = choosePlans(variances, evidence, candidates_, work_, everything_);
            for (size_t tile : chosen.tiles) choice += std::to_string(tile) + " ";
            report(variances, evidence, chosen);
            const std::vector<float> w = PlanMoments::relativeWeights(mean);
            weights.assign(reinterpret_cast<const char*>(w.data()), w.size() * sizeof(float));
            scales = team.tileScales(mean);
            moments_ = std::move(team);
        } else {
            moments_.clearTotals();
        }
        team_.broadcast(choice);
        team_.broadcast(weights);
        std::vector<float> w(weights.size() / sizeof(float));
        std::memcpy(w.data(), weights.data(), weights.size());
        moments_.setWeights(std::move(w), scales);
        std::vector<size_t> tiles;
        std::istringstream in(choice);
        for (size_t k; in >> k;) tiles.push_back(k);
        choose(tiles, next);
    }
    // What --stats and the EXR show of a choice: each candidate as if every tile ran it, then the
    // choice itself.
    void report(const std::vector<std::vector<double>>& variances, const PlanEvidence& evidence, const PlanChoice& chosen) {
        estimates_.clear();
        for (size_t k = 0; k < candidates_.size(); ++k) {
            double variance = 0;
            for (double v : variances[k]) variance += v;
            const bool uncovered = std::find(evidence.uncovered[k].begin(), evidence.uncovered[k].end(), true) !=
                                   evidence.uncovered[k].end();
            estimates_.push_back({planName(candidates_[k], pixels_), variance, passCost(candidates_[k], work_, pixels_), uncovered});
        }
        std::vector<PassPlan> plans;
        for (size_t k : chosen.tiles) plans.push_back(candidates_[k]);
        estimates_.push_back({"chosen: " + choiceName(plans, pixels_), chosen.relativeVariance, chosen.cost, false});
    }
    void choose(const std::vector<size_t>& tiles, uint64_t firstPass) {
        // Each stretch draws its own scramble of Sobol points: its passes are then independent of
        // the passes its plans were chosen from, as independent numbers are. Points of one scramble
        // are stratified together, so a pass's numbers would depend on those before it, and a
        // plan chosen from them would weigh the rest of their strata.
        renderer_.setScramble(uint64_t(stretchOf(blocks_)) + 1);
        choice_ = tiles;
        tilePlans_.clear();
        for (size_t k : tiles) tilePlans_.push_back(candidates_[k]);
        const PassPlan all = unionOf(tilePlans_);
        IntegratorSettings s = settings_;
        if (all.lightPaths == 0) ++s.walk.rrDepth;  // as pt's roulette starts one vertex after the others'
        chosen_ = makePlannedPasses(all, s);
        const bool alike = std::all_of(tilePlans_.begin(), tilePlans_.end(), [&](const PassPlan& p) { return p == all; });
        unmeasured_ = all.lightTraces && !alike ? nullptr : makePlannedPasses(all, s, false);
        std::vector<TechniqueSums> factors;
        for (const PassPlan& c : candidates_) factors.push_back(c.factors(chosen_->lightPaths(scene_)));
        moments_.setFactors(std::move(factors));
        moments_.setRunning(choice_);
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
    const RenderResult* resumed_;                    // the render this one goes on from, if any
    std::vector<size_t> choice_;                     // the candidate of each tile
    std::vector<PassPlan> tilePlans_;                // the choice, per tile
    std::unique_ptr<PixelSampleIntegrator> chosen_;  // the passes of its union
    // The same passes where they do not measure, when a splat is weighed alike in every tile (every
    // tile runs the same plan, or none traces light to the sensor): each contribution weighed as it
    // comes, without technique sums.
    std::unique_ptr<PixelSampleIntegrator> unmeasured_;
    uint64_t blocks_ = 0;                            // the team's next block: the blocks done before it
    uint64_t resumedBlocks_ = 0, resumedMeasured_ = 0;
    uint64_t rendered_ = 0, measured_ = 0;           // the passes this rank rendered, and measured in
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
        RenderResult result = startRender(scene, *this, settings);
        const auto full = makePlannedPasses({unit(scene), true, true, true, true}, this->settings());
        std::optional<AutoState> state;
        RenderSettings render = settings;
        if (settings.resume) {
            state = AutoState::read(settings.resume->methodState, settings.team ? *settings.team : solo(),
                                    settings.resume->nextPass);
            render.firstPass = state->first;
        }
        AutoPasses passes(scene, *full, render, std::move(state));
        return runPasses(render, passes, std::move(result));
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
