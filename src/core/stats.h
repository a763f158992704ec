// Where a render's work and time go: event counters that are always on, and phase
// sampling that runs only when asked for (`tripath render --stats`).
//
// Counters. Each thread counts into its own thread-local array (an increment is one instruction:
// no sharing, no atomics, no check on the hot path), and a thread that enrols once (the render
// loop's tasks do, at their start) lists its array where snapshots find it; when the thread ends,
// its counts move to a total of finished threads. The counts are of events a seed determines
// (rays, BSDF calls, connections), so they are the same for any number of threads. A snapshot
// reads other threads' arrays without synchronisation of its own: take it when the work it
// measures has been joined (render() does), never while another render runs.
//
// Phases. With timing on, each thread keeps a tag of the phase it is in (a PhaseScope sets it and
// puts the outer one back, so phases are exclusive: a shadow ray cast inside a connection is
// traversal, not sampling), and a profiling timer (SIGPROF every millisecond of the process's
// CPU time) samples the tag of the thread that is running. The shares of the samples are the
// shares of CPU time, to within the sampling error (about 1/sqrt(samples), which the report
// shows). Tagging is one load and two stores per scope, so the render runs at its own speed;
// reading a clock around every scope instead would cost ~8 ns per read here and distort exactly
// the small, frequent phases (a BSDF evaluation) that the report is for.
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
    EmitterSamples,   // a point drawn on an emitter (light subpath start, next-event estimation)
    Connections,      // a join of two subpath endpoints evaluated up to its shadow ray
    EmitterHits,      // a camera vertex found on an emitter (strategy s = 0)
    Splats,           // a t = 1 contribution kept for another pixel
    LightVertices,    // vertices stored by light phases
    RangeQueries,     // merge searches around a camera vertex
    Merges,           // light vertices found within the radius and merged
    Count
};
inline constexpr int kEventCount = static_cast<int>(Event::Count);
std::string_view eventName(Event e);
// The name as an identifier (spaces and hyphens as underscores): CSV columns, Python's dict keys.
std::string eventKey(Event e);

enum class Phase : int {
    Idle,        // outside any scope: not working on a render
    Sampling,    // the walks' and connections' own logic: everything not below
    Traversal,   // Embree: closest-hit and shadow rays
    Scattering,  // BSDF sampling and evaluation; Le at connections (emitter points: Sampling)
    Mis,         // area pdfs from points and MIS weights
    Search,      // light phase: storing and indexing; merges: range queries
    Film,        // adding contributions to the film
    Count
};
inline constexpr int kPhaseCount = static_cast<int>(Phase::Count);
std::string_view phaseName(Phase p);

inline thread_local uint64_t tlsEvents[kEventCount];  // zero-initialised: no guard on access

inline void count(Event e, uint64_t n = 1) { tlsEvents[static_cast<int>(e)] += n; }

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
