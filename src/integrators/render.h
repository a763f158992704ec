// A render's settings and result, and the passes of the methods that render camera samples
// (PixelSampleIntegrator): progressive passes of one sample per pixel, parallel over tiles,
// reproducible whatever the number of threads and of processes. The loop over the passes, which
// every method shares, is render_loop.h; mlt's passes are metropolis_render.h.
//
// Passes are grouped in canonical blocks of kPassesPerBlock, counted from the first pass. A block
// is summed in double in pass order, then added exactly into the film's totals (film.h). A team of
// N processes (team.h) renders in rounds: in round j, rank r renders block j·N + r; at the round's
// end the team decides together whether to go on. Since each block's sums do not depend on who
// renders it and blocks add exactly, a --spp render is bit-identical for any N and thread count.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/rng.h"
#include "core/sample_stream.h"
#include "core/stats.h"
#include "integrators/film.h"
#include "integrators/memory_estimate.h"
#include "integrators/pixel_sample_integrator.h"
#include "integrators/plan_report.h"
#include "integrators/team.h"

namespace tripath {

// Passes per canonical block. Small enough that a pass-count budget spreads over a few ranks and a
// checkpoint comes soon after its interval; large enough that ending blocks costs nothing
// measurable (bench/distributed.cpp: folding a 512² film into its totals).
constexpr int kPassesPerBlock = 4;

struct RenderResult;

// A pixel's sample that made a NaN or infinite contribution, which the film dropped: enough to
// render that one sample again with replaySample. A render keeps the first few. For lt the sample
// is the pixel's share of the pass's light paths (PixelSampleIntegrator::splatLightPaths).
struct DroppedSample {
    uint64_t pass = 0;
    int pixel = 0;  // y · width + x of the sample (lt too: its light paths are pixel, pixel + P, …)
};
constexpr size_t kDroppedLogSize = 16;

// The largest first pass a render may be given or a saved render may claim to have reached (a
// checkpoint's next-pass, a reference's tripath:next-pass): a pass's random streams are numbered
// pass × pixels + pixel and pass × light paths + path, which stay below 2^64 for every pass up to
// 2^35 even at 16384² pixels and as many light paths (2^28 each), so no stream is used twice.
constexpr uint64_t kMaxFirstPass = uint64_t(1) << 35;

struct RenderSettings {
    int spp = 16;                 // passes this run renders; with `seconds` > 0, an upper bound (0: none)
    double seconds = 0;           // > 0: stop at the first pass boundary after this much time
    uint64_t seed = 1;
    // The streams the per-pixel samples draw from: CameraSample for renders, Reference for
    // references, so that a reference and a render with the same seed share no random numbers.
    StreamDomain domain = StreamDomain::CameraSample;
    SamplerKind sampler = SamplerKind::Sobol;  // what the samples draw from (core/sample_stream.h)
    StreamSource streams() const { return {seed, domain, sampler}; }
    uint64_t firstPass = 0;       // sample index of the first pass: lets a reference add fresh samples
    int threads = 0;              // 0: all cores
    bool timing = false;          // run the phase timers (core/stats.h) for RenderResult::stats
    FilmLayers layers;
    // Called after each pass with (passes done, seconds so far); may be empty.
    std::function<void(int, double)> progress;
    // Called after each pass with the film so far (its image is film.image(passes)); may be empty.
    // Time spent inside it belongs to the caller (e.g. measuring error against a reference), so it
    // counts neither towards `seconds` nor towards RenderResult::seconds.
    std::function<void(const Film&, int passes, double seconds)> onPass;
    // Set from elsewhere (a signal handler) to stop at the next pass boundary: every rank stops at
    // its next pass, so the passes used need not be contiguous then (RenderResult::nextPass).
    // mlt looks at it in its bootstrap too, and stops there before any pass.
    const std::atomic<bool>* stop = nullptr;
    // The processes sharing the render; nullptr: this one alone.
    Team* team = nullptr;
    // A checkpointed render to go on from (its film's blocks ended; it counts towards nothing
    // but the result's totals): the render starts at its nextPass, and rank 0 adds its film.
    const RenderResult* resume = nullptr;
    // > 0: at the first round boundary after each such interval, rank 0 is handed the whole
    // render so far (reduced over the team) through onCheckpoint.
    double checkpointSeconds = 0;
    std::function<void(const RenderResult&)> onCheckpoint;
    // Called with the render's memory estimate (memory_estimate.h) before the film and the light
    // paths are allocated, on every rank together: it throws InputError to refuse the render, and
    // every rank then throws the lowest failing rank's (team.h, together). May be empty.
    std::function<void(const MemoryEstimate&)> checkMemory;
};

// What mlt's chains did (integrators/metropolis_render.h), per path length k = 1 … max-depth
// (index k − 1), over the whole team and the resumed render.
struct MetropolisLength {
    double normalisation = 0;  // b_k: the mean luminance of the target C_k over the bootstrap samples
    uint64_t chains = 0, steps = 0, accepted = 0;
};
struct MetropolisReport {
    uint64_t run = 0;               // the pass index the chains started at: their streams' identity
    uint64_t bootstrapSamples = 0;  // N, over all lengths
    std::vector<MetropolisLength> lengths;
};

struct RenderResult {
    Film film;                    // on rank 0 of a team, every rank's passes; on the others, their own
    int passes = 0;               // passes in the film, over the whole team (and the resumed render)
    uint64_t nextPass = 0;        // the first pass index that no pass in the film used
    double seconds = 0;
    uint64_t droppedSamples = 0;  // NaN or infinite contributions kept off the film
    uint64_t guardedWeights = 0;  // MIS weights set to 0 because a pdf ratio was not finite (mis.h)
    double reduceSeconds = 0;     // spent adding the team's films into rank 0's at the end
    // The team's first kDroppedLogSize dropped samples in pass, tile and pixel order: the same log
    // for any number of ranks and threads.
    std::vector<DroppedSample> droppedLog{};
    // What the render did (core/stats.h): its events, and with timing on its profiling samples
    // per phase of the render loop.
    // Taken as the difference of two process-wide snapshots, so renders must not overlap.
    StatsSnapshot stats{};
    // The budget it was given, the resumed render's part included (0: no bound of that kind), and
    // whether a stop request (RenderSettings::stop, on any rank) ended it.
    int budgetPasses = 0;
    double budgetSeconds = 0;
    bool interrupted = false;
    // Whether the stop request came before this run rendered any pass, which only mlt allows (it
    // stops in its bootstrap; the other loops finish their first pass): the result then holds
    // nothing, not even the render it resumed, and has no image to write nor state to checkpoint.
    bool interruptedBeforeAnyPass = false;
    // On rank 0, the method's state to go on from (checkpoints): mlt's chains, in chain order;
    // auto's moments and plans. Empty for the other methods.
    std::string methodState{};
    MetropolisReport metropolis{};  // mlt only
    PlanReport plans{};             // auto only
    MemoryEstimate memory{};        // what the render was estimated to need before it started
    Image image() const { return film.image(passes); }
};

// How far an interrupted render got against its budget: "after 5 of 16 passes, 0.52 s" or, for a
// time budget, "after 5 passes, 0.52 s of 10 s". The summary line and tripath:interrupted say it.
std::string interruptionText(const RenderResult& r);

// Rank 0's result gains the render it resumed (films add exactly, so where a render was cut does
// not show in its bits): its film, passes, seconds, counts and budget.
RenderResult& addResumed(RenderResult& r, const RenderResult* resume);

RenderResult render(const Scene& scene, const Integrator& integrator, const RenderSettings& settings);

// The render's memory estimate, passed through settings.checkMemory (if set) on every rank of its
// team together: what every method's render calls (startRender) before it allocates anything large.
MemoryEstimate admitMemory(const Scene& scene, const Integrator& integrator, const RenderSettings& settings);

// The result a method's render starts from: the film of the camera's size with the settings'
// layers and the method's strategies, the budget, and the memory estimate admitted (admitMemory)
// before the film is allocated.
RenderResult startRender(const Scene& scene, const Integrator& integrator, const RenderSettings& settings);

// The memory `splats` light-tracing splats (t = 1 connections) take while they wait for the end of
// their pass, when they are added to the film in tile order.
uint64_t pendingSplatBytes(double splats);

// Renders camera sample (pass, pixel) of a render with these settings again, exactly as render()
// did (after the light phase of its pass, when the integrator has one), and hands each of its
// contributions to `sink`, finite or not: `tripath render --replay`. For lt, the pixel's sample
// is its light paths pixel, pixel + P, … below N_L (P pixels), each joined to the sensor.
void replaySample(const Scene& scene, const PixelSampleIntegrator& integrator, const RenderSettings& settings, uint64_t pass,
                  int pixel, ContributionSink& sink);

}  // namespace tripath
