// The path core against first principles: the kernels, the pdf bookkeeping of connections, and
// MIS weights checked against a brute-force computation over whole paths.
#include <gtest/gtest.h>

#include "geometry/builtin_scenes.h"
#include "paths/connect.h"
#include "paths/kernels.h"
#include "paths/oracle.h"
#include "paths/walk.h"

namespace tripath {
namespace {

using Path = std::vector<Vertex>;  // x0 (emitter) … xk (sensor)

Vec3 dirTo(const Vertex& from, const Vertex& to) { return normalize(to.p - from.p); }
bool isDeltaVertex(const Vertex& v) { return v.kind == Vertex::Kind::Surface && isDelta(*v.material); }

// ---- brute force: every pdf of a full path computed from scratch ------------------------------

// Area pdf of x_i when the light side generates it (from x_{i-1}, x_{i-2}); 0 through a delta.
float forwardPdf(const Scene& scene, const Path& x, size_t i) {
    if (i == 0) return scene.emitters().pdfA(x[0].emitter);
    if (i == 1) return toAreaPdf(scene.emitters().directionPdf(x[0].emitter, x[0].ng, dirTo(x[0], x[1])), x[0], x[1]);
    const Vertex& v = x[i - 1];
    const Frame f(v.ns);
    return toAreaPdf(pdfBsdf(*v.material, f.toLocal(dirTo(v, x[i - 2])), f.toLocal(dirTo(v, x[i]))), v, x[i]);
}

// Area pdf of x_i when the camera side generates it (from x_{i+1}, x_{i+2}).
float reversePdf(const Scene& scene, const Path& x, size_t i) {
    const size_t k = x.size() - 1;
    if (i == k) return 1.0f;
    if (i == k - 1) return toAreaPdf(scene.camera().imagePdf(dirTo(x[k], x[k - 1])), x[k], x[k - 1]);
    const Vertex& v = x[i + 1];
    const Frame f(v.ns);
    return toAreaPdf(pdfBsdf(*v.material, f.toLocal(dirTo(v, x[i + 2])), f.toLocal(dirTo(v, x[i]))), v, x[i]);
}

bool strategyCanSample(const Path& x, int s, StrategySet set) {
    const int k = static_cast<int>(x.size()) - 1, t = k + 1 - s;
    if (t < 1 || !set.enabled(s, t)) return false;
    if (s == 0) return !x[0].isDeltaLight();
    return !isDeltaVertex(x[s - 1]) && !isDeltaVertex(x[s]);
}

// p_{s,t}(x̄): light-side pdfs for x_0..x_{s-1}, camera-side for x_s..x_k. A delta scattering
// contributes the same factor to every strategy that can sample the path, so it counts as 1.
double strategyPdf(const Scene& scene, const Path& x, int s) {
    double p = 1;
    for (int i = 0; i < static_cast<int>(x.size()); ++i) {
        const bool afterDelta = i < s ? (i >= 2 && isDeltaVertex(x[i - 1]))
                                      : (i + 1 < static_cast<int>(x.size()) && isDeltaVertex(x[i + 1]));
        if (!afterDelta) p *= i < s ? forwardPdf(scene, x, i) : reversePdf(scene, x, i);
    }
    return p;
}

double bruteForceWeight(const Scene& scene, const Path& x, int s, MisHeuristic h, StrategySet set) {
    auto term = [&](double p) { return h == MisHeuristic::Balance ? p : h == MisHeuristic::Power ? p * p : (p > 0 ? 1.0 : 0.0); };
    double sum = 0;
    for (int i = 0; i < static_cast<int>(x.size()); ++i)
        if (strategyCanSample(x, i, set)) sum += term(strategyPdf(scene, x, i));
    return term(strategyPdf(scene, x, s)) / sum;
}

// ---- sampling full paths with the production walks ------------------------------------------

struct SampledPath {
    Path x;
    int s;
    Connection c;
};

// Full paths from connecting real subpaths; no Russian roulette, so `unweighted` is exactly f/p.
std::vector<SampledPath> samplePaths(const Scene& scene, int samples, MisHeuristic h, StrategySet set, int maxDepth = 5) {
    std::vector<SampledPath> out;
    const WalkSettings ws{maxDepth, 1000};
    Subpath light, camera;
    for (int i = 0; i < samples; ++i) {
        Rng rng(11, static_cast<uint64_t>(StreamDomain::Test), i);
        const float rx = rng.uniform() * scene.camera().width(), ry = rng.uniform() * scene.camera().height();
        cameraSubpath(scene, {rx, ry}, rng, ws, set.cameraWalkPdfs(), camera);
        lightSubpath(scene, rng, ws, set.lightWalkPdfs(), light);
        for (int t = 1; t <= static_cast<int>(camera.size()); ++t)
            for (int s = 0; s <= static_cast<int>(light.size()); ++s) {
                if (s + t < 2 || s + t - 1 > maxDepth || !set.enabled(s, t)) continue;
                const Connection c = connect(scene, light, s, camera, t, h, set);
                if (isBlack(c.unweighted)) continue;
                SampledPath sp{{}, s, c};
                for (int i2 = 0; i2 < s; ++i2) sp.x.push_back(light[i2]);
                for (int j = t - 1; j >= 0; --j) sp.x.push_back(camera[j]);
                out.push_back(sp);
            }
    }
    return out;
}

const char* kScenes[] = {"cornell", "cornell-spheres", "cornell-small", "cornell-point", "veach-mis", "furnace"};
const StrategySet kSets[] = {{StrategySet::Kind::PathTracing}, {StrategySet::Kind::LightTracing},
                             {StrategySet::Kind::Bidirectional}};
const MisHeuristic kHeuristics[] = {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Uniform};

TEST(Mis, ConnectionWeightsMatchBruteForce) {
    for (const char* name : kScenes) {
        const Scene scene(builtinScene(name), 24, 24);
        for (StrategySet set : kSets)
            for (MisHeuristic h : kHeuristics) {
                const auto paths = samplePaths(scene, 150, h, set);
                ASSERT_GT(paths.size(), 20u) << name;
                for (const SampledPath& p : paths) {
                    const double expected = bruteForceWeight(scene, p.x, p.s, h, set);
                    ASSERT_NEAR(p.c.weight, expected, 2e-3 * std::max(1.0, expected))
                        << name << " s=" << p.s << " k=" << p.x.size() - 1 << " set=" << int(set.kind) << " h=" << int(h);
                }
            }
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
    if (s > 0) y[0].kind = Vertex::Kind::Emitter;
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
    for (const char* name : kScenes) {
        const Scene scene(builtinScene(name), 24, 24);
        for (StrategySet set : kSets)
            for (MisHeuristic h : kHeuristics) {
                const auto paths = samplePaths(scene, 60, h, set);
                for (const SampledPath& p : paths) {
                    const int k = static_cast<int>(p.x.size()) - 1;
                    double sum = 0;
                    for (int s = 0; s <= k; ++s) {
                        const int t = k + 1 - s;
                        if (!set.enabled(s, t) || (s == 0 && p.x[0].isDeltaLight())) continue;
                        Subpath y = lightPrefix(scene, p.x, s), z = cameraPrefix(scene, p.x, s);
                        const Connection c = connect(scene, y, s, z, t, h, set);
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

// The unweighted estimate of a strategy is f(x̄) / p_{s,t}(x̄), with f the product of the kernels.
// (Diffuse scenes: no delta factors. The camera's pdf per pixel is N times the image pdf.)
TEST(Paths, ConnectionEstimateIsContributionOverPdf) {
    // The coarse smooth-normal sphere makes light subpaths carry the adjoint shading correction.
    for (const char* name : {"cornell", "cornell-small", "furnace", "smooth sphere"}) {
        const Scene scene(std::string(name) == "smooth sphere" ? cornellTessellated(100) : builtinScene(name), 24, 24);
        const auto paths = samplePaths(scene, 200, MisHeuristic::Balance, {StrategySet::Kind::Bidirectional});
        for (const SampledPath& p : paths) {
            const int k = static_cast<int>(p.x.size()) - 1, t = k + 1 - p.s;
            const Spectrum f = pathContribution(scene, p.x);
            const double pdf = strategyPdf(scene, p.x, p.s) * (t >= 2 ? 24.0 * 24.0 : 1.0);
            for (int c = 0; c < 3; ++c)
                ASSERT_NEAR(p.c.unweighted[c], f[c] / pdf, 2e-3 * std::abs(f[c] / pdf) + 1e-9)
                    << name << " s=" << p.s << " t=" << t;
        }
    }
}

TEST(Kernels, GeometryTermIsSymmetricAndEmittanceIsLeCosCos) {
    const Scene scene(builtinScene("cornell"), 8, 8);
    const auto paths = samplePaths(scene, 100, MisHeuristic::Balance, {StrategySet::Kind::Bidirectional});
    int checked = 0;
    for (const SampledPath& p : paths) {
        const Path& x = p.x;
        for (size_t i = 0; i + 1 < x.size(); ++i) {
            EXPECT_FLOAT_EQ(g(scene, x[i], x[i + 1]), g(scene, x[i + 1], x[i]));
            EXPECT_FLOAT_EQ(geometricFactor(x[i], x[i + 1]), geometricFactor(x[i + 1], x[i]));
        }
        const Vec3 w = dirTo(x[0], x[1]);
        const Spectrum expected = scene.emitters().Le(x[0].emitter, x[0].ng, w) * (absDot(x[0].ng, w) * cosine(x[1], w));
        const Spectrum eps = emittance(scene, x[0], x[1]);
        for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(eps[c], expected[c]);
        // ρ ≥ 0, and f_r reciprocal where there are no shading normals (all flat in the Cornell box).
        for (size_t i = 1; i + 1 < x.size(); ++i) {
            const Spectrum r = rho(scene, x[i - 1], x[i], x[i + 1]);
            EXPECT_TRUE(r.x >= 0 && r.y >= 0 && r.z >= 0);
            if (x[i].kind != Vertex::Kind::Surface) continue;
            const Spectrum a = scatter(scene, x[i], &x[i - 1], &x[i + 1]), b = scatter(scene, x[i], &x[i + 1], &x[i - 1]);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], 1e-5f * std::abs(a[c]));
            ++checked;
        }
    }
    EXPECT_GT(checked, 50);
}

}  // namespace
}  // namespace tripath
