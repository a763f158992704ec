// The passes of the methods of pixel samples and what they share with auto's (tile_passes.h).
#include "integrators/tile_passes.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <tuple>

#include "core/stats.h"
#include "integrators/plan_moments.h"
#include "paths/sample_dimensions.h"

namespace tripath {

namespace {
constexpr Counter kSplats{Event::Splats};
}  // namespace

// A t = 1 contribution, kept for the pixel it lands in.
struct Splat {
    int pixel;
    Strategy strategy;
    Spectrum weighted, unweighted;
};

// What one tile produced in one pass, beyond what it wrote to its own pixels: with moments, each
// splat's technique sums too, in the splats' order.
struct TileOutput {
    std::vector<Splat> splats;
    std::vector<TechniqueSums> splatTechniques;
    uint64_t dropped = 0;
    std::vector<DroppedSample> droppedLog;  // the tile's first kDroppedLogSize in this pass
    uint64_t guardedWeights = 0;
};

namespace {

// Camera contributions go straight to the sample's pixel (owned by this tile for the pass), and
// to the moments when the pass measures; splats are kept in order and merged after the pass,
// tile by tile, so floating-point sums are added in the same order whatever the thread count.
// With plans per tile, each contribution is weighed by the classes of the plan of the tile it
// lands in, from its technique sums, unless the pass measures none (it splats nowhere, and its
// own weights are those).
class TileSink final : public ContributionSink {
public:
    TileSink(Film& film, PlanMoments* moments, std::span<const PassPlan> plans, bool byClass, const Camera& camera,
             double lightPaths, TileOutput& out, uint64_t pass)
        : film_(film), moments_(moments), plans_(plans), byClass_(byClass), camera_(camera), out_(out),
          lightPaths_(lightPaths), splatShare_(static_cast<float>(1.0 / lightPaths)), pass_(pass) {}
    void setPixel(int pixel) { pixel_ = pixel; }
    // The tile is done: the last sample's cross terms go to the moments.
    void finish() {
        if (moments_) moments_->endSample(sample_);
    }
    void add(Strategy st, const Connection& c) override {
        const bool splat = !st.merge && st.t == 1;
        const int pixel = splat ? landing(*c.raster) : pixel_;
        const MisWeight weight = !byClass_ ? MisWeight{c.weight, c.weightGuarded}
                                           : classWeight(plans_[tileOf(pixel)].factors(lightPaths_),
                                                         techniqueClass(st.s, st.t, st.merge), c.techniques);
        if (weight.guarded) ++out_.guardedWeights;
        const Spectrum w = c.unweighted * weight.value;
        if (!isFinite(w) || !isFinite(c.unweighted)) {
            ++out_.dropped;
            if (out_.droppedLog.size() < kDroppedLogSize) out_.droppedLog.push_back({pass_, pixel_});
            return;
        }
        if (splat) {
            out_.splats.push_back({pixel, st, w * splatShare_, c.unweighted * splatShare_});
            if (moments_) out_.splatTechniques.push_back(c.techniques);
        } else {
            film_.add(pixel, st, w, c.unweighted);
            if (moments_) moments_->add(sample_, pixel, w, c.unweighted, c.techniques, techniqueClass(st.s, st.t, st.merge));
        }
    }

private:
    int landing(Vec2 raster) const {
        const int x = std::min(static_cast<int>(raster.x), camera_.width() - 1);
        const int y = std::min(static_cast<int>(raster.y), camera_.height() - 1);
        return y * camera_.width() + x;
    }
    int tileOf(int pixel) const {
        const int tilesX = (camera_.width() + kTileSize - 1) / kTileSize;
        return (pixel / camera_.width() / kTileSize) * tilesX + (pixel % camera_.width()) / kTileSize;
    }
    Film& film_;
    PlanMoments* moments_;
    std::span<const PassPlan> plans_;
    const bool byClass_;  // weighs each contribution by its landing tile's classes, from its technique sums
    const Camera& camera_;
    TileOutput& out_;
    const double lightPaths_;
    const float splatShare_;  // each splat is one of the pass's N_L estimates of every pixel it lands in
    const uint64_t pass_;
    int pixel_ = 0;
    PlanMoments::Sample sample_;  // the current camera sample's sums, when measuring
};

}  // namespace

SampleStream sampleStream(const StreamSource& source, uint64_t pass, const Camera& cam, int pixel) {
    const uint64_t pixels = uint64_t(cam.width()) * cam.height();
    return SampleStream(source.sampler, source.sobolSeed(), source.domain, uint64_t(pixel), pass,
                        Rng(source.seed, static_cast<uint64_t>(source.domain), pass * pixels + uint64_t(pixel)));
}
Vec2 jitteredRaster(SampleStream& rng, int pixel, int width) {
    rng.dimensions(dimensions::kPixel);
    const float jx = rng.uniform(), jy = rng.uniform();
    return {pixel % width + jx, pixel / width + jy};
}

namespace {

// The pass as tile `tile` of plan `plan` runs it: its own classes, and the joins to the sensor of
// the light paths its samples splat whenever the pass splats (they land anywhere).
Pass tilePass(const Pass& pass, const PixelSampleIntegrator& integrator, const PassPlan& plan) {
    Pass p = pass;
    PassPlan runs = plan;
    runs.lightTraces = integrator.strategies().enabled(1, 1);
    p.mis.strategies = runs.strategies();
    if (!plan.merges) p.search = nullptr;
    return p;
}

void renderTile(const Scene& scene, const PixelSampleIntegrator& integrator, const Pass& wholePass, Film& film,
                PlanMoments* moments, std::span<const PassPlan> plans, int tile, const StreamSource& source,
                TileOutput& out) {
    const Camera& cam = scene.camera();
    const int tilesX = (cam.width() + kTileSize - 1) / kTileSize;
    const int x0 = (tile % tilesX) * kTileSize, y0 = (tile / tilesX) * kTileSize;
    thread_local PathBuffers paths;
    const Pass pass = plans.empty() ? wholePass : tilePass(wholePass, integrator, plans[size_t(tile)]);
    TileSink sink(film, moments, plans, !plans.empty() && pass.mis.measure.on, cam, pass.mis.constants.lightPaths, out,
                  pass.index);
    enrolThread();
    const PhaseScope scope(Phase::CameraSamples);
    const bool packets = pass.mis.strategies.walksCamera();
    // Runs of up to 8 pixels of a row: their camera rays are traced together (Scene::intersect8),
    // then each sample goes on with its own stream. The runs depend on the tile alone.
    constexpr int kRun = 8;
    std::array<std::optional<SampleStream>, kRun> rngs;
    std::array<Vec2, kRun> rasters;
    std::array<Vec3, kRun> dirs;
    std::array<std::optional<SurfacePoint>, kRun> hits;
    const int xEnd = std::min(x0 + kTileSize, cam.width());
    for (int y = y0; y < std::min(y0 + kTileSize, cam.height()); ++y)
        for (int xRun = x0; xRun < xEnd; xRun += kRun) {
            const int n = std::min(kRun, xEnd - xRun);
            for (int i = 0; i < n; ++i) {
                const int pixel = y * cam.width() + xRun + i;
                SampleStream& rng = rngs[i].emplace(sampleStream(source, pass.index, cam, pixel));
                rasters[i] = jitteredRaster(rng, pixel, cam.width());
                dirs[i] = cam.direction(rasters[i]);
            }
            if (packets) scene.intersect8(cam.position(), std::span(dirs.data(), n), std::span(hits.data(), n));
            for (int i = 0; i < n; ++i) {
                const int pixel = y * cam.width() + xRun + i;
                sink.setPixel(pixel);
                const CameraRay ray = packets ? CameraRay(rasters[i], dirs[i], &hits[i]) : CameraRay(rasters[i]);
                integrator.sample(scene, pass, pixel, ray, *rngs[i], paths, sink);
            }
        }
    sink.finish();
}

}  // namespace

PassRenderer::PassRenderer(const Scene& scene, const RenderSettings& settings)
    : scene_(scene), streams_(settings.streams()),
      arena_(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic) {
    const Camera& cam = scene.camera();
    tiles_ = ((cam.width() + kTileSize - 1) / kTileSize) * ((cam.height() + kTileSize - 1) / kTileSize);
    outputs_.resize(tiles_);
}

PassRenderer::~PassRenderer() = default;

void PassRenderer::run(const PixelSampleIntegrator& method, uint64_t passIndex, RenderResult& result, PlanMoments* moments,
                       std::span<const PassPlan> tilePlans) {
    arena_.execute([&] {
        const Pass pass = lightPhase_.run(scene_, method, passIndex, streams_);
        tbb::parallel_for(tbb::blocked_range<int>(0, tiles_, 1), [&](const tbb::blocked_range<int>& r) {
            for (int tile = r.begin(); tile < r.end(); ++tile)
                renderTile(scene_, method, pass, result.film, moments, tilePlans, tile, streams_, outputs_[tile]);
        });
    });
    const PhaseScope filing(Phase::Film);
    for (TileOutput& out : outputs_) {
        kSplats.add(out.splats.size());
        for (size_t i = 0; i < out.splats.size(); ++i) {
            const Splat& sp = out.splats[i];
            result.film.add(sp.pixel, sp.strategy, sp.weighted, sp.unweighted);
            if (moments) moments->addSplat(sp.pixel, sp.weighted, sp.unweighted, out.splatTechniques[i]);
        }
        out.splats.clear();
        out.splatTechniques.clear();
        result.droppedSamples += out.dropped;
        result.guardedWeights += out.guardedWeights;
        for (const DroppedSample& d : out.droppedLog)
            if (result.droppedLog.size() < kDroppedLogSize) result.droppedLog.push_back(d);
        out.droppedLog.clear();
        out.dropped = out.guardedWeights = 0;
    }
}

void PassRenderer::endBlock(Film& film) {
    const PhaseScope filing(Phase::Film);
    arena_.execute([&] { film.endBlock(); });
}

uint64_t pendingSplatBytes(double splats) { return static_cast<uint64_t>(std::ceil(splats)) * sizeof(Splat); }

namespace {

// The order one process logs dropped samples in: by pass, then tile (PassRenderer::run collects
// the tiles' logs in tile order), then pixel (renderTile walks a tile's rows in order); a sample
// that dropped twice is logged twice, and a stable sort keeps such twins together.
struct DroppedOrder {
    int width;
    std::tuple<uint64_t, int, int> key(const DroppedSample& d) const {
        const int tilesX = (width + kTileSize - 1) / kTileSize, x = d.pixel % width, y = d.pixel / width;
        return {d.pass, (y / kTileSize) * tilesX + x / kTileSize, d.pixel};
    }
    bool operator()(const DroppedSample& a, const DroppedSample& b) const { return key(a) < key(b); }
};

// Makes every rank's log the team's first kDroppedLogSize dropped samples, the log one process
// would have kept. A rank's log holds the first of its own passes, so the team's first are among
// their union. Each rank writes its log into its own slot of a zeroed array (count, then pass and
// pixel per entry) and the team's sum gathers them all.
void gatherDroppedLog(Team& team, const Camera& cam, std::vector<DroppedSample>& log) {
    constexpr size_t kSlot = 1 + 2 * kDroppedLogSize;
    std::vector<uint64_t> slots(kSlot * size_t(team.size()), 0);
    uint64_t* mine = slots.data() + kSlot * size_t(team.rank());
    mine[0] = log.size();
    for (size_t i = 0; i < log.size(); ++i) {
        mine[1 + 2 * i] = log[i].pass;
        mine[2 + 2 * i] = uint64_t(log[i].pixel);
    }
    team.sum(slots);
    log.clear();
    for (int r = 0; r < team.size(); ++r) {
        const uint64_t* slot = slots.data() + kSlot * size_t(r);
        for (uint64_t i = 0; i < slot[0]; ++i) log.push_back({slot[1 + 2 * i], static_cast<int>(slot[2 + 2 * i])});
    }
    std::stable_sort(log.begin(), log.end(), DroppedOrder{cam.width()});
    if (log.size() > kDroppedLogSize) log.resize(kDroppedLogSize);
}

}  // namespace

TilePasses::TilePasses(const Scene& scene, const PixelSampleIntegrator& method, const RenderSettings& settings,
                       uint64_t firstPass)
    : renderer_(scene, settings), method_(method), camera_(scene.camera()), team_(settings.team ? *settings.team : solo()),
      firstPass_(firstPass) {}

std::pair<uint64_t, uint64_t> TilePasses::round(uint64_t round, uint64_t budget) const {
    const uint64_t begin = (round * ranks() + uint64_t(team_.rank())) * kPassesPerBlock;
    return {std::min(budget, begin), std::min(budget, begin + kPassesPerBlock)};
}

bool TilePasses::budgetDone(uint64_t round, uint64_t budget) const { return (round + 1) * ranks() * kPassesPerBlock >= budget; }

void TilePasses::run(uint64_t offset, RenderResult& result) { renderer_.run(method_, firstPass_ + offset, result); }

void TilePasses::endRound(Film& film) { renderer_.endBlock(film); }

void TilePasses::gather(RenderResult& into, Film& mine, uint64_t local, uint64_t localNext, const RenderResult& counts) {
    std::array<uint64_t, 3> sums{local, counts.droppedSamples, counts.guardedWeights};
    team_.sum(sums);
    std::array<uint64_t, 1> next{firstPass_ + localNext};
    team_.max(next);
    std::vector<DroppedSample> log = counts.droppedLog;
    gatherDroppedLog(team_, camera_, log);
    into.passes = static_cast<int>(sums[0]);
    into.droppedSamples = sums[1];
    into.guardedWeights = sums[2];
    into.nextPass = next[0];
    into.droppedLog = std::move(log);
    team_.reduce(team_.rank() == 0 ? into.film : mine);
}

}  // namespace tripath
