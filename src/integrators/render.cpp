#include "integrators/render.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <tuple>

#include "core/stats.h"
#include "integrators/light_phase.h"
#include "integrators/render_loop.h"

namespace tripath {

namespace {

constexpr int kTileSize = 16;
constexpr Counter kSplats{Event::Splats};

struct Splat {
    int pixel;
    Strategy strategy;
    Spectrum weighted, unweighted;
};

// What one tile produced in one pass, beyond what it wrote to its own pixels.
struct TileOutput {
    std::vector<Splat> splats;
    uint64_t dropped = 0;
    std::vector<DroppedSample> droppedLog;  // the tile's first kDroppedLogSize in this pass
    uint64_t guardedWeights = 0;
};

// Camera contributions go straight to the sample's pixel (owned by this tile for the pass);
// splats are kept in order and merged after the pass, tile by tile, so floating-point sums are
// added in the same order whatever the thread count.
class TileSink final : public ContributionSink {
public:
    TileSink(Film& film, const Camera& camera, double lightPaths, TileOutput& out, uint64_t pass)
        : film_(film), camera_(camera), out_(out), splatShare_(static_cast<float>(1.0 / lightPaths)),
          pass_(pass) {}
    void setPixel(int pixel) { pixel_ = pixel; }
    void add(Strategy st, const Connection& c) override {
        if (c.weightGuarded) ++out_.guardedWeights;
        const Spectrum w = c.weighted();
        if (!isFinite(w) || !isFinite(c.unweighted)) {
            ++out_.dropped;
            if (out_.droppedLog.size() < kDroppedLogSize) out_.droppedLog.push_back({pass_, pixel_});
            return;
        }
        if (!st.merge && st.t == 1) {
            const int x = std::min(static_cast<int>(c.raster->x), camera_.width() - 1);
            const int y = std::min(static_cast<int>(c.raster->y), camera_.height() - 1);
            out_.splats.push_back({y * camera_.width() + x, st, w * splatShare_, c.unweighted * splatShare_});
        } else {
            film_.add(pixel_, st, w, c.unweighted);
        }
    }

private:
    Film& film_;
    const Camera& camera_;
    TileOutput& out_;
    const float splatShare_;  // each splat is one of the pass's N_L estimates of every pixel it lands in
    const uint64_t pass_;
    int pixel_ = 0;
};

// The random stream of camera sample (pass, pixel), and its raster position: the stream's first
// two draws jitter it within the pixel. render() and replaySample() both start a sample here.
Rng sampleStream(uint64_t seed, StreamDomain domain, uint64_t pass, const Camera& cam, int pixel) {
    const uint64_t pixels = uint64_t(cam.width()) * cam.height();
    return Rng(seed, static_cast<uint64_t>(domain), pass * pixels + uint64_t(pixel));
}
Vec2 jitteredRaster(Rng& rng, int pixel, int width) {
    const float jx = rng.uniform(), jy = rng.uniform();
    return {pixel % width + jx, pixel / width + jy};
}

void renderTile(const Scene& scene, const PixelSampleIntegrator& integrator, const Pass& pass, Film& film, int tile,
                uint64_t seed, StreamDomain domain, TileOutput& out) {
    const Camera& cam = scene.camera();
    const int tilesX = (cam.width() + kTileSize - 1) / kTileSize;
    const int x0 = (tile % tilesX) * kTileSize, y0 = (tile / tilesX) * kTileSize;
    thread_local PathBuffers paths;
    TileSink sink(film, cam, pass.mis.constants.lightPaths, out, pass.index);
    enrolThread();
    const PhaseScope scope(Phase::CameraSamples);
    const bool packets = integrator.tracesCameraRays();
    // Runs of up to 8 pixels of a row: their camera rays are traced together (Scene::intersect8),
    // then each sample goes on with its own stream. The runs depend on the tile alone.
    constexpr int kRun = 8;
    std::array<std::optional<Rng>, kRun> rngs;
    std::array<Vec2, kRun> rasters;
    std::array<Vec3, kRun> dirs;
    std::array<std::optional<SurfacePoint>, kRun> hits;
    const int xEnd = std::min(x0 + kTileSize, cam.width());
    for (int y = y0; y < std::min(y0 + kTileSize, cam.height()); ++y)
        for (int xRun = x0; xRun < xEnd; xRun += kRun) {
            const int n = std::min(kRun, xEnd - xRun);
            for (int i = 0; i < n; ++i) {
                const int pixel = y * cam.width() + xRun + i;
                Rng& rng = rngs[i].emplace(sampleStream(seed, domain, pass.index, cam, pixel));
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
}

// One pass: the light phase, the tiles in parallel, then the splats in tile order.
class PassRenderer {
public:
    PassRenderer(const Scene& scene, const PixelSampleIntegrator& integrator, const RenderSettings& settings)
        : scene_(scene), integrator_(integrator), settings_(settings),
          arena_(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic) {
        const Camera& cam = scene.camera();
        tiles_ = ((cam.width() + kTileSize - 1) / kTileSize) * ((cam.height() + kTileSize - 1) / kTileSize);
        outputs_.resize(tiles_);
    }

    void run(uint64_t passIndex, RenderResult& result) {
        arena_.execute([&] {
            const Pass pass = lightPhase_.run(scene_, integrator_, passIndex, settings_.seed, settings_.domain);
            tbb::parallel_for(tbb::blocked_range<int>(0, tiles_, 1), [&](const tbb::blocked_range<int>& r) {
                for (int tile = r.begin(); tile < r.end(); ++tile)
                    renderTile(scene_, integrator_, pass, result.film, tile, settings_.seed, settings_.domain, outputs_[tile]);
            });
        });
        const PhaseScope filing(Phase::Film);
        for (TileOutput& out : outputs_) {
            kSplats.add(out.splats.size());
            for (const Splat& sp : out.splats) result.film.add(sp.pixel, sp.strategy, sp.weighted, sp.unweighted);
            out.splats.clear();
            result.droppedSamples += out.dropped;
            result.guardedWeights += out.guardedWeights;
            for (const DroppedSample& d : out.droppedLog)
                if (result.droppedLog.size() < kDroppedLogSize) result.droppedLog.push_back(d);
            out.droppedLog.clear();
            out.dropped = out.guardedWeights = 0;
        }
    }

    void endBlock(Film& film) {
        const PhaseScope filing(Phase::Film);
        arena_.execute([&] { film.endBlock(); });
    }

private:
    const Scene& scene_;
    const PixelSampleIntegrator& integrator_;
    const RenderSettings& settings_;
    tbb::task_arena arena_;
    LightPhase lightPhase_;
    int tiles_ = 0;
    std::vector<TileOutput> outputs_;
};

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

// The fixed methods' passes: canonical blocks of kPassesPerBlock, dealt to the ranks in rounds,
// rank r rendering block j·N + r in round j (render.h).
class TilePasses final : public PassSource {
public:
    TilePasses(const Scene& scene, const PixelSampleIntegrator& integrator, const RenderSettings& settings,
               uint64_t firstPass)
        : renderer_(scene, integrator, settings), camera_(scene.camera()), team_(settings.team ? *settings.team : solo()),
          firstPass_(firstPass) {}
    std::pair<uint64_t, uint64_t> round(uint64_t round, uint64_t budget) const override {
        const uint64_t begin = (round * ranks() + uint64_t(team_.rank())) * kPassesPerBlock;
        return {std::min(budget, begin), std::min(budget, begin + kPassesPerBlock)};
    }
    bool budgetDone(uint64_t round, uint64_t budget) const override { return (round + 1) * ranks() * kPassesPerBlock >= budget; }
    bool stopsAlone() const override { return true; }
    void run(uint64_t offset, RenderResult& result) override { renderer_.run(firstPass_ + offset, result); }
    void endRound(Film& film) override { renderer_.endBlock(film); }
    int passesDone(uint64_t local) const override { return static_cast<int>(local * ranks()); }
    void gather(RenderResult& into, Film& mine, uint64_t local, uint64_t localNext, const RenderResult& counts) override {
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

private:
    uint64_t ranks() const { return uint64_t(team_.size()); }
    PassRenderer renderer_;
    const Camera& camera_;
    Team& team_;
    const uint64_t firstPass_;
};

}  // namespace

RenderResult& addResumed(RenderResult& r, const RenderResult* resume) {
    if (!resume) return r;
    r.film.add(resume->film);
    r.passes += resume->passes;
    r.seconds += resume->seconds;
    if (r.budgetPasses > 0) r.budgetPasses += resume->passes;
    if (r.budgetSeconds > 0) r.budgetSeconds += resume->seconds;
    r.droppedSamples += resume->droppedSamples;
    r.guardedWeights += resume->guardedWeights;
    return r;
}

MemoryEstimate admitMemory(const Scene& scene, const Integrator& integrator, const RenderSettings& settings) {
    MemoryEstimate estimate = estimateMemory(scene, integrator, settings);
    if (settings.checkMemory)
        together(settings.team ? *settings.team : solo(), [&] { settings.checkMemory(estimate); });
    return estimate;
}

uint64_t pendingSplatBytes(double splats) { return static_cast<uint64_t>(std::ceil(splats)) * sizeof(Splat); }

RenderResult PixelSampleIntegrator::render(const Scene& scene, const RenderSettings& settings) const {
    const Camera& cam = scene.camera();
    FilmLayers layers = settings.layers;
    layers.strategies = strategies();
    MemoryEstimate memory = admitMemory(scene, *this, settings);
    RenderResult result{.film = Film(cam.width(), cam.height(), layers),
                        .budgetPasses = settings.spp,
                        .budgetSeconds = settings.seconds,
                        .memory = std::move(memory)};
    TilePasses passes(scene, *this, settings, settings.resume ? settings.resume->nextPass : settings.firstPass);
    return runPasses(settings, passes, std::move(result));
}

RenderResult render(const Scene& scene, const Integrator& integrator, const RenderSettings& settings) {
    return integrator.render(scene, settings);
}

std::string interruptionText(const RenderResult& r) {
    if (r.budgetSeconds > 0) return fmt::format("after {} passes, {:.2f} s of {:g} s", r.passes, r.seconds, r.budgetSeconds);
    return fmt::format("after {} of {} passes, {:.2f} s", r.passes, r.budgetPasses, r.seconds);
}

void replaySample(const Scene& scene, const PixelSampleIntegrator& integrator, const RenderSettings& settings, uint64_t pass,
                  int pixel, ContributionSink& sink) {
    const Camera& cam = scene.camera();
    LightPhase lightPhase;
    tbb::task_arena arena(settings.threads > 0 ? settings.threads : tbb::task_arena::automatic);
    arena.execute([&] {
        const Pass p = lightPhase.run(scene, integrator, pass, settings.seed, settings.domain);
        PathBuffers paths;
        Rng rng = sampleStream(settings.seed, settings.domain, pass, cam, pixel);
        const Vec2 raster = jitteredRaster(rng, pixel, cam.width());
        integrator.sample(scene, p, pixel, CameraRay(raster), rng, paths, sink);
    });
}

}  // namespace tripath
