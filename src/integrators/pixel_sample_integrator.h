// The methods that render passes of camera samples: pt, lt, bdpt, vcm, bpm and ppm (pbrt-v4's
// image-tile integrators, as against its MLT integrator). In each pass every pixel takes one
// sample, by sample(), after the pass's light phase when the method has one (light_phase.h);
// what a method estimates is then its strategy set and its settings. Their render() is one for
// all (render.cpp): passes in tiles, dealt over a team in canonical blocks (tile_passes.h). A pixel's sample can
// be rendered again alone (replaySample, render.h).
#pragma once
#include "core/sample_stream.h"
#include "integrators/integrator.h"

namespace tripath {

// Per-thread scratch subpaths, reused from sample to sample.
struct PathBuffers {
    Subpath light, camera;
};

// What every camera sample of one pass shares: the pass's stored light subpaths (its light
// phase, integrators/light_phase.h), the range search over them, and the MIS context with the
// pass's constants (N_L, merge radius and η: pass_constants.h). Read-only while the camera
// samples run.
struct Pass {
    uint64_t index = 0;                         // 0-based, over the whole render
    const LightStore* light = nullptr;          // set when the integrator has a light phase
    const LightVertexSearch* search = nullptr;  // set when it merges
    MisContext mis;
};

// Receives the contributions of one camera sample: the strategy and its result; t = 1
// connections carry the raster position to splat at, the others belong to the sample's own pixel.
class ContributionSink {
public:
    virtual ~ContributionSink() = default;
    virtual void add(Strategy strategy, const Connection& c) = 0;
};

class PixelSampleIntegrator : public Integrator {
public:
    using Integrator::Integrator;
    // Passes of camera samples in tiles, each sample by sample() (render.cpp, tile_passes.h).
    RenderResult render(const Scene& scene, const RenderSettings& settings) const override;
    const PixelSampleIntegrator* pixelSamples() const final { return this; }
    // The camera and light walks play roulette from WalkSettings::rrDepth.
    bool playsRoulette() const final { return true; }
    // When a strategy needs stored light subpaths: any with s ≥ 2, or a merge.
    bool hasLightPhase() const final { return strategies().merges() || strategies().maxS >= 2; }

    // One sample for pixel `pixel` whose camera ray is `ray` (its raster position already jittered
    // inside the pixel, and its hit found when the render loop traced it in a packet). By default:
    // a camera walk; the splats of the pass's light paths that fall to this pixel's sample
    // (splatLightPaths); every enabled connection with t ≥ 2 with light path number pixel mod N_L
    // (an empty one without a light phase); and every merge with the pass's light vertices if
    // the integrator merges. Where the pass's strategies need no camera walk (StrategySet::
    // walksCamera: lt, and auto's tiles that only trace light), the sensor alone and its splats;
    // the render loop then traces no camera ray for it.
    virtual void sample(const Scene& scene, const Pass& pass, int pixel, const CameraRay& ray, SampleStream& rng, PathBuffers& paths,
                        ContributionSink& sink) const;
    // The strategies it measures, a superset of those it enables (mis.h's TechniqueMeasure): none
    // by default; a measuring pass of auto's measures the whole vcm set whatever its plan
    // (pass_plan.h).
    virtual std::optional<StrategySet> measuredStrategies() const { return std::nullopt; }
    // The strategies whose pdfs its walks record: the measured ones, else the enabled ones.
    StrategySet walkStrategies() const { return measuredStrategies().value_or(strategies()); }

    // N_L, the light paths each pass traces when it has a light phase: the settings' count, or one
    // per pixel. The one place that number is decided; the light phase puts it in the pass's
    // constants (pass_constants.h), which every kernel then reads.
    double lightPaths(const Scene& scene) const;
    // The first pass's merge radius r_1 (0 when the integrator neither merges nor measures merges).
    // It may trace a few hundred rays (the default measures pixels): compute it once per render.
    float firstMergeRadius(const Scene& scene) const;
    // The radius of 0-based pass `index` given r_1: the schedule r_1 · (index + 1)^((α−1)/2).
    float mergeRadius(float firstRadius, uint64_t index) const;
    // The MIS context of a pass with these constants, measuring the measured strategies with the
    // constants' merge factor.
    MisContext misContext(const PassConstants& constants) const;

protected:
    // The sample's camera subpath along `ray`, with the MIS running sums of
    // the pass's context where it keeps them.
    void cameraWalk(const Scene& scene, const Pass& pass, const CameraRay& ray, SampleStream& rng, Subpath& camera) const;
    // Runs every enabled connection with t ≥ firstT over the two subpaths into the sink.
    void connectAll(const Scene& scene, const Pass& pass, const SubpathView& light, const SubpathView& camera, int firstT,
                    SampleStream& rng, ContributionSink& sink) const {
        evaluateStrategies(scene, light, camera, firstT, rng, settings().walk.maxDepth, pass.mis,
                           [&](Strategy st, const Connection& c) { sink.add(st, c); });
    }
    // The t = 1 connections (light tracing's splats) of the pass's light paths j = pixel,
    // pixel + P, pixel + 2P, … below N_L, P being the pixel count: every light path is joined to
    // the sensor `sensor` once per pass, whatever N_L, in the order of the pixels' samples (so the
    // film's sums do not depend on threads). Each draws what it needs from the pixel's stream.
    void splatLightPaths(const Scene& scene, const Pass& pass, int pixel, const SubpathView& sensor, SampleStream& rng,
                         ContributionSink& sink) const;
    // Runs every merge of the camera subpath with the pass's light vertices into the sink.
    void mergeAll(const Scene& scene, const Pass& pass, const Subpath& camera, ContributionSink& sink) const {
        evaluateMerges(scene, *pass.search, camera, settings().walk.maxDepth, pass.mis,
                       [&](Strategy st, const Connection& c) { sink.add(st, c); });
    }
};

}  // namespace tripath
