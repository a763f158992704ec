// The kernels one at a time, single-threaded: BSDFs per material type, the three-point kernels as
// production calls them (ε, ρ, W and g of points, which build the frame and segment and call the
// fast overloads; ρ given its frame; a segment and its g; the area-pdf conversion), the MIS weight against path length,
// and one connect() per strategy (s, t). Inputs are precomputed pools cycled through, so each
// iteration is one call on fresh data and the loop costs a load and an increment.
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <vector>

#include "bench_scenes.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "paths/connect.h"
#include "paths/kernels.h"
#include "paths/mis.h"
#include "paths/walk.h"

namespace tripath::bench {

namespace {

constexpr size_t kPool = 1024;  // a power of two: the cycling index is a mask
constexpr uint64_t kSeed = 7;
constexpr double kLightPaths = double(kWidth) * kHeight;  // N_L: one light path per pixel, as rendered

Rng testRng(uint64_t index) { return Rng(kSeed, static_cast<uint64_t>(StreamDomain::Test), index); }

// Runs f(i) once per iteration with i cycling over [0, n), n a power of two.
template <class F>
void cycle(benchmark::State& state, size_t n, F&& f) {
    size_t i = 0;
    for (auto _ : state) {
        f(i);
        i = (i + 1) & (n - 1);
    }
    state.SetItemsProcessed(state.iterations());
}

// ---- BSDFs ----------------------------------------------------------------------------------

Material materialOf(MaterialType type) {
    Material m;
    m.name = materialTypeName(type);
    m.type = type;
    m.albedo = Spectrum(0.8f);
    m.roughness = 0.3f;
    m.ior = 1.5f;
    return m;
}

// Directions in the local shading frame, both cosine-distributed on the upper side (the common
// case for reflection: wo where the walk came from, wi where a connection goes).
struct BsdfInputs {
    std::vector<Vec3> wo, wi;
    std::vector<Vec2> u;
    std::vector<float> uc;
    BsdfInputs() {
        Rng rng = testRng(1);
        for (size_t i = 0; i < kPool; ++i) {
            const float a = rng.uniform(), b = rng.uniform(), c = rng.uniform(), d = rng.uniform();
            wo.push_back(sampleCosineHemisphere({a, b}));
            wi.push_back(sampleCosineHemisphere({c, d}));
            const float e = rng.uniform(), f = rng.uniform();
            u.push_back({e, f});
            uc.push_back(rng.uniform());
        }
    }
};
const BsdfInputs& bsdfInputs() {
    static const BsdfInputs inputs;
    return inputs;
}

enum class BsdfOp { Eval, Sample, Pdf };

void runBsdf(benchmark::State& state, MaterialType type, BsdfOp op) {
    const Material m = materialOf(type);
    const BsdfInputs& in = bsdfInputs();
    // One call first, outside the timing: the plastic's coat-albedo table is built on first use.
    benchmark::DoNotOptimize(sampleBsdf(m, in.wo[0], in.u[0], in.uc[0], TransportMode::Radiance));
    switch (op) {
        case BsdfOp::Eval:
            cycle(state, kPool, [&](size_t i) {
                Spectrum f = evalBsdf(m, in.wo[i], in.wi[i], TransportMode::Radiance);
                benchmark::DoNotOptimize(f);
            });
            break;
        case BsdfOp::Sample:
            cycle(state, kPool, [&](size_t i) {
                auto s = sampleBsdf(m, in.wo[i], in.u[i], in.uc[i], TransportMode::Radiance);
                benchmark::DoNotOptimize(s);
            });
            break;
        case BsdfOp::Pdf:
            cycle(state, kPool, [&](size_t i) {
                float p = pdfBsdf(m, in.wo[i], in.wi[i]);
                benchmark::DoNotOptimize(p);
            });
            break;
    }
}

// ---- vertices from real subpaths on cornell ----------------------------------------------------

struct VertexPools {
    std::vector<std::pair<Vertex, Vertex>> emitterEdges;  // (y0, y1) of light subpaths: ε
    std::vector<std::pair<Vertex, Vertex>> sensorEdges;   // (z1, z0) of camera subpaths: W
    std::vector<std::array<Vertex, 3>> triples;           // (x″, x′, x) along camera subpaths: ρ
    std::vector<std::pair<Vertex, Vertex>> surfacePairs;  // two surface vertices of different paths: G, g
};

const VertexPools& vertexPools() {
    static const VertexPools pools = [] {
        const Scene& scene = cachedScene("cornell");
        VertexPools p;
        std::vector<Vertex> surfaces;
        WalkSettings walk;
        walk.maxDepth = 8;
        Subpath cam, light;
        for (uint64_t i = 0; p.triples.size() < kPool || p.emitterEdges.size() < kPool || surfaces.size() < 2 * kPool; ++i) {
            Rng rng = testRng(1000 + i);
            const float x = rng.uniform() * kWidth, y = rng.uniform() * kHeight;
            cameraSubpath(scene, Vec2{x, y}, rng, walk, WalkPdfs::All, kLightPaths, cam);
            lightSubpath(scene, rng, walk, WalkPdfs::All, light);
            if (cam.size() >= 2 && p.sensorEdges.size() < kPool) p.sensorEdges.push_back({cam[1], cam[0]});
            if (light.size() >= 2 && p.emitterEdges.size() < kPool) p.emitterEdges.push_back({light[0], light[1]});
            for (size_t j = 1; j + 1 < cam.size() && p.triples.size() < kPool; ++j)
                p.triples.push_back({cam[j + 1], cam[j], cam[j - 1]});  // light flows from the far end
            for (size_t j = 1; j < cam.size(); ++j) surfaces.push_back(cam[j]);
            for (size_t j = 1; j < light.size(); ++j) surfaces.push_back(light[j]);
        }
        // Pair vertex i with one far down the list: different paths, so visibility is a mixture.
        for (size_t i = 0; i < kPool; ++i) p.surfacePairs.push_back({surfaces[i], surfaces[(i * 7 + 5 * kPool / 3) % surfaces.size()]});
        return p;
    }();
    return pools;
}

void registerPathKernels() {
    auto reg = [](const char* name, auto body) {
        benchmark::RegisterBenchmark(name, [body](benchmark::State& st) {
            const Scene& scene = cachedScene("cornell");
            const VertexPools& p = vertexPools();
            body(st, scene, p);
        });
    };
    reg("kernel/emittance", [](benchmark::State& st, const Scene& scene, const VertexPools& p) {
        cycle(st, kPool, [&](size_t i) {
            Spectrum e = emittance(scene, p.emitterEdges[i].first, p.emitterEdges[i].second);
            benchmark::DoNotOptimize(e);
        });
    });
    reg("kernel/rho", [](benchmark::State& st, const Scene& scene, const VertexPools& p) {
        cycle(st, kPool, [&](size_t i) {
            Spectrum r = rho(scene, p.triples[i][0], p.triples[i][1], p.triples[i][2]);
            benchmark::DoNotOptimize(r);
        });
    });
    reg("kernel/W", [](benchmark::State& st, const Scene& scene, const VertexPools& p) {
        cycle(st, kPool, [&](size_t i) {
            float w = W(scene, p.sensorEdges[i].first, p.sensorEdges[i].second);
            benchmark::DoNotOptimize(w);
        });
    });
    // What every connection builds first: the joining segment (direction, length), and g of it.
    reg("kernel/segment_g", [](benchmark::State& st, const Scene&, const VertexPools& p) {
        cycle(st, kPool, [&](size_t i) {
            const Segment s(p.surfacePairs[i].first, p.surfacePairs[i].second);
            Spectrum v = g(s);
            benchmark::DoNotOptimize(v);
        });
    });
    reg("kernel/g_with_shadow_ray", [](benchmark::State& st, const Scene& scene, const VertexPools& p) {
        uint64_t visible = 0;
        cycle(st, kPool, [&](size_t i) {
            Spectrum v = g(scene, p.surfacePairs[i].first, p.surfacePairs[i].second);
            visible += !isBlack(v);
            benchmark::DoNotOptimize(v);
        });
        st.counters["visible_fraction"] = double(visible) / double(st.iterations());
    });
    // Everything a connection evaluates at one endpoint from the same local geometry: the
    // scatter factor and the pdfs of generating either neighbour (frame and directions once).
    reg("kernel/localScattering", [](benchmark::State& st, const Scene& scene, const VertexPools& p) {
        cycle(st, kPool, [&](size_t i) {
            const auto& [light, v, camera] = p.triples[i];
            const Vec3 l = normalize(light.p - v.p), c = normalize(camera.p - v.p);
            const LocalScattering at(scene, v, v.material, &l, &c);  // cornell: its materials' parameters
            Spectrum f = at.value();
            float pdfs = at.pdfTowardCamera() + at.pdfTowardLight(kLightPaths);
            benchmark::DoNotOptimize(f);
            benchmark::DoNotOptimize(pdfs);
        });
    });
    // The fast overload a connection calls at an endpoint whose frame it has built (the point
    // form above builds the frame and the segment, then calls this).
    reg("kernel/rho_given_frame", [](benchmark::State& st, const Scene& scene, const VertexPools& p) {
        std::vector<Vec3> toLight, toCamera;
        for (const auto& [light, v, camera] : p.triples) {
            toLight.push_back(normalize(light.p - v.p));
            toCamera.push_back(normalize(camera.p - v.p));
        }
        std::vector<LocalScattering> at;
        std::vector<Segment> out;
        for (size_t i = 0; i < kPool; ++i) {
            at.emplace_back(scene, p.triples[i][1], p.triples[i][1].material, &toLight[i], &toCamera[i]);
            out.emplace_back(p.triples[i][1], p.triples[i][2]);
        }
        cycle(st, kPool, [&](size_t i) {
            Spectrum r = rho(at[i], out[i]);
            benchmark::DoNotOptimize(r);
        });
    });
    reg("kernel/toArea", [](benchmark::State& st, const Scene&, const VertexPools& p) {
        std::vector<Segment> s;
        for (const auto& [a, b] : p.surfacePairs) s.emplace_back(a, b);
        cycle(st, kPool, [&](size_t i) {
            float v = s[i].toArea(0.3f, p.surfacePairs[i].second);
            benchmark::DoNotOptimize(v);
        });
    });
}

// ---- MIS weight against path length ------------------------------------------------------------

// A path of k segments split into s light and t = k + 1 − s camera vertices with random pdfs:
// misWeight reads only kinds, delta flags, normals (for a delta light), the two pdfs, the
// junction's four and the roulette's continuation probability of each vertex.

struct SyntheticPath {
    std::vector<Vertex> light, camera;
    Junction junction;
};

SyntheticPath syntheticPath(int s, int t, Rng& rng) {
    auto pdf = [&] { return 0.01f + 10.0f * rng.uniform(); };
    SyntheticPath p;
    for (int i = 0; i < s; ++i) {
        Vertex v;
        v.kind = i == 0 ? Vertex::Kind::Emitter : Vertex::Kind::Surface;
        v.ng = Vec3(0, 1, 0);  // an area emitter, not a point light
        v.continuation = 0.7f;
        v.pdfFwd = pdf();
        v.pdfRev = pdf();
        p.light.push_back(v);
    }
    for (int i = 0; i < t; ++i) {
        Vertex v;
        v.kind = i == 0 ? Vertex::Kind::Sensor : Vertex::Kind::Surface;
        v.ng = Vec3(0, 0, -1);
        v.continuation = 0.7f;
        v.pdfFwd = pdf();
        v.pdfRev = pdf();
        p.camera.push_back(v);
    }
    p.junction.cameraEnd = pdf();
    p.junction.cameraBeforeEnd = pdf();
    p.junction.lightEnd = pdf();
    p.junction.lightBeforeEnd = pdf();
    return p;
}

struct MisSeries {
    MisHeuristic heuristic;
    StrategySet set;
    bool runningSums = false;  // the O(1) form (mis.h): the vertices carry recorded sums
    bool merge = false;        // the weight of a merge of y_{s−1} with z_{t−1} (vcm) instead of a connection
    bool pt = false;           // pt's next-event estimation (s = 1, t = k) instead of the middle split
};

void runMis(benchmark::State& state, int k, MisSeries series) {
    // BDPT and VCM: the middle split, every strategy enabled. PT: next-event estimation (s = 1,
    // t = k), the connection pt makes at every bounce; its loop walks the same k vertices. A merge
    // of s light and t camera vertices has k = s + t − 2.
    const bool pt = series.pt;
    const int s = pt ? 1 : (k + 1) / 2 + (series.merge ? 1 : 0), t = k + (series.merge ? 2 : 1) - s;
    constexpr size_t kPaths = 64;
    std::vector<SyntheticPath> paths;
    Rng rng = testRng(static_cast<uint64_t>(k));
    // Roulette from the 3rd vertex (pt's default; bdpt and vcm render from the 2nd); a merge factor η of 0.5.
    MisContext mis{series.heuristic, series.set, Roulette{}, passConstants(kLightPaths, std::sqrt(0.5f / (kPi * kLightPaths)))};
    mis.runningSums = series.runningSums;
    for (size_t i = 0; i < kPaths; ++i) {
        paths.push_back(syntheticPath(s, t, rng));
        recordRunningSums(paths.back().light, true, mis);
        recordRunningSums(paths.back().camera, false, mis);
    }
    cycle(state, kPaths, [&](size_t i) {
        const SyntheticPath& p = paths[i];
        MisWeight w = series.merge ? mergeWeight(p.light, s, p.camera, t, p.junction, mis)
                                   : misWeight(p.light, s, p.camera, t, p.junction, mis);
        benchmark::DoNotOptimize(w);
    });
    state.counters["k"] = k;
}

// ---- connect() on real subpaths -----------------------------------------------------------------

struct SubpathPair {
    Subpath light, camera;
};

void runConnect(benchmark::State& state, int s, int t) {
    const Scene& scene = cachedScene("cornell");
    // Pairs whose subpaths are long enough for (s, t); for s = 0 the camera's t-th vertex must be
    // on the light. The sample is what the walks give, so some connections fail early (a
    // back-facing BSDF, a point outside the image) exactly as often as they do in a render.
    constexpr size_t kPairs = 256;
    std::vector<SubpathPair> pairs;
    WalkSettings walk;
    walk.maxDepth = 16;
    for (uint64_t i = 0; pairs.size() < kPairs && i < 2'000'000; ++i) {
        Rng rng = testRng(1'000'000 + i);
        SubpathPair p;
        const float x = rng.uniform() * kWidth, y = rng.uniform() * kHeight;
        cameraSubpath(scene, Vec2{x, y}, rng, walk, WalkPdfs::All, kLightPaths, p.camera);
        lightSubpath(scene, rng, walk, WalkPdfs::All, p.light);
        if (static_cast<int>(p.camera.size()) < t || static_cast<int>(p.light.size()) < s) continue;
        if (s == 0 && p.camera[t - 1].emitter < 0) continue;
        pairs.push_back(std::move(p));
    }
    if (pairs.size() < kPairs) {
        state.SkipWithError("could not find subpaths for this (s, t)");
        return;
    }
    const MisContext mis{MisHeuristic::Power, StrategySet{}, Roulette{}, passConstants(kLightPaths, 0.0f)};
    uint64_t nonzero = 0;
    const RayCounts before = threadRayCounts();
    cycle(state, kPairs, [&](size_t i) {
        Connection c = connect(scene, pairs[i].light, s, pairs[i].camera, t, mis);
        nonzero += !isBlack(c.unweighted);
        benchmark::DoNotOptimize(c);
    });
    const RayCounts rays = threadRayCounts() - before;
    state.counters["nonzero_fraction"] = double(nonzero) / double(state.iterations());
    state.counters["rays_per_call"] = double(rays.total()) / double(state.iterations());
}

const bool registered = [] {
    for (MaterialType type : {MaterialType::Lambertian, MaterialType::Mirror, MaterialType::Dielectric,
                              MaterialType::Conductor, MaterialType::Plastic})
        for (auto [op, opName] : {std::pair{BsdfOp::Eval, "eval"}, std::pair{BsdfOp::Sample, "sample"},
                                  std::pair{BsdfOp::Pdf, "pdf"}})
            benchmark::RegisterBenchmark(
                (std::string("kernel/bsdf/") + opName + "/" + materialTypeName(type)).c_str(),
                [type, op = op](benchmark::State& st) { runBsdf(st, type, op); });

    registerPathKernels();

    const int lengths[] = {2, 3, 4, 6, 8, 12, 16, 20, 24, 28, 32};
    // The integrators' sets (src/integrators/bdpt.cpp, vcm.cpp, pt.cpp).
    const StrategySet bdpt{}, vcm{.merging = StrategySet::Merging::EveryVertex}, pt{.maxS = 1, .minT = 2};
    const std::pair<const char*, MisSeries> misSeries[] = {
        {"bdpt/balance", {MisHeuristic::Balance, bdpt}},
        {"bdpt/power", {MisHeuristic::Power, bdpt}},
        {"bdpt/uniform", {MisHeuristic::Uniform, bdpt}},
        {"bdpt/balance/sums", {MisHeuristic::Balance, bdpt, true}},
        {"bdpt/power/sums", {MisHeuristic::Power, bdpt, true}},
        {"vcm/power", {MisHeuristic::Power, vcm}},
        {"vcm/power/sums", {MisHeuristic::Power, vcm, true}},
        {"vcm_merge/power", {MisHeuristic::Power, vcm, false, true}},
        {"vcm_merge/power/sums", {MisHeuristic::Power, vcm, true, true}},
        {"pt_nee/power", {MisHeuristic::Power, pt, false, false, true}},
    };
    for (const auto& [name, series] : misSeries)
        for (int k : lengths)
            benchmark::RegisterBenchmark((std::string("kernel/mis/") + name + "/k:" + std::to_string(k)).c_str(),
                                         [k, series = series](benchmark::State& st) { runMis(st, k, series); });

    const std::pair<int, int> strategies[] = {{0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 2}, {2, 3},
                                              {3, 3}, {4, 4}, {2, 1}, {3, 1}};
    for (auto [s, t] : strategies)
        benchmark::RegisterBenchmark(("kernel/connect/s:" + std::to_string(s) + "/t:" + std::to_string(t)).c_str(),
                                     [s = s, t = t](benchmark::State& st) { runConnect(st, s, t); });
    return true;
}();

}  // namespace

}  // namespace tripath::bench
