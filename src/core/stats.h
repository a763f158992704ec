// Where a render's work and time go: event counters that are always on, and phase
// sampling that runs only when asked for (`tripath render --stats`).
//
// Counters. Each file that counts an event declares its Counter once, at its top, and bumps it
// where the event happens. Each thread counts into its own thread-local array (an increment is
// one instruction: no sharing, no atomics, no check on the hot path), and a thread that enrols
// once (the render loop's tasks do, at their start) lists its array where snapshots find it; when
// the thread ends, its counts move to a total of finished threads. The counts are of events a seed
// determines (rays, BSDF calls, connections), so they are the same for any number of threads. A
// snapshot reads other threads' arrays without synchronisation of its own: take it when the work
// it measures has been joined (render() does), never while another render runs.
//
// Phases are the render loop's: the light phase's tracing and its merge index, the tiles of camera
// samples, the film. The loop tags each task with its phase (a PhaseScope per task or step, never
// inside a kernel: a tile's rays, BSDFs, connections and merges are all its camera samples'
// time), and with timing on a profiling timer (SIGPROF every millisecond of the process's CPU
// time) samples the tag of the thread that is running. The shares of the samples are the shares
// of CPU time, to within the sampling error (about 1/sqrt(samples), which the report shows).
#pragma once
#include <array>
#include <atomic>
#include <cstdint>
#include <string>
#include <string_view>

namespace tripath {

enum class Event : int {
    ClosestHitRays,   // Scene::intersect
    ShadowRays,       // Scene::unoccluded
    BsdfSamples,      // sampleBsdf
    BsdfEvaluations,  // evalBsdf
    BsdfPdfs,         // pdfBsdf
    BsdfDerivations,  // Scene::bsdfAt where textures or vertex colours vary a material's parameters
    EmitterSamples,   // a point drawn on an emitter (light subpath start, next-event estimation)
    Connections,      // a join of two subpath endpoints evaluated up to its shadow ray
    EmitterHits,      // a camera vertex found on an emitter (strategy s = 0)
    Splats,           // a t = 1 contribution kept for another pixel
    LightVertices,    // vertices stored by light phases
    RangeQueries,     // merge searches around a camera vertex
    Merges,           // light vertices found within the radius and merged
    Mutations,        // proposals of mlt's chains
    AcceptedMutations,  // of which accepted
    Count
};
inline constexpr int kEventCount = static_cast<int>(Event::Count);
std::string_view eventName(Event e);
// The name as an identifier (spaces and hyphens as underscores): CSV columns, Python's dict keys.
std::string eventKey(Event e);

enum class Phase : int {
    Idle,           // outside any scope: pass set-up, TBB scheduling and waiting, or no render
    LightPaths,     // the light phase: tracing and storing the pass's light subpaths
    MergeIndex,     // the light phase: indexing the light vertices for merging
    CameraSamples,  // the tiles: camera walks, connections, merges, and their own pixels' film writes
    Film,           // after each pass its splats, after each block the fold into the film's totals
    Count
};
inline constexpr int kPhaseCount = static_cast<int>(Phase::Count);
std::string_view phaseName(Phase p);

inline thread_local uint64_t tlsEvents[kEventCount];  // zero-initialised: no guard on access

// One event's counter, declared once at the top of a file that counts it, e.g.
//     constexpr Counter kShadowRays{Event::ShadowRays};
// and bumped where the event happens: kShadowRays.add().
class Counter {
public:
    explicit constexpr Counter(Event e) : index_(static_cast<int>(e)) {}
    void add(uint64_t n = 1) const { tlsEvents[index_] += n; }

private:
    int index_;
};

// Lists the calling thread's counters for snapshots; the first call per thread does the work.
void enrolThread();

// Totals over every thread that ever counted, and the profiling samples taken in each phase:
// differences of two snapshots measure what ran between.
struct StatsSnapshot {
    std::array<uint64_t, kEventCount> events{};
    std::array<uint64_t, kPhaseCount> phaseSamples{};
    uint64_t operator[](Event e) const { return events[static_cast<int>(e)]; }
    StatsSnapshot operator-(const StatsSnapshot& earlier) const;
};
StatsSnapshot statsSnapshot();

// Phase sampling for the whole process: on starts the profiling timer, off stops it. Not nested.
void setTiming(bool on);
inline std::atomic<bool> timingOn{false};
inline bool timingEnabled() { return timingOn.load(std::memory_order_relaxed); }
inline thread_local Phase tlsPhase = Phase::Idle;

class PhaseScope {
public:
    explicit PhaseScope(Phase p) {
        if (!timingEnabled()) return;
        active_ = true;
        outer_ = tlsPhase;
        tlsPhase = p;
    }
    ~PhaseScope() {
        if (active_) tlsPhase = outer_;
    }
    PhaseScope(const PhaseScope&) = delete;
    PhaseScope& operator=(const PhaseScope&) = delete;

private:
    bool active_ = false;
    Phase outer_ = Phase::Idle;
};

}  // namespace tripath
