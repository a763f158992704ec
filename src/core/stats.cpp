#include "core/stats.h"

#include <signal.h>
#include <sys/time.h>

#include <algorithm>
#include <mutex>
#include <vector>

namespace tripath {

namespace {

// The enrolled threads' counters, and what finished threads counted.
struct Registry {
    std::mutex mutex;
    std::vector<const uint64_t*> live;
    std::array<uint64_t, kEventCount> finished{};
};

// Never destroyed: worker threads may end after the static destructors ran at exit, and their
// Enrolment still reports to it then.
Registry& registry() {
    static Registry* r = new Registry;
    return *r;
}

// Lives as long as its thread: lists the thread's counters on creation, folds them into the
// finished total on exit.
struct Enrolment {
    Enrolment() {
        Registry& r = registry();
        std::lock_guard lock(r.mutex);
        r.live.push_back(tlsEvents);
    }
    ~Enrolment() {
        Registry& r = registry();
        std::lock_guard lock(r.mutex);
        for (int i = 0; i < kEventCount; ++i) r.finished[i] += tlsEvents[i];
        std::erase(r.live, tlsEvents);
    }
};

// Profiling samples per phase. Written by the signal handler (lock-free atomics are
// async-signal-safe), read by snapshots.
std::array<std::atomic<uint64_t>, kPhaseCount> phaseSamples{};
static_assert(std::atomic<uint64_t>::is_always_lock_free);

void onProfilingTick(int) { phaseSamples[static_cast<int>(tlsPhase)].fetch_add(1, std::memory_order_relaxed); }

constexpr long kTickMicroseconds = 1000;  // of process CPU time; the kernel rounds up to its tick

void setProfilingTimer(long micros) {
    itimerval t{};
    t.it_interval.tv_usec = micros;
    t.it_value.tv_usec = micros;
    setitimer(ITIMER_PROF, &t, nullptr);
}

}  // namespace

std::string_view eventName(Event e) {
    switch (e) {
    case Event::ClosestHitRays: return "closest-hit rays";
    case Event::ShadowRays: return "shadow rays";
    case Event::BsdfSamples: return "BSDF samples";
    case Event::BsdfEvaluations: return "BSDF evaluations";
    case Event::BsdfPdfs: return "BSDF pdfs";
    case Event::BsdfDerivations: return "BSDF derivations";
    case Event::EmitterSamples: return "emitter samples";
    case Event::Connections: return "connections";
    case Event::EmitterHits: return "emitter hits";
    case Event::Splats: return "splats";
    case Event::LightVertices: return "light vertices stored";
    case Event::RangeQueries: return "range queries";
    case Event::Merges: return "merges";
    case Event::Mutations: return "mutations";
    case Event::AcceptedMutations: return "accepted mutations";
    case Event::Count: break;
    }
    return "?";
}

std::string eventKey(Event e) {
    std::string key(eventName(e));
    std::replace_if(key.begin(), key.end(), [](char c) { return c == ' ' || c == '-'; }, '_');
    return key;
}

std::string_view phaseName(Phase p) {
    switch (p) {
    case Phase::Idle: return "outside the render's phases";
    case Phase::LightPaths: return "light phase: light paths";
    case Phase::MergeIndex: return "light phase: merge index";
    case Phase::CameraSamples: return "camera samples (tiles)";
    case Phase::Film: return "film: splats and blocks";
    case Phase::Count: break;
    }
    return "?";
}

void enrolThread() { thread_local Enrolment enrolment; }

StatsSnapshot StatsSnapshot::operator-(const StatsSnapshot& earlier) const {
    StatsSnapshot d;
    for (int i = 0; i < kEventCount; ++i) d.events[i] = events[i] - earlier.events[i];
    for (int i = 0; i < kPhaseCount; ++i) d.phaseSamples[i] = phaseSamples[i] - earlier.phaseSamples[i];
    return d;
}

StatsSnapshot statsSnapshot() {
    Registry& r = registry();
    std::lock_guard lock(r.mutex);
    StatsSnapshot total;
    total.events = r.finished;
    for (const uint64_t* events : r.live)
        for (int i = 0; i < kEventCount; ++i) total.events[i] += events[i];
    for (int i = 0; i < kPhaseCount; ++i) total.phaseSamples[i] = phaseSamples[i].load(std::memory_order_relaxed);
    return total;
}

void setTiming(bool on) {
    if (on == timingEnabled()) return;
    if (on) {
        struct sigaction sa {};
        sa.sa_handler = onProfilingTick;
        sa.sa_flags = SA_RESTART;
        sigemptyset(&sa.sa_mask);
        sigaction(SIGPROF, &sa, nullptr);
        timingOn.store(true, std::memory_order_relaxed);
        setProfilingTimer(kTickMicroseconds);
    } else {
        setProfilingTimer(0);
        timingOn.store(false, std::memory_order_relaxed);
    }
}

}  // namespace tripath
