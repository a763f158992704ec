// The passes of the methods of pixel samples (pixel_sample_integrator.h). A pass is its light
// phase (light_phase.h), then every pixel's camera sample in 16×16 tiles on threads, then the
// splats in tile order, so that the film's sums are added in one order whatever the thread
// count. The passes come in canonical blocks of kPassesPerBlock, dealt to a team's ranks in
// rounds (render.h). auto (auto.cpp) renders the same passes, each with its own plan, and
// measures its candidates in them (plan_moments.h).
#pragma once
#include <tbb/task_arena.h>

#include <vector>

#include "integrators/light_phase.h"
#include "integrators/pass_plan.h"
#include "integrators/render_loop.h"

namespace tripath {

class PlanMoments;

inline constexpr int kTileSize = 16;

// The stream of camera sample (pass, pixel), and its raster position: the draws of the sample's
// first set of dimensions jitter it within the pixel. The passes and replaySample() both start a
// sample here.
SampleStream sampleStream(const StreamSource& source, uint64_t pass, const Camera& cam, int pixel);
Vec2 jitteredRaster(SampleStream& rng, int pixel, int width);

struct TileOutput;

// Renders passes one at a time into a render's result, in the threads of the settings' arena.
class PassRenderer {
public:
    PassRenderer(const Scene& scene, const RenderSettings& settings);
    ~PassRenderer();
    // Pass `passIndex` of `method`; each contribution also goes to `moments` when given. A method
    // that weighs by class (auto's passes, pass_plan.h) is given a plan per tile, all of its N_L:
    // each tile runs its plan's classes, and each contribution is weighed by the classes of the
    // plan of the tile it lands in. One PassRenderer serves one render: every method it is given
    // shares the first pass's radius.
    void run(const PixelSampleIntegrator& method, uint64_t passIndex, RenderResult& result, PlanMoments* moments = nullptr,
             std::span<const PassPlan> tilePlans = {});
    // Adds the block's sums to the film's exact totals.
    void endBlock(Film& film);
    // The passes from here on draw Sobol points of scramble `scramble` (StreamSource).
    void setScramble(uint64_t scramble) { streams_.scramble = scramble; }

private:
    const Scene& scene_;
    StreamSource streams_;
    tbb::task_arena arena_;
    LightPhase lightPhase_;
    int tiles_ = 0;
    std::vector<TileOutput> outputs_;
};

// The fixed methods' passes: canonical blocks of kPassesPerBlock, dealt to the ranks in rounds,
// rank r rendering block j·N + r in round j (render.h).
class TilePasses : public PassSource {
public:
    TilePasses(const Scene& scene, const PixelSampleIntegrator& method, const RenderSettings& settings, uint64_t firstPass);
    std::pair<uint64_t, uint64_t> round(uint64_t round, uint64_t budget) const override;
    bool budgetDone(uint64_t round, uint64_t budget) const override;
    bool stopsAlone() const override { return true; }
    void run(uint64_t offset, RenderResult& result) override;
    void endRound(Film& film) override;
    int passesDone(uint64_t local) const override { return static_cast<int>(local * ranks()); }
    void gather(RenderResult& into, Film& mine, uint64_t local, uint64_t localNext, const RenderResult& counts) override;

protected:
    uint64_t ranks() const { return uint64_t(team_.size()); }
    PassRenderer renderer_;
    const PixelSampleIntegrator& method_;
    const Camera& camera_;
    Team& team_;
    const uint64_t firstPass_;
};

}  // namespace tripath
