// The light phase of a pass: before any camera sample, trace the pass's N_L light subpaths
// (PixelSampleIntegrator::lightPaths: one per pixel, or --light-paths), store them, and index
// their vertices for merging (docs/design.md §1.1). It also makes the pass's constants
// (paths/pass_constants.h): N_L, the merge radius of the pass's index, and η.
//
// Light path i of pass p draws from its own stream (seed, light-path domain, p · N_L + i; the
// Sobol sampler's stream i at point p), and the
// paths are traced in the store's fixed chunks, one task per chunk, so the store -- and every
// image made from it -- is the same for any number of threads.
#pragma once
#include <memory>
#include <optional>
#include <vector>

#include "integrators/pixel_sample_integrator.h"

namespace tripath {

// What a pass's light subpaths hold, per light path on average: their vertices (all stored), the
// BSDF parameters kept beside them (where the scene's textures or vertex colours vary them), the
// mergeable vertices (indexed for the merge search when the integrator merges) and those that may
// splat into the image (t = 1, when the integrator joins light vertices to the sensor).
struct LightPathSurvey {
    double vertices = 0, bsdfs = 0, mergeable = 0, splats = 0;
};

// The numbers of light path j of pass `index`, a pass tracing `paths` of them: the light phase,
// its survey and auto's survey of a pass's work all start a light path here. Under Sobol points
// light path j is a sequence over the passes, as pixel j's camera samples are: the light path a
// pixel's camera samples connect to is stratified over the passes with them. (Every pass's light
// paths as one sequence, point pass · N_L + j, would stratify a pass's among themselves: it
// measured less gain for bdpt and vcm, and heavy-tailed errors between runs, which share one
// scramble for all their light paths; docs/performance-notes.md, "The sampler".)
SampleStream lightPathStream(const StreamSource& source, uint64_t index, uint64_t paths, uint64_t j);

class LightPhase {
public:
    // The averages of LightPathSurvey over up to kSurveyPaths of pass `index`'s light paths, spread
    // evenly over them and traced exactly as run() traces them (its streams): what a pass will
    // store, known before the store is allocated. Zero without a light phase.
    static constexpr int kSurveyPaths = 4096;
    static LightPathSurvey survey(const Scene& scene, const PixelSampleIntegrator& integrator, uint64_t index,
                                  const StreamSource& source);
    // The memory a pass of `paths` light paths of these averages takes at its peak, while the
    // merge search is built (pixel_sample_integrator.h's Pass: the store, the chunks' mergeable
    // lists and the grid with its temporaries, when `merges`).
    static uint64_t bytes(double paths, const LightPathSurvey& survey, bool merges);

    // Traces pass `index` for `integrator` (nothing if it has no light phase), in parallel in the
    // calling thread's TBB arena, and returns what the pass's camera samples share. The Pass
    // points into this object: it stays valid until the next run. One LightPhase serves one
    // render (one scene and integrator): the first pass's radius is found once and kept.
    Pass run(const Scene& scene, const PixelSampleIntegrator& integrator, uint64_t index, const StreamSource& source);

    const LightStore& store() const { return store_; }

private:
    LightStore store_;
    std::vector<std::vector<LightVertexSearch::Entry>> mergeable_;  // per chunk of the store, when merging
    std::optional<LightVertexSearch> search_;
    std::optional<float> firstRadius_;
};

}  // namespace tripath
