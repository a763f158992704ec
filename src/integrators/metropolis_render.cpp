#include "integrators/metropolis_render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <optional>

#include "core/stats.h"
#include "integrators/render_loop.h"
#include "paths/markov_chain.h"

namespace tripath {

namespace {

constexpr Counter kMutations{Event::Mutations};
constexpr Counter kAcceptedMutations{Event::AcceptedMutations};

// The stream index of bootstrap sample or chain `id` of run `run`, at its step `step`.
uint64_t streamIndex(uint64_t run, uint64_t id, uint64_t step) { return mix64(mix64(run) + id) + step; }

// What every rank derives alike from the bootstrap: b_k and the chains of each length.
struct ChainLayout {
    uint64_t samplesPerLength = 0;                // N_k
    std::vector<std::vector<double>> cumulative;  // per length: the bootstrap luminances' running sums
    std::vector<double> normalisation;            // b_k
    std::vector<int> firstChain{0};               // chains of length k: [firstChain[k − 1], firstChain[k])
    int stepsPerPass = 0;                         // m
    uint64_t notFinite = 0;                       // bootstrap samples whose value was not finite (counted as 0)
    int chains() const { return firstChain.back(); }
    int lengthOf(int chain) const {
        return static_cast<int>(std::upper_bound(firstChain.begin(), firstChain.end(), chain) - firstChain.begin());
    }
    // The scale of a contribution of length k per pass: b_k / (n_k m).
    double scale(int k) const { return normalisation[k - 1] / (double(firstChain[k] - firstChain[k - 1]) * stepsPerPass); }
};

// Everything one render's chains share.
struct ChainRun {
    const Scene& scene;
    MultiplexedTarget target;
    uint64_t seed, run;
    StreamDomain bootstrapDomain, chainDomain;
    float largeStep;
    int maxDepth;
    // Bootstrap sample j of length k: its stream, and so its point.
    Rng bootstrapStream(int k, uint64_t j, uint64_t perLength) const {
        return Rng(seed, uint64_t(bootstrapDomain), streamIndex(run, uint64_t(k - 1) * perLength + j, 0));
    }
    Rng chainStream(int chain, uint64_t step) const { return Rng(seed, uint64_t(chainDomain), streamIndex(run, uint64_t(chain), step)); }
};

// How many bootstrap samples a task takes between two looks at the stop request: a large
// --bootstrap takes seconds, and a look costs nothing beside 64 samples' paths.
constexpr uint64_t kSamplesPerStopCheck = 64;

// The bootstrap: each rank evaluates its share of the N samples, in parallel, the team gathers
// the luminances in sample order, and every rank lays the chains out from them. Nothing if a stop
// request (on any rank) came first: the ranks then stop in it together, with no chain to start.
std::optional<ChainLayout> bootstrap(const ChainRun& cr, int64_t samples, int chains, const std::atomic<bool>* stop,
                                     Team& team) {
    auto stopRequested = [stop] { return stop && stop->load(std::memory_order_relaxed); };
    ChainLayout layout;
    const int K = cr.maxDepth;
    const uint64_t perLength = (uint64_t(samples) + uint64_t(K) - 1) / uint64_t(K);
    const uint64_t total = perLength * uint64_t(K);
    const uint64_t begin = total * uint64_t(team.rank()) / uint64_t(team.size());
    const uint64_t end = total * uint64_t(team.rank() + 1) / uint64_t(team.size());
    std::vector<float> mine(end - begin);
    tbb::parallel_for(tbb::blocked_range<uint64_t>(begin, end, 64), [&](const tbb::blocked_range<uint64_t>& r) {
        thread_local TargetPaths paths;
        enrolThread();
        for (uint64_t i = r.begin(); i < r.end(); ++i) {
            if ((i - r.begin()) % kSamplesPerStopCheck == 0 && stopRequested()) return;
            const int k = static_cast<int>(i / perLength) + 1;
            Rng fresh = cr.bootstrapStream(k, i % perLength, perLength);
            MarkovChain sample(k);
            sample.start(cr.target, fresh, paths);
            const float l = sample.current().luminance();
            mine[i - begin] = std::isfinite(l) ? l : -1.0f;  // -1: not finite, counted and taken as 0
        }
    });
    if (team.any(stopRequested())) return std::nullopt;
    // Rank 0 gathers every rank's slice (in rank order: sample order) and hands the whole to all.
    std::string bytes(reinterpret_cast<const char*>(mine.data()), mine.size() * sizeof(float));
    const std::vector<std::string> slices = team.gather(bytes);
    bytes.clear();
    for (const std::string& s : slices) bytes += s;
    team.broadcast(bytes);
    const auto* luminance = reinterpret_cast<const float*>(bytes.data());

    layout.samplesPerLength = perLength;
    double sum = 0;
    for (int k = 1; k <= K; ++k) {
        std::vector<double>& c = layout.cumulative.emplace_back();
        double running = 0;
        for (uint64_t j = 0; j < perLength; ++j) {
            const float l = luminance[uint64_t(k - 1) * perLength + j];
            layout.notFinite += l < 0;
            running += std::max(0.0f, l);
            c.push_back(running);
        }
        layout.normalisation.push_back(running / double(perLength));
        sum += running / double(perLength);
    }
    for (int k = 1; k <= K; ++k) {
        const double b = layout.normalisation[k - 1];
        const int n = b > 0 ? std::max(1, static_cast<int>(std::lround(chains * b / sum))) : 0;
        layout.firstChain.push_back(layout.firstChain.back() + n);
    }
    return layout;
}

// Chain i of the layout, started at a bootstrap sample of its length drawn in proportion to its
// luminance (by the first number of the chain's own stream).
MarkovChain startChain(const ChainRun& cr, const ChainLayout& layout, int i, TargetPaths& paths) {
    const int k = layout.lengthOf(i);
    const std::vector<double>& c = layout.cumulative[k - 1];
    Rng pick = cr.chainStream(i, 0);
    const double u = pick.uniform() * c.back();
    const uint64_t j = std::min<uint64_t>(std::upper_bound(c.begin(), c.end(), u) - c.begin(), c.size() - 1);
    Rng fresh = cr.bootstrapStream(k, j, layout.samplesPerLength);
    MarkovChain chain(k);
    chain.start(cr.target, fresh, paths);
    return chain;
}

struct ChainSplat {
    int pixel, k;
    Spectrum value;
};

// What this rank's chains did in one pass besides their splats.
struct PassCounts {
    uint64_t notFinite = 0, guarded = 0;
};

class ChainRenderer {
public:
    ChainRenderer(const ChainRun& cr, const ChainLayout& layout, Team& team) : cr_(cr), layout_(layout) {
        for (int i = team.rank(); i < layout.chains(); i += team.size()) ids_.push_back(i);
        chains_.resize(ids_.size());
        splats_.resize(ids_.size());
        counts_.resize(ids_.size());
    }

    void start() {
        forEachChain([&](size_t c, TargetPaths& paths) { chains_[c] = startChain(cr_, layout_, ids_[c], paths); });
    }

    // Every chain's state from `states` (all chains', in chain order): this rank's.
    void resume(std::string_view states) {
        std::string_view in = states;
        size_t mine = 0;
        for (int i = 0; i < layout_.chains(); ++i) {
            const auto size = takeBytes<uint64_t>(in);
            if (size > in.size()) throw InputError("a checkpoint's chain states are cut short");
            std::string_view bytes = in.substr(0, size);
            in.remove_prefix(size);
            if (mine < ids_.size() && ids_[mine] == i) {
                chains_[mine] = MarkovChain(layout_.lengthOf(i));
                chains_[mine++].read(bytes);
            }
        }
        if (mine != ids_.size() || !in.empty()) throw InputError("a checkpoint's chain states do not match its chains");
    }

    // One pass: every chain takes m steps; their splats go into the film, chain by chain.
    void pass(Film& film, RenderResult& result) {
        const int width = cr_.scene.camera().width(), height = cr_.scene.camera().height();
        forEachChain([&](size_t c, TargetPaths& paths) {
            MarkovChain& chain = chains_[c];
            const float scale = static_cast<float>(layout_.scale(chain.length()));
            std::vector<ChainSplat>& out = splats_[c];
            out.clear();
            auto splat = [&](const PathSample& s, float weight) {
                const int x = std::clamp(static_cast<int>(s.raster.x), 0, width - 1);
                const int y = std::clamp(static_cast<int>(s.raster.y), 0, height - 1);
                out.push_back({y * width + x, chain.length(), s.value * (weight * scale)});
            };
            PassCounts& counts = counts_[c];
            const uint64_t guardedBefore = chain.guardedWeights();
            for (int i = 0; i < layout_.stepsPerPass; ++i) {
                Rng rng = cr_.chainStream(ids_[c], chain.steps() + 1);
                const StepOutcome o = chain.step(cr_.target, cr_.largeStep, rng, paths, splat);
                counts.notFinite += o == StepOutcome::NotFinite;
                kAcceptedMutations.add(o == StepOutcome::Accepted);
            }
            counts.guarded += chain.guardedWeights() - guardedBefore;
            kMutations.add(uint64_t(layout_.stepsPerPass));
        });
        const PhaseScope filing(Phase::Film);
        for (size_t c = 0; c < chains_.size(); ++c) {
            for (const ChainSplat& s : splats_[c]) film.addExactly(s.pixel, s.k, s.value);
            result.droppedSamples += counts_[c].notFinite;
            result.guardedWeights += counts_[c].guarded;
            counts_[c] = {};
        }
    }

    // Every chain's state in chain order, on rank 0 (collective).
    std::string states(Team& team) const {
        std::string mine;
        for (const MarkovChain& chain : chains_) {
            std::string bytes;
            chain.write(bytes);
            putBytes(mine, uint64_t(bytes.size()));
            mine += bytes;
        }
        const std::vector<std::string> all = team.gather(mine);
        if (all.empty()) return {};
        // Rank r holds chains r, r + R, …: interleave the ranks' lists back into chain order.
        std::vector<std::string_view> rest(all.begin(), all.end());
        std::string out;
        for (int i = 0; i < layout_.chains(); ++i) {
            std::string_view& in = rest[size_t(i) % rest.size()];
            std::string_view size = in;
            const size_t n = sizeof(uint64_t) + takeBytes<uint64_t>(size);
            out.append(in.substr(0, n));
            in.remove_prefix(n);
        }
        return out;
    }

    // The chains' counts per length, over the team (collective).
    std::vector<MetropolisLength> lengths(Team& team) const {
        std::vector<uint64_t> counts(2 * cr_.maxDepth, 0);
        for (const MarkovChain& chain : chains_) {
            counts[2 * size_t(chain.length() - 1)] += chain.steps();
            counts[2 * size_t(chain.length() - 1) + 1] += chain.accepted();
        }
        team.sum(counts);
        std::vector<MetropolisLength> out;
        for (int k = 1; k <= cr_.maxDepth; ++k)
            out.push_back({layout_.normalisation[k - 1], uint64_t(layout_.firstChain[k] - layout_.firstChain[k - 1]),
                           counts[2 * size_t(k - 1)], counts[2 * size_t(k - 1) + 1]});
        return out;
    }

private:
    template <class F>
    void forEachChain(F&& f) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, chains_.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
            thread_local TargetPaths paths;
            enrolThread();
            const PhaseScope scope(Phase::CameraSamples);
            for (size_t c = r.begin(); c < r.end(); ++c) f(c, paths);
        });
    }

    const ChainRun& cr_;
    const ChainLayout& layout_;
    std::vector<int> ids_;  // the chains this rank runs: rank, rank + ranks, …
    std::vector<MarkovChain> chains_;
    std::vector<std::vector<ChainSplat>> splats_;
    std::vector<PassCounts> counts_;
};

// mlt's passes: every rank renders every pass, each with its share of the chains (chain i on
// rank i mod ranks), so the team stops only together; the bootstrap comes first, on the clock.
class ChainPasses final : public PassSource {
public:
    ChainPasses(const Scene& scene, const Integrator& integrator, const RenderSettings& settings)
        : team_(settings.team ? *settings.team : solo()), settings_(settings),
          ms_(integrator.settings().metropolis), pixels_(double(scene.camera().width()) * scene.camera().height()),
          firstPass_(settings.resume ? settings.resume->nextPass : settings.firstPass),
          cr_(runOf(scene, integrator, settings, pixels_)),
          arena_(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic) {}

    bool start(RenderResult& result) override {
        const int chains = static_cast<int>(std::min<double>(ms_.chains, pixels_));
        std::optional<ChainLayout> bootstrapped =
            arena_.execute([&] { return bootstrap(cr_, ms_.bootstrap, chains, settings_.stop, team_); });
        if (!bootstrapped) return false;
        layout_ = std::move(*bootstrapped);
        layout_.stepsPerPass = layout_.chains() > 0 ? static_cast<int>(std::ceil(pixels_ / layout_.chains())) : 0;
        renderer_.emplace(cr_, layout_, team_);
        std::string states = settings_.resume ? settings_.resume->methodState : std::string();
        team_.broadcast(states);
        if (settings_.resume)
            renderer_->resume(states);
        else
            arena_.execute([&] { renderer_->start(); });
        if (team_.rank() == 0) result.droppedSamples += layout_.notFinite;
        result.metropolis.run = cr_.run;
        result.metropolis.bootstrapSamples = uint64_t(ms_.bootstrap);
        return true;
    }
    std::pair<uint64_t, uint64_t> round(uint64_t round, uint64_t budget) const override {
        return {round, std::min(budget, round + 1)};
    }
    // Without chains (the bootstrap found no light at any length) a pass is empty and the image
    // black: one pass says so, whatever the time budget.
    bool budgetDone(uint64_t round, uint64_t budget) const override {
        return round + 1 >= budget || (layout_.chains() == 0 && settings_.seconds > 0);
    }
    bool stopsAlone() const override { return false; }
    void run(uint64_t, RenderResult& result) override {
        arena_.execute([&] { renderer_->pass(result.film, result); });
    }
    int passesDone(uint64_t local) const override { return static_cast<int>(local); }
    void gather(RenderResult& into, Film& mine, uint64_t local, uint64_t, const RenderResult& counts) override {
        into.passes = static_cast<int>(local);
        into.nextPass = firstPass_ + local;
        std::array<uint64_t, 2> sums{counts.droppedSamples, counts.guardedWeights};
        team_.sum(sums);
        into.droppedSamples = sums[0];
        into.guardedWeights = sums[1];
        into.metropolis.run = cr_.run;
        into.metropolis.bootstrapSamples = uint64_t(ms_.bootstrap);
        into.metropolis.lengths = renderer_->lengths(team_);
        into.methodState = renderer_->states(team_);
        team_.reduce(team_.rank() == 0 ? into.film : mine);
    }

private:
    // The chains' run: a fresh render's first pass, or the resumed render's run.
    static ChainRun runOf(const Scene& scene, const Integrator& integrator, const RenderSettings& settings, double pixels) {
        const auto [bootstrapDomain, chainDomain] = metropolisDomains(settings.domain);
        return {scene,
                {&scene, multiplexedMisContext(integrator.settings().mis, pixels), pixels},
                settings.seed,
                settings.resume ? settings.resume->metropolis.run : settings.firstPass,
                bootstrapDomain,
                chainDomain,
                integrator.settings().metropolis.largeStep,
                integrator.settings().walk.maxDepth};
    }
    Team& team_;
    const RenderSettings& settings_;
    const MetropolisSettings& ms_;
    const double pixels_;
    const uint64_t firstPass_;
    const ChainRun cr_;
    tbb::task_arena arena_;
    ChainLayout layout_;
    std::optional<ChainRenderer> renderer_;
};

}  // namespace

MetropolisMemory metropolisMemory(double pixels, const MetropolisSettings& settings, int maxDepth) {
    const double chains = std::min<double>(settings.chains, pixels);
    // The bootstrap's bytes per sample: the rank's luminances, the bytes they are sent as (which
    // then hold the concatenation) and the gathered slices, 4 each, and the layout's running sum.
    constexpr uint64_t kBootstrapBytes = 3 * sizeof(float) + sizeof(double);
    return {static_cast<uint64_t>(chains) * MarkovChain::bytesFor(maxDepth),
            static_cast<uint64_t>(2 * std::ceil(pixels / chains) * chains) * sizeof(ChainSplat),
            uint64_t(settings.bootstrap) * kBootstrapBytes};
}

RenderResult renderMetropolis(const Scene& scene, const Integrator& integrator, const RenderSettings& settings) {
    RenderResult result = startRender(scene, integrator, settings);
    ChainPasses passes(scene, integrator, settings);
    return runPasses(settings, passes, std::move(result));
}

}  // namespace tripath
