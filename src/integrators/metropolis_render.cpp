#include "integrators/metropolis_render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/stats.h"
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

// The bootstrap: each rank evaluates its share of the N samples, in parallel, the team gathers
// the luminances in sample order, and every rank lays the chains out from them.
ChainLayout bootstrap(const ChainRun& cr, int64_t samples, int chains, Team& team) {
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
            const int k = static_cast<int>(i / perLength) + 1;
            Rng fresh = cr.bootstrapStream(k, i % perLength, perLength);
            MarkovChain sample(k);
            sample.start(cr.target, fresh, paths);
            const float l = sample.current().luminance();
            mine[i - begin] = std::isfinite(l) ? l : -1.0f;  // -1: not finite, counted and taken as 0
        }
    });
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
    const Camera& cam = scene.camera();
    Team& team = settings.team ? *settings.team : solo();
    const MetropolisSettings& ms = integrator.settings().metropolis;
    const double pixels = double(cam.width()) * cam.height();
    const RenderResult* resume = settings.resume;
    const auto [bootstrapDomain, chainDomain] = metropolisDomains(settings.domain);
    const uint64_t firstPass = resume ? resume->nextPass : settings.firstPass;
    const ChainRun cr{scene,
                      {&scene, multiplexedMisContext(integrator.settings().mis, pixels), pixels},
                      settings.seed,
                      resume ? resume->metropolis.run : settings.firstPass,
                      bootstrapDomain,
                      chainDomain,
                      ms.largeStep,
                      integrator.settings().walk.maxDepth};
    FilmLayers layers = settings.layers;
    layers.strategies = integrator.strategies();
    MemoryEstimate memory = admitMemory(scene, integrator, settings);
    RenderResult result{.film = Film(cam.width(), cam.height(), layers),
                        .budgetPasses = settings.spp,
                        .budgetSeconds = settings.seconds,
                        .memory = std::move(memory)};
    result.metropolis.run = cr.run;
    result.metropolis.bootstrapSamples = uint64_t(ms.bootstrap);
    tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
    setTiming(settings.timing);
    enrolThread();
    const StatsSnapshot statsBefore = statsSnapshot();
    team.any(false);  // start together
    const auto start = std::chrono::steady_clock::now();
    double callbackSeconds = 0;
    auto since = [](auto t0) { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    auto elapsed = [&] { return since(start) - callbackSeconds; };

    const int chains = static_cast<int>(std::min<double>(ms.chains, pixels));
    ChainLayout layout = arena.execute([&] { return bootstrap(cr, ms.bootstrap, chains, team); });
    layout.stepsPerPass = layout.chains() > 0 ? static_cast<int>(std::ceil(pixels / layout.chains())) : 0;
    ChainRenderer renderer(cr, layout, team);
    std::string states = resume ? resume->metropolis.chainStates : std::string();
    team.broadcast(states);
    if (resume)
        renderer.resume(states);
    else
        arena.execute([&] { renderer.start(); });
    if (team.rank() == 0) result.droppedSamples += layout.notFinite;

    const uint64_t budget = settings.spp > 0 ? uint64_t(settings.spp) : UINT64_MAX;
    auto timeUpOrStopped = [&] {
        return (settings.seconds > 0 && elapsed() >= settings.seconds) || (settings.stop && settings.stop->load());
    };
    // The team's totals so far: rank 0's film gains the others' (into `into`), counts and states.
    auto gather = [&](RenderResult& into, Film& mine, uint64_t passes) {
        into.passes = static_cast<int>(passes);
        into.nextPass = firstPass + passes;
        std::array<uint64_t, 2> sums{result.droppedSamples, result.guardedWeights};
        team.sum(sums);
        into.droppedSamples = sums[0];
        into.guardedWeights = sums[1];
        into.metropolis.run = cr.run;
        into.metropolis.bootstrapSamples = uint64_t(ms.bootstrap);
        into.metropolis.lengths = renderer.lengths(team);
        into.metropolis.chainStates = renderer.states(team);
        team.reduce(team.rank() == 0 ? into.film : mine);
    };
    double lastCheckpoint = 0;
    uint64_t local = 0;
    while (local < budget) {
        arena.execute([&] { renderer.pass(result.film, result); });
        ++local;
        result.seconds = elapsed();
        if (settings.progress) settings.progress(int(local), result.seconds);
        if (settings.onPass) {
            const auto t0 = std::chrono::steady_clock::now();
            settings.onPass(result.film, int(local), result.seconds);
            callbackSeconds += since(t0);
        }
        // Without chains (the bootstrap found no light at any length) a pass is empty and the
        // image black: one pass says so, whatever the time budget.
        const bool nothingToDo = layout.chains() == 0 && settings.seconds > 0;
        if (local >= budget || nothingToDo || team.any(timeUpOrStopped())) break;
        if (settings.checkpointSeconds > 0 && team.any(elapsed() - lastCheckpoint >= settings.checkpointSeconds)) {
            const auto t0 = std::chrono::steady_clock::now();
            RenderResult sofar{.film = team.rank() == 0 ? result.film : Film(0, 0), .seconds = result.seconds};
            sofar.memory = result.memory;
            gather(sofar, result.film, local);
            if (team.rank() == 0 && settings.onCheckpoint) settings.onCheckpoint(addResumed(sofar, resume));
            callbackSeconds += since(t0);
            lastCheckpoint = elapsed();
        }
    }
    result.seconds = elapsed();
    std::array<uint64_t, 2> maxima{static_cast<uint64_t>(result.seconds * 1e6), settings.stop && settings.stop->load()};
    team.max(maxima);
    result.seconds = maxima[0] / 1e6;
    result.interrupted = maxima[1] != 0;
    const auto reduceStart = std::chrono::steady_clock::now();
    gather(result, result.film, local);
    result.reduceSeconds = since(reduceStart);
    if (team.rank() == 0) addResumed(result, resume);
    result.stats = statsSnapshot() - statsBefore;
    team.sum(result.stats.events);
    team.sum(result.stats.phaseSamples);
    setTiming(false);
    return result;
}

}  // namespace tripath
