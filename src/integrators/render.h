// The one render loop every integrator runs in: progressive passes of one sample per pixel,
// parallel over tiles, reproducible whatever the number of threads.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>

#include "geometry/rng.h"
#include "geometry/stats.h"
#include "integrators/film.h"
#include "integrators/integrator.h"

namespace tripath {

struct RenderSettings {
    int spp = 16;                 // passes to render; with `seconds` > 0, an upper bound (0: none)
    double seconds = 0;           // > 0: stop at the first pass boundary after this much time
    uint64_t seed = 1;
    // The streams the per-pixel samples draw from: CameraSample for renders, Reference for
    // references, so that a reference and a render with the same seed share no random numbers.
    StreamDomain domain = StreamDomain::CameraSample;
    uint64_t firstPass = 0;       // sample index of the first pass: lets a reference add fresh samples
    int threads = 0;              // 0: all cores
    bool timing = false;          // run the phase timers (geometry/stats.h) for RenderResult::stats
    FilmLayers layers;
    // Called after each pass with (passes done, seconds so far); may be empty.
    std::function<void(int, double)> progress;
    // Called after each pass with the film so far (its image is film.image(passes)); may be empty.
    // Time spent inside it belongs to the caller (e.g. measuring error against a reference), so it
    // counts neither towards `seconds` nor towards RenderResult::seconds.
    std::function<void(const Film&, int passes, double seconds)> onPass;
    // Set from elsewhere (a signal handler) to stop at the next pass boundary.
    const std::atomic<bool>* stop = nullptr;
};

struct RenderResult {
    Film film;
    int passes = 0;
    double seconds = 0;
    uint64_t droppedSamples = 0;  // NaN or infinite contributions kept off the film
    uint64_t guardedWeights = 0;  // MIS weights set to 0 because a pdf ratio was not finite (mis.h)
    // What the render did (geometry/stats.h): its events, and with timing on its cycles per phase.
    // Taken as the difference of two process-wide snapshots, so renders must not overlap.
    StatsSnapshot stats{};
    Image image() const { return film.image(passes); }
};

RenderResult render(const Scene& scene, const Integrator& integrator, const RenderSettings& settings);

}  // namespace tripath
