// The loop over passes (render_loop.h).
#include "integrators/render_loop.h"

#include <array>
#include <chrono>

namespace tripath {

namespace {

double since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The render's wall time and whether a stop request reached any rank, the same on every rank.
void agreeOnTimeAndStop(Team& team, RenderResult& r, bool stopped) {
    std::array<uint64_t, 2> maxima{static_cast<uint64_t>(r.seconds * 1e6), stopped};
    team.max(maxima);
    r.seconds = maxima[0] / 1e6;
    r.interrupted = maxima[1] != 0;
}

}  // namespace

RenderResult runPasses(const RenderSettings& settings, PassSource& source, RenderResult result) {
    Team& team = settings.team ? *settings.team : solo();
    const RenderResult* resume = settings.resume;
    setTiming(settings.timing);
    enrolThread();
    const StatsSnapshot statsBefore = statsSnapshot();
    team.any(false);  // start together: --time counts from the same moment on every rank
    const auto start = std::chrono::steady_clock::now();
    double callbackSeconds = 0;  // spent in onPass and onCheckpoint: the caller's time, not the render's
    auto elapsed = [&] { return since(start) - callbackSeconds; };
    auto stopRequested = [&] { return settings.stop && settings.stop->load(); };
    auto timeUpOrStopped = [&] { return (settings.seconds > 0 && elapsed() >= settings.seconds) || stopRequested(); };
    if (!source.start(result)) {
        result.seconds = elapsed();
        result.interrupted = result.interruptedBeforeAnyPass = true;
        setTiming(false);
        return result;
    }

    double lastCheckpoint = 0;
    uint64_t local = 0;      // passes this rank rendered
    uint64_t localNext = 0;  // one past the highest pass offset this rank used
    const uint64_t budget = settings.spp > 0 ? uint64_t(settings.spp) : UINT64_MAX;
    for (uint64_t round = 0;; ++round) {
        source.beginRound(result.film);
        const auto [begin, end] = source.round(round, budget);
        bool halted = false;  // by the clock or by a stop request, before the round's end
        for (uint64_t p = begin; p < end; ++p) {
            if (source.stopsAlone() && local > 0 && timeUpOrStopped()) {
                halted = true;
                break;
            }
            source.run(p, result);
            ++local;
            localNext = p + 1;
            result.seconds = elapsed();
            if (settings.progress) settings.progress(source.passesDone(local), result.seconds);
            if (settings.onPass) {
                const auto t0 = std::chrono::steady_clock::now();
                settings.onPass(result.film, int(local), result.seconds);
                callbackSeconds += since(t0);
            }
        }
        source.endRound(result.film);
        if (team.any(halted || timeUpOrStopped()) || source.budgetDone(round, budget)) break;
        if (settings.checkpointSeconds > 0 && team.any(elapsed() - lastCheckpoint >= settings.checkpointSeconds)) {
            const auto t0 = std::chrono::steady_clock::now();
            // Rank 0 reduces into a copy (its own film must keep only its own passes); the others
            // only send theirs.
            RenderResult sofar{
                .film = team.rank() == 0 ? result.film : Film(0, 0), .seconds = result.seconds, .memory = result.memory};
            agreeOnTimeAndStop(team, sofar, false);
            source.gather(sofar, result.film, local, localNext, result);
            if (team.rank() == 0 && settings.onCheckpoint) settings.onCheckpoint(addResumed(sofar, resume));
            callbackSeconds += since(t0);
            lastCheckpoint = elapsed();
        }
    }
    result.seconds = elapsed();
    agreeOnTimeAndStop(team, result, stopRequested());
    const auto reduceStart = std::chrono::steady_clock::now();
    source.gather(result, result.film, local, localNext, result);
    result.reduceSeconds = since(reduceStart);
    if (team.rank() == 0) addResumed(result, resume);
    result.stats = statsSnapshot() - statsBefore;
    team.sum(result.stats.events);  // counts over the whole team, like the passes
    team.sum(result.stats.phaseSamples);
    setTiming(false);
    return result;
}

}  // namespace tripath
