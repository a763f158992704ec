// The path core against first principles: the kernels, the pdf bookkeeping of connections, and
// MIS weights checked against a brute-force computation over whole paths.
#include <gtest/gtest.h>

#include "geometry/builtin_scenes.h"
#include "paths/connect.h"
#include "paths/kernels.h"
#include "paths/oracle.h"
#include "paths/walk.h"
#include "test_scenes.h"

namespace tripath {
namespace {

using Path = std::vector<Vertex>;  // x0 (emitter) … xk (sensor)

Vec3 dirTo(const Vertex& from, const Vertex& to) { return normalize(to.p - from.p); }
// x_i scatters through a delta lobe: an interior vertex of delta material. x0 emits and xk senses,
// whatever their material or however the walk that found them saw them.
bool scattersDelta(const Path& x, int i) {
    const int k = static_cast<int>(x.size()) - 1;
    return i > 0 && i < k && x[i].material && isDelta(*x[i].material);
}

// ---- brute force: every pdf of a full path computed from scratch ------------------------------

// Area pdf of x_i when the light side generates it (from x_{i-1}, x_{i-2}); 0 through a delta.
float forwardPdf(const Scene& scene, const Path& x, size_t i) {
    if (i == 0) return scene.emitters().pdfA(x[0].emitter);
    if (i == 1) return toAreaPdf(scene.emitters().directionPdf(x[0].emitter, x[0].ng, dirTo(x[0], x[1])), x[0], x[1]);
    const Vertex& v = x[i - 1];
    const Frame f(v.ns);
    return toAreaPdf(pdfBsdf(*v.material, f.toLocal(dirTo(v, x[i - 2])), f.toLocal(dirTo(v, x[i]))), v, x[i]);
}

// Area pdf of x_i when the camera side generates it (from x_{i+1}, x_{i+2}). The camera's pdf of
// the first direction is its per-pixel pdf N / (A cos³θ) over the pass's N_L = N light paths.
float reversePdf(const Scene& scene, const Path& x, size_t i) {
    const size_t k = x.size() - 1;
    if (i == k) return 1.0f;
    if (i == k - 1) return toAreaPdf(scene.camera().imagePdf(dirTo(x[k], x[k - 1])), x[k], x[k - 1]);
    const Vertex& v = x[i + 1];
    const Frame f(v.ns);
    return toAreaPdf(pdfBsdf(*v.material, f.toLocal(dirTo(v, x[i + 2])), f.toLocal(dirTo(v, x[i]))), v, x[i]);
}

// A point light cannot be hit (s = 0), and no shadow ray joins a delta lobe.
bool strategyCanSample(const Path& x, int s, StrategySet set) {
    const int k = static_cast<int>(x.size()) - 1, t = k + 1 - s;
    if (t < 1 || !set.enabled(s, t)) return false;
    if (s == 0) return !x[0].isDeltaLight();
    return !scattersDelta(x, s - 1) && !scattersDelta(x, s);
}

// The probability that a walk goes on from x_g, the walk's vertex number j, toward the next
// vertex: q(x_g) once the walk holds rrDepth vertices (j + 1 ≥ rrDepth), never from its start.
double continuation(const Path& x, int g, int j, int rrDepth) {
    return j >= 1 && j + 1 >= rrDepth ? continuationProbability(*x[g].material) : 1.0;
}

// p_{s,t}(x̄): light-side pdfs for x_0..x_{s-1}, camera-side for x_s..x_k, each times the
// continuation probability of the vertex that generated it: the light walk reaches x_{i−1} as its
// (i−1)-th vertex, the camera walk reaches x_{i+1} as its (k−i−1)-th. A delta scattering
// contributes the same factor to every strategy that can sample the path, so it counts as 1.
double strategyPdf(const Scene& scene, const Path& x, int s, int rrDepth) {
    const int k = static_cast<int>(x.size()) - 1;
    double p = 1;
    for (int i = 0; i <= k; ++i) {
        const bool afterDelta = i < s ? scattersDelta(x, i - 1) : scattersDelta(x, i + 1);
        if (!afterDelta) p *= i < s ? forwardPdf(scene, x, i) : reversePdf(scene, x, i);
        p *= i < s ? continuation(x, i - 1, i - 1, rrDepth) : continuation(x, i + 1, k - i - 1, rrDepth);
    }
    return p;
}

double bruteForceWeight(const Scene& scene, const Path& x, int s, const MisContext& mis) {
    const MisHeuristic h = mis.heuristic;
    auto term = [&](double p) { return h == MisHeuristic::Balance ? p : h == MisHeuristic::Power ? p * p : (p > 0 ? 1.0 : 0.0); };
    double sum = 0;
    for (int i = 0; i < static_cast<int>(x.size()); ++i)
        if (strategyCanSample(x, i, mis.strategies)) sum += term(strategyPdf(scene, x, i, mis.roulette.depth));
    return term(strategyPdf(scene, x, s, mis.roulette.depth)) / sum;
}

// ---- sampling full paths with the production walks ------------------------------------------

struct SampledPath {
    Path x;
    int s;
    Connection c;
};

// Full paths from connecting real subpaths, with the walks' Russian roulette.
std::vector<SampledPath> samplePaths(const Scene& scene, int samples, const MisContext& mis, int maxDepth = 5) {
    const StrategySet set = mis.strategies;
    std::vector<SampledPath> out;
    const WalkSettings ws{maxDepth, mis.roulette.depth};
    Subpath light, camera;
    for (int i = 0; i < samples; ++i) {
        Rng rng(11, static_cast<uint64_t>(StreamDomain::Test), i);
        const float rx = rng.uniform() * scene.camera().width(), ry = rng.uniform() * scene.camera().height();
        cameraSubpath(scene, {rx, ry}, rng, ws, set.cameraWalkPdfs(), camera);
        lightSubpath(scene, rng, ws, set.lightWalkPdfs(), light);
        for (int t = 1; t <= static_cast<int>(camera.size()); ++t)
            for (int s = 0; s <= static_cast<int>(light.size()); ++s) {
                if (s + t < 2 || s + t - 1 > maxDepth || !set.enabled(s, t)) continue;
                const Connection c = connect(scene, light, s, camera, t, mis);
                if (isBlack(c.unweighted)) continue;
                SampledPath sp{{}, s, c};
                for (int i2 = 0; i2 < s; ++i2) sp.x.push_back(light[i2]);
                for (int j = t - 1; j >= 0; --j) sp.x.push_back(camera[j]);
                out.push_back(sp);
            }
    }
    return out;
}

// The oracles run on every material and emitter kind the loader accepts: delta, glossy and diffuse
// surfaces, emitters of each material (an emissive mirror or pane is a scatterer to the walk that
// hits it and x0 of the path that ends there), two-sided emitters, point lights, smooth normals.
std::vector<SceneDesc> oracleScenes() {
    std::vector<SceneDesc> v;
    for (const char* name : {"cornell", "cornell-spheres", "cornell-small", "cornell-point", "veach-mis", "furnace", "smallvcm-5"})
        v.push_back(builtinScene(name));
    v.push_back(cornellTessellated(100));
    for (MaterialType type : {MaterialType::Mirror, MaterialType::Dielectric, MaterialType::Conductor})
        v.push_back(test::cornellEmissive(type));
    v.push_back(test::everyEmitterKind());
    return v;
}
const StrategySet kSets[] = {{StrategySet::Kind::PathTracing}, {StrategySet::Kind::LightTracing},
                             {StrategySet::Kind::Bidirectional}};
const MisHeuristic kHeuristics[] = {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Uniform};

TEST(Mis, ConnectionWeightsMatchBruteForce) {
    for (const SceneDesc& desc : oracleScenes()) {
        const Scene scene(desc, 24, 24);
        const std::string& name = desc.name;
        for (StrategySet set : kSets)
            for (MisHeuristic h : kHeuristics) {
                // Roulette from the 3rd vertex: within max depth 5, some generators play and some not.
                const MisContext mis{h, set, Roulette{3}};
                const auto paths = samplePaths(scene, 150, mis);
                ASSERT_GT(paths.size(), 20u) << name;
                for (const SampledPath& p : paths) {
                    const double expected = bruteForceWeight(scene, p.x, p.s, mis);
                    ASSERT_NEAR(p.c.weight, expected, 2e-3 * std::max(1.0, expected))
                        << name << " s=" << p.s << " k=" << p.x.size() - 1 << " set=" << int(set.kind) << " h=" << int(h);
                }
            }
    }
}

// ---- MIS on hand-made pdfs: deltas are flags, zeros are zeros ---------------------------------

const Roulette kNoRoulette{1000};

// A path x0 (light[0], an area emitter) … xk (camera[0], the sensor) with the given camera
// vertices' forward pdfs; every other pdf the weight reads comes from the junction.
struct HandPath {
    Subpath light, camera;
    Junction junction;
};

HandPath handPath(std::vector<float> cameraFwd) {
    HandPath h;
    Vertex y0;
    y0.kind = Vertex::Kind::Emitter;
    y0.ng = Vec3(0, -1, 0);
    y0.pdfFwd = 2.0f;  // e: the emitter sampler's area pdf
    h.light.push_back(y0);
    Vertex z0;
    z0.kind = Vertex::Kind::Sensor;
    z0.pdfFwd = 1.0f;
    h.camera.push_back(z0);
    for (float a : cameraFwd) {
        Vertex z;
        z.kind = Vertex::Kind::Surface;
        z.pdfFwd = a;
        h.camera.push_back(z);
    }
    return h;
}

// (s, t) = (1, 2): x0 joined to x1 by NEE. Its rivals are (0, 3), which moves x0 to the camera side
// (ratio lightEnd / e), and (2, 1), which moves x1 to the light side (ratio cameraEnd / a).
TEST(Mis, AZeroPdfThatIsNoDeltaRulesOutOnlyTheStrategiesThatNeedIt) {
    HandPath h = handPath({4.0f});  // a = 4
    h.junction.cameraEnd = 2.0f;    // b: x1 from x0's emission
    h.junction.lightEnd = 0.0f;     // x1's BSDF cannot send the camera walk to x0: (0, 3) is impossible
    const StrategySet bdpt{StrategySet::Kind::Bidirectional};
    const MisWeight w = misWeight(h.light, 1, h.camera, 2, h.junction, {MisHeuristic::Power, bdpt, kNoRoulette});
    // Only (2, 1) competes: 1 / (1 + (b/a)²) = 1 / (1 + 1/4). Reading the zero as a delta (a pdf of
    // 1) would add (1/e)² = 1/4 and give 2/3.
    EXPECT_FLOAT_EQ(w.value, 0.8f);
    EXPECT_FALSE(w.guarded);
}

TEST(Mis, ADeltaScattererCountsAsOneAndRulesOutTheConnectionsAtIt) {
    // x0 = light[0], x1 = camera[2] (reached through the mirror x2 = camera[1]), x3 = the sensor.
    HandPath h = handPath({4.0f, 0.0f});  // x1's pdf from the mirror: a delta, recorded as 0
    h.camera[1].delta = true;
    h.junction.cameraEnd = 3.0f;
    h.junction.cameraBeforeEnd = 5.0f;  // x2 from x1: (3, 1) still joins the sensor to the mirror
    h.junction.lightEnd = 1.0f;         // c: x0 from x1's BSDF
    const StrategySet bdpt{StrategySet::Kind::Bidirectional};
    const MisWeight w = misWeight(h.light, 1, h.camera, 3, h.junction, {MisHeuristic::Power, bdpt, kNoRoulette});
    // (2, 2) and (3, 1) would join at the mirror: impossible. (0, 4) competes with (c/e)² = 1/4.
    EXPECT_FLOAT_EQ(w.value, 0.8f);
    EXPECT_FALSE(w.guarded);
}

TEST(Mis, ANonFiniteRatioGivesWeightZeroAndIsReported) {
    // x1's pdf from the sensor rounds to 0 though the camera generated it, and nothing there is a
    // delta: the ratio toward (2, 1) is b/0. Read as a delta it would be b/1 and a wrong weight.
    HandPath h = handPath({0.0f});
    h.junction.cameraEnd = 2.0f;
    h.junction.lightEnd = 1.0f;
    const StrategySet bdpt{StrategySet::Kind::Bidirectional};
    for (MisHeuristic heuristic : {MisHeuristic::Balance, MisHeuristic::Power}) {
        const MisWeight w = misWeight(h.light, 1, h.camera, 2, h.junction, {heuristic, bdpt, kNoRoulette});
        EXPECT_EQ(w.value, 0.0f);
        EXPECT_TRUE(w.guarded);
    }
}


// Re-splits one full path into every strategy (s', t') and runs the production `connect` on each:
// the weights of the strategies that can sample the path add up to 1.
Subpath lightPrefix(const Scene& scene, const Path& x, int s) {
    Subpath y(x.begin(), x.begin() + s);
    for (int i = 0; i < s; ++i) {
        y[i].pdfFwd = forwardPdf(scene, x, i);
        y[i].pdfRev = reversePdf(scene, x, i);
        y[i].beta = Spectrum(1.0f);
    }
    if (s > 0) {  // x0 as next-event estimation and light subpaths produce it: a point on an emitter
        y[0].kind = Vertex::Kind::Emitter;
        y[0].delta = false;
    }
    return y;
}

Subpath cameraPrefix(const Scene& scene, const Path& x, int s) {
    Subpath z(x.rbegin(), x.rend() - s);
    const int k = static_cast<int>(x.size()) - 1;
    for (int j = 0; j < static_cast<int>(z.size()); ++j) {
        z[j].pdfFwd = reversePdf(scene, x, k - j);
        z[j].pdfRev = forwardPdf(scene, x, k - j);
        z[j].beta = Spectrum(1.0f);
    }
    if (s == 0) {  // x0 reached by the camera walk: a surface that happens to emit
        Vertex& e = z.back();
        e.kind = Vertex::Kind::Surface;
        e.material = &scene.materialOf(e.triangle);
        e.ns = e.ng;
    }
    return z;
}

TEST(Mis, EnabledStrategyWeightsSumToOne) {
    for (const SceneDesc& desc : oracleScenes()) {
        const Scene scene(desc, 24, 24);
        const std::string& name = desc.name;
        for (StrategySet set : kSets)
            for (MisHeuristic h : kHeuristics) {
                const MisContext mis{h, set, Roulette{2}};
                const auto paths = samplePaths(scene, 60, mis);
                for (const SampledPath& p : paths) {
                    const int k = static_cast<int>(p.x.size()) - 1;
                    double sum = 0;
                    for (int s = 0; s <= k; ++s) {
                        const int t = k + 1 - s;
                        if (!set.enabled(s, t) || (s == 0 && p.x[0].isDeltaLight())) continue;
                        Subpath y = lightPrefix(scene, p.x, s), z = cameraPrefix(scene, p.x, s);
                        const Connection c = connect(scene, y, s, z, t, mis);
                        const bool possible = strategyCanSample(p.x, s, set);
                        if (!possible) {
                            EXPECT_TRUE(isBlack(c.unweighted) || c.weight == 0) << name << " delta strategy s=" << s;
                            continue;
                        }
                        sum += c.weight;
                    }
                    ASSERT_NEAR(sum, 1.0, 2e-3) << name << " k=" << k << " set=" << int(set.kind) << " h=" << int(h);
                }
            }
    }
}

// The unweighted estimate of a strategy is f(x̄) / p_{s,t}(x̄), with f the product of the kernels
// and p including the continuation probabilities of the strategy's own walks (roulette from the
// 2nd vertex, so every vertex past the walks' starts plays).
// Paths through a delta scatterer are left out (f and p share a delta factor the oracle cannot
// evaluate); the rest still cross emissive metal and mirror x0s, glossy plastic, two-sided and
// point emitters, and the coarse smooth-normal spheres, where light subpaths carry the adjoint
// shading correction and the leak mask cuts paths. The camera's pdf per pixel is N times the
// image pdf.
TEST(Paths, ConnectionEstimateIsContributionOverPdf) {
    for (const SceneDesc& desc : oracleScenes()) {
        const Scene scene(desc, 24, 24);
        const MisContext mis{MisHeuristic::Balance, {StrategySet::Kind::Bidirectional}, Roulette{2}};
        const auto paths = samplePaths(scene, 200, mis);
        int checked = 0;
        for (const SampledPath& p : paths) {
            const int k = static_cast<int>(p.x.size()) - 1, t = k + 1 - p.s;
            bool delta = false;
            for (int i = 0; i <= k; ++i) delta = delta || scattersDelta(p.x, i);
            if (delta) continue;
            const Spectrum f = pathContribution(scene, p.x);
            const double pdf = strategyPdf(scene, p.x, p.s, mis.roulette.depth) * (t >= 2 ? 24.0 * 24.0 : 1.0);
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(p.c.unweighted[c], f[c] / pdf, 2e-3 * std::abs(f[c] / pdf) + 1e-9)
                    << desc.name << " s=" << p.s << " t=" << t;
            ++checked;
        }
        EXPECT_GT(checked, 50) << desc.name;
    }
}

}  // namespace
}  // namespace tripath
