// Ray queries (and their independence of the threads that built the BVH), robust ray origins,
// emitter sampling, the sensor's importance, and smallvcm-5 against the peer's conventions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "scenes/builtin_scenes.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "geometry/scene.h"
#include "support.h"

namespace tripath {
namespace {

Rng testRng(uint64_t i) { return Rng(7, static_cast<uint64_t>(StreamDomain::Test), i); }

TEST(SceneQueries, HitsWhereGeometryIsAndMissesWhereNot) {
    const Scene scene(builtinScene("cornell"), 8, 8);
    // Straight up from the middle of the floor: the light (y = 1.99) is in the way of the ceiling.
    auto up = scene.intersect({0, 0.5f, 0.9f}, {0, 1, 0});
    ASSERT_TRUE(up);
    EXPECT_NEAR(up->p.y, 2.0f, 1e-5f);  // z = 0.9 is outside the light's square: hits the ceiling
    auto light = scene.intersect({0, 1.5f, 0}, {0, 1, 0});
    ASSERT_TRUE(light);
    EXPECT_NEAR(light->p.y, 1.99f, 1e-5f);
    EXPECT_GE(scene.emitters().emitterOfTriangle(light->triangle), 0);
    // Out through the open front of the box: nothing.
    EXPECT_FALSE(scene.intersect({0, 1.5f, 0}, {0, 0, 1}));
    // Toward the red wall at x = -1.
    auto left = scene.intersect({0, 1.5f, 0}, {-1, 0, 0});
    ASSERT_TRUE(left);
    EXPECT_NEAR(left->p.x, -1.0f, 1e-5f);
    EXPECT_NEAR(left->t, 1.0f, 1e-5f);
    EXPECT_TRUE(scene.unoccluded({0, 1.5f, 0.9f}, {}, {0.5f, 1.5f, 0.9f}, {}));
    EXPECT_FALSE(scene.unoccluded({-0.34f, 0.3f, 0.5f}, {}, {-0.34f, 0.3f, -0.9f}, {}));  // through the tall box
}

// A large quad at `offset`; rays leave random points of it at grazing elevations and must not
// hit the quad itself.
void expectNoSelfHits(float offset, float size) {
    SceneDesc d;
    Material m;
    m.name = "floor";
    d.materials.push_back(m);
    Material e = m;
    e.emission = Spectrum(1.0f);
    d.materials.push_back(e);
    const Vec3 o(offset, offset, offset);
    d.meshes.push_back({"floor", {o + Vec3(-size, 0, -size), o + Vec3(size, 0, -size), o + Vec3(size, 0, size), o + Vec3(-size, 0, size)},
                        {}, {0, 2, 1, 0, 3, 2}, 0});
    d.meshes.push_back({"light", {o + Vec3(0, 1, 0), o + Vec3(0.1f, 1, 0), o + Vec3(0, 1, 0.1f)}, {}, {0, 1, 2}, 1});
    const Scene scene(d, 4, 4);
    int selfHits = 0, trials = 0;
    for (int i = 0; i < 4000; ++i) {
        Rng rng = testRng(i);
        // Two declarators, so the draws are sequenced (two arguments of one call would not be).
        const float ux = rng.uniform(), uz = rng.uniform();
        const Vec3 target = o + Vec3((ux - 0.5f) * size, 0, (uz - 0.5f) * size);
        // Find the floor point along a vertical ray, as a path vertex would.
        const auto hit = scene.intersect(target + Vec3(0, 1, 0), {0, -1, 0});
        if (!hit || hit->triangle > 1) continue;
        const float elevation = 1e-4f + 1e-2f * rng.uniform();  // up to ~0.6°
        const float phi = 2 * kPi * rng.uniform();
        const Vec3 dir = normalize(Vec3(std::cos(phi), elevation, std::sin(phi)));
        const auto again = scene.intersect(offsetRayOrigin(hit->p, hit->ng, dir), dir);
        ++trials;
        if (again && again->triangle <= 1) ++selfHits;
    }
    EXPECT_GT(trials, 3000);
    EXPECT_EQ(selfHits, 0);
}

// Camera rays traced as one packet (the render loop's runs of up to 8 pixels) must hit, lane by
// lane, what each ray hits alone: a lane mix-up, a lane past the run's end left valid, or a
// non-finite ray not masked out would show here. Directions from the camera through random
// pixels of cornell-spheres (spheres, walls, the open front where rays miss).
TEST(SceneQueries, PacketsOfCameraRaysHitWhatSingleRaysHit) {
    const Scene scene(builtinScene("cornell-spheres"), 32, 32);
    const Camera& cam = scene.camera();
    Rng rng = testRng(42);
    int hits = 0, misses = 0;
    for (int packet = 0; packet < 200; ++packet) {
        const size_t n = 1 + packet % 8;
        std::vector<Vec3> dirs;
        for (size_t i = 0; i < n; ++i) {
            const float x = rng.uniform() * 40.0f - 4.0f, y = rng.uniform() * 40.0f - 4.0f;  // some outside the image
            dirs.push_back(cam.direction({x, y}));
        }
        if (packet % 17 == 0) dirs[n / 2] = Vec3(std::nanf(""), 0, 1);
        std::vector<std::optional<SurfacePoint>> packed(n);
        scene.intersect8(cam.position(), dirs, packed);
        for (size_t i = 0; i < n; ++i) {
            const auto alone = scene.intersect(cam.position(), dirs[i]);
            ASSERT_EQ(packed[i].has_value(), alone.has_value()) << "packet " << packet << " lane " << i;
            if (!alone) {
                ++misses;
                continue;
            }
            ++hits;
            EXPECT_EQ(packed[i]->triangle, alone->triangle) << "packet " << packet << " lane " << i;
            EXPECT_NEAR(packed[i]->t, alone->t, 1e-5f * alone->t);
            EXPECT_NEAR(length(packed[i]->p - alone->p), 0.0f, 1e-5f);
        }
    }
    EXPECT_GT(hits, 200);
    EXPECT_GT(misses, 10);  // the open front and the directions outside the box are in the test
    std::vector<Vec3> nine(9, cam.forward());
    std::vector<std::optional<SurfacePoint>> out(9);
    EXPECT_THROW(scene.intersect8(cam.position(), nine, out), std::logic_error);
}

// The image size is a render's parameter: a scene reframed at another size renders exactly as one
// built at that size, and the scene it came from renders as before once the reframed one is gone
// (they share the BVH). Catches a camera not framed anew (the wrong size or aspect), and a shared
// BVH released by the copy (the base would then trace against freed memory).
TEST(Scene, AReframedSceneRendersAsOneBuiltAtThatSize) {
    const SceneDesc desc = builtinScene("cornell-spheres");
    const Scene base(desc, 40, 40);
    RenderRequest r = test::smallRequest();
    r.integrator = "bdpt";
    r.spp = 3;
    const Image before = test::renderScene(base, r).image();
    {
        const Scene reframed(base, 24, 16);
        const Image framed = test::renderScene(reframed, r).image();
        const Image built = test::renderScene(Scene(desc, 24, 16), r).image();
        ASSERT_EQ(framed.width, 24);
        ASSERT_EQ(framed.height, 16);
        EXPECT_EQ(framed.rgb, built.rgb);
    }
    EXPECT_EQ(test::renderScene(base, r).image().rgb, before.rgb);
}

// A hit on a triangle far larger than the ray's reach is where the ray meets the plane:
// degenerate-tiny's ground (two triangles with corners 5 km away) seen from 3 mm, at points within
// a few millimetres of the origin. Rebuilt from Embree's barycentrics, such a point lands up to
// 0.5 mm off (2^-24 of 10 km), in or out of the shadow of the millimetre cube beside it, and every
// method read that cube's side faces 1-4 % low. Fails with the barycentric point: errors of
// 1e-4 m and more against a bound of 1e-6 m.
TEST(SceneQueries, AHitOnAFarLargerTriangleIsWhereTheRayMeetsIt) {
    const Scene scene(builtinScene("degenerate-tiny"), 16, 16);
    const Vec3 origin(0.0025f, 0.002f, 0.003f);
    float worst = 0;
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j) {
            const Vec3 target(-0.004f - 0.0002f * float(i), 0.0f, -0.004f - 0.0002f * float(j));  // behind the cube, clear of it
            const auto hit = scene.intersect(origin, normalize(target - origin));
            ASSERT_TRUE(hit.has_value()) << i << " " << j;
            worst = std::max(worst, length(hit->p - target));
        }
    EXPECT_LT(worst, 1e-6f);
}

TEST(SceneQueries, NoSelfHitsAtGrazingAnglesNearTheOrigin) { expectNoSelfHits(0.0f, 1.0f); }
TEST(SceneQueries, NoSelfHitsAtGrazingAnglesAtCoordinatesOf1e4) { expectNoSelfHits(1e4f, 100.0f); }

// What each of n rays hits: triangle index, material and the bits of t (-1s for a miss).
// Origins are anywhere in the scene's bounding box, inside closed boxes too, so that the rays
// also reach faces that coincide with others (contact's box faces inside the walls and floor).
struct RayHit {
    int64_t triangle = -1, material = -1;
    uint32_t tBits = 0;
    bool operator==(const RayHit&) const = default;
};
std::vector<RayHit> hitsOfRandomRays(const Scene& scene, int n) {
    const Vec3 lo = scene.boundsMin(), extent = scene.boundsMax() - lo;
    std::vector<RayHit> hits(n);
    for (int i = 0; i < n; ++i) {
        Rng rng = testRng(static_cast<uint64_t>(i));
        const float a = rng.uniform(), b = rng.uniform(), c = rng.uniform(), u = rng.uniform(), v = rng.uniform();
        const auto hit = scene.intersect(lo + extent * Vec3(a, b, c), sampleUniformSphere({u, v}));
        if (!hit) continue;
        hits[i].triangle = hit->triangle;
        hits[i].material = scene.triangles()[hit->triangle].material;
        std::memcpy(&hits[i].tBits, &hit->t, sizeof(float));
    }
    return hits;
}

// A ray that meets two coincident faces meets them at the same distance, and Embree reports the
// one its traversal finds first: the answer depends on the BVH's shape. So the BVH must not
// depend on the threads that built it (Determinism.SameSeedSameImageWhateverTheThreadCount checks
// the images; here every hit is compared). Embree 3.13 builds sets of fewer than 1024 primitives
// on one thread and partitions sets of fewer than 3072 sequentially: the tessellated `contact`
// (4800 triangles) and cornell-spheres (18060) reach its parallel code. Built on 1, 2 and 4
// threads, Embree 3.13.5 gives the same hits.
TEST(Determinism, SameHitsWhateverTheThreadsThatBuiltTheBvh) {
    constexpr int kRays = 100000;
    const std::pair<const char*, SceneDesc> scenes[] = {
        {"contact", builtinScene("contact")},
        {"contact tessellated", test::tessellated(builtinScene("contact"), 10)},
        {"cornell-spheres", builtinScene("cornell-spheres")}};
    for (const auto& [name, desc] : scenes) {
        const auto reference = hitsOfRandomRays(*test::buildWithThreads(desc, 8, 8, 1), kRays);
        for (int threads : {2, 4, 2, 4}) {  // twice each: a parallel build could also vary between runs
            const auto hits = hitsOfRandomRays(*test::buildWithThreads(desc, 8, 8, threads), kRays);
            int changed = 0;
            for (int i = 0; i < kRays; ++i) changed += !(hits[i] == reference[i]);
            EXPECT_EQ(changed, 0) << name << ": rays that hit something else with the BVH built on " << threads
                                  << " threads";
        }
    }
    // The comparison can fail: with contact's triangles given in the opposite order (the same
    // surfaces, other leaves in the BVH) some rays report the other of two coincident faces.
    SceneDesc reversed = builtinScene("contact");
    std::reverse(reversed.meshes.begin(), reversed.meshes.end());
    const auto forward = hitsOfRandomRays(*test::buildWithThreads(builtinScene("contact"), 8, 8, 1), kRays);
    const auto backward = hitsOfRandomRays(*test::buildWithThreads(reversed, 8, 8, 1), kRays);
    int otherMaterial = 0;
    for (int i = 0; i < kRays; ++i) otherMaterial += forward[i].material != backward[i].material;
    EXPECT_GT(otherMaterial, 0);
}

// Pearson's χ² upper tail by the Wilson-Hilferty cube-root normal approximation (a few percent
// in p for k ≳ 30: ample for a 1e-5 rejection threshold).
double chiSquarePValue(double x, int k) {
    const double v = 2.0 / (9.0 * k);
    const double z = (std::cbrt(x / k) - (1.0 - v)) / std::sqrt(v);
    return 0.5 * std::erfc(z / std::sqrt(2.0));
}

// Three triangle emitters and a point light with hand-picked powers (grey, so the power does not
// depend on how a colour is weighed), and one non-emitting triangle that must never be chosen:
//   A: area 1/2, Le 2,   one-sided  Φ = π·A·Le      = π
//   B: area 2,   Le 1/2, two-sided  Φ = 2·π·A·Le    = 2π
//   C: area 3/2, Le 1,   one-sided  Φ = π·A·Le      = 3π/2
//   P: point light, I 1/4           Φ = 4π·I        = π        total 11π/2
// so the choice probabilities are 2/11, 4/11, 3/11, 2/11 and the area densities (share / area)
// 4/11 on A, 2/11 on B, 2/11 on C; P's "area pdf" is its choice probability 2/11.
struct EmitterCase {
    const char* name;
    Vec3 p0, p1, p2;
    double share, density;
};
const EmitterCase kEmitterCases[] = {
    {"A", {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 2.0 / 11, 4.0 / 11},
    {"B", {0, 0, 1}, {0, 2, 1}, {2, 0, 1}, 4.0 / 11, 2.0 / 11},
    {"C", {3, 0, 0}, {4, 0, 0}, {3, 3, 0}, 3.0 / 11, 2.0 / 11},
};
constexpr double kPointShare = 2.0 / 11;

SceneDesc emitterTestScene() {
    SceneDesc d;
    d.name = "emitter-test";
    auto material = [&](float le, bool twoSided) {
        Material m;
        m.name = "m" + std::to_string(d.materials.size());
        m.albedo = Spectrum(0.5f);
        m.emission = Spectrum(le);
        m.twoSidedEmission = twoSided;
        d.materials.push_back(m);
        return static_cast<int>(d.materials.size()) - 1;
    };
    const int dark = material(0.0f, false);
    d.meshes.push_back({"dark", {{-5, -1, -5}, {5, -1, -5}, {0, -1, 5}}, {}, {0, 1, 2}, dark});
    const int mats[3] = {material(2.0f, false), material(0.5f, true), material(1.0f, false)};
    for (int i = 0; i < 3; ++i) {
        const EmitterCase& c = kEmitterCases[i];
        d.meshes.push_back({c.name, {c.p0, c.p1, c.p2}, {}, {0, 1, 2}, mats[i]});
    }
    d.lights.push_back({{1, 1, 3}, Spectrum(0.25f)});
    return d;
}

// Which of the 16 congruent sub-triangles (each edge cut in 4) barycentrics (b1, b2) fall in.
int subTriangle(double b1, double b2) {
    constexpr int n = 4;
    const int i = std::clamp(static_cast<int>(std::floor(n * b1)), 0, n - 1);
    const int j = std::clamp(static_cast<int>(std::floor(n * b2)), 0, n - 1);
    const bool down = (n * b1 - i) + (n * b2 - j) > 1;
    return (i * n + j) * 2 + (down ? 1 : 0);  // sparse index in [0, 32): 16 of them occur
}

// Points from Emitters::sample, histogrammed per emitter and per sixteenth of each triangle,
// against area × power share (χ², p > 1e-5), and the pdf each sample reports against the
// density computed by hand above. Catches: choosing emitters by area or by radiance instead of
// power, forgetting the factor 2 of a two-sided emitter or the 4π of a point light, choosing the
// non-emitting triangle, sampling a triangle non-uniformly (e.g. barycentrics u, v without the
// square root or fold, which crowd a corner or leave the triangle), and a pdfA that is not
// share / area (not divided by the area, or divided by another triangle's).
// The branchless search must give std::upper_bound's index for every u, zero-weight entries
// (never returned) and the cdf's exact steps included: an off-by-one would pick a neighbour.
TEST(Distribution1D, PicksTheFirstEntryWhoseCdfExceedsU) {
    Rng rng(3, static_cast<uint64_t>(StreamDomain::Test), 0);
    for (size_t n : {1, 2, 3, 5, 8, 13, 64}) {
        std::vector<double> w(n);
        for (size_t i = 0; i < n; ++i) w[i] = i % 3 == 1 ? 0.0 : 0.5 + rng.uniform();
        const Distribution1D d(w);
        std::vector<double> cdf(n + 1, 0.0);
        for (size_t i = 0; i < n; ++i) cdf[i + 1] = cdf[i] + w[i];
        for (double& c : cdf) c /= cdf.back();
        std::vector<float> us{0.0f, std::nextafter(1.0f, 0.0f)};
        for (int k = 0; k < 2000; ++k) us.push_back(rng.uniform());
        for (float u : us) {
            const auto it = std::upper_bound(cdf.begin() + 1, cdf.end(), double(u));
            const size_t expected = std::min(static_cast<size_t>(it - cdf.begin()) - 1, n - 1);
            ASSERT_EQ(d.sample(u), expected) << "n=" << n << " u=" << u;
            EXPECT_GT(w[d.sample(u)], 0.0) << "n=" << n << " u=" << u;
        }
    }
    // Exactly on a step, which only weights summing to a power of two make representable: u =
    // cdf[i] belongs to the entry after it (and past a zero-weight entry, to the next non-zero one).
    const std::vector<std::pair<std::vector<double>, std::vector<size_t>>> exact{
        {{1, 1, 1, 1}, {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3}},
        {{1, 0, 1, 2}, {0, 0, 0, 0, 2, 2, 2, 2, 3, 3, 3, 3, 3, 3, 3, 3}},
        {{2, 0, 0, 1, 1, 4, 0, 8}, {0, 0, 3, 4, 5, 5, 5, 5, 7, 7, 7, 7, 7, 7, 7, 7}}};
    for (const auto& [w, expected] : exact) {
        const Distribution1D d(w);
        double total = 0;
        for (double x : w) total += x;
        for (size_t k = 0; k < expected.size(); ++k) {
            const float u = static_cast<float>(double(k) * total / double(expected.size()) / total);
            EXPECT_EQ(d.sample(u), expected[k]) << "u=" << u;
        }
    }
}

TEST(Emitters, SampledPointsFollowPowerShareTimesAreaAndReportTheirDensity) {
    const Scene scene(emitterTestScene(), 4, 4, [](const std::string&) {});
    const Emitters& emitters = scene.emitters();
    ASSERT_EQ(emitters.all().size(), 4u);
    const int n = 200000;
    std::vector<double> observed(3 * 32 + 1, 0.0), expected(3 * 32 + 1, 0.0);
    for (int k = 0; k < 3; ++k)
        for (int b = 0; b < 32; ++b)
            if (b / 2 / 4 + b / 2 % 4 <= (b % 2 == 0 ? 3 : 2))  // the 10 upward and 6 downward cells
                expected[k * 32 + b] = n * kEmitterCases[k].share / 16;
    expected.back() = n * kPointShare;
    int misplaced = 0, wrongDensity = 0, wrongNormal = 0;
    for (int i = 0; i < n; ++i) {
        Rng rng = testRng(1000000 + i);
        const float uc = rng.uniform();
        const Vec2 u{rng.uniform(), rng.uniform()};
        const EmitterSample s = emitters.sample(uc, u, scene.triangles());
        if (emitters.all()[s.emitter].kind == Emitter::Kind::Point) {
            observed.back() += 1;
            if (!(s.p == Vec3(1, 1, 3)) || std::abs(s.pdfA - kPointShare) > 1e-6 * kPointShare) ++wrongDensity;
            continue;
        }
        // Which hand-made triangle holds the point, and where in it.
        int which = -1;
        double b1 = 0, b2 = 0;
        for (int k = 0; k < 3 && which < 0; ++k) {
            const EmitterCase& c = kEmitterCases[k];
            const Vec3 e1 = c.p1 - c.p0, e2 = c.p2 - c.p0, q = s.p - c.p0, nrm = cross(e1, e2);
            const double area2 = length(nrm);
            if (std::abs(dot(q, nrm)) > 1e-5 * area2) continue;  // not in this triangle's plane
            const double x1 = dot(cross(q, e2), nrm) / (area2 * area2), x2 = dot(cross(e1, q), nrm) / (area2 * area2);
            if (x1 < -1e-6 || x2 < -1e-6 || x1 + x2 > 1 + 1e-6) continue;
            which = k, b1 = x1, b2 = x2;
            if (length(s.n - nrm / static_cast<float>(area2)) > 1e-5f) ++wrongNormal;
        }
        if (which < 0) {
            ++misplaced;
            continue;
        }
        observed[which * 32 + subTriangle(b1, b2)] += 1;
        const double density = kEmitterCases[which].density;
        if (std::abs(s.pdfA - density) > 1e-5 * density ||
            std::abs(emitters.pdfA(static_cast<int>(s.emitter), s.towardLight) - density) > 1e-5 * density)
            ++wrongDensity;
    }
    EXPECT_EQ(misplaced, 0);
    EXPECT_EQ(wrongDensity, 0);
    EXPECT_EQ(wrongNormal, 0);
    double chi2 = 0;
    int cells = 0;
    for (size_t b = 0; b < observed.size(); ++b) {
        if (expected[b] == 0) {
            EXPECT_EQ(observed[b], 0) << "cell " << b;
            continue;
        }
        chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
        ++cells;
    }
    ASSERT_EQ(cells, 3 * 16 + 1);
    EXPECT_GT(chiSquarePValue(chi2, cells - 1), 1e-5) << "χ² = " << chi2 << " over " << cells << " cells";
}

TEST(Emitters, ChoiceFollowsPower) {
    // veach-mis: four spheres of equal power, made of many triangles each.
    const Scene scene(builtinScene("veach-mis"), 4, 4);
    const auto& tris = scene.triangles();
    std::vector<int> counts(4, 0);
    const int n = 40000;
    for (int i = 0; i < n; ++i) {
        Rng rng = testRng(i);
        const float uc = rng.uniform();
        const EmitterSample s = scene.emitters().sample(uc, {rng.uniform(), rng.uniform()}, tris);
        const int material = tris[scene.emitters().all()[s.emitter].triangle].material;
        counts[material - 1]++;  // materials 1..4 are the lights, in order
        ASSERT_GT(s.pdfA, 0.0f);
    }
    for (int c : counts) EXPECT_NEAR(c, n / 4.0, 4 * std::sqrt(n * 0.25 * 0.75));
}

TEST(Camera, ImportanceIntegratesToOneOverTheImage) {
    const Scene scene(builtinScene("cornell"), 16, 12);
    const Camera& cam = scene.camera();
    // ∫ W_j(ω) cos θ dω over the sphere = 1 for every pixel j, so over the whole image it sums to
    // the pixel count. Estimated with uniform directions (pdf 1/4π).
    std::vector<double> estimates;
    for (int batch = 0; batch < 16; ++batch) {
        double sum = 0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) {
            Rng rng = testRng(batch * n + i);
            const float u = rng.uniform();
            const Vec3 d = sampleUniformSphere({u, rng.uniform()});
            sum += cam.importance(d) * cam.cosTheta(d) / kUniformSpherePdf;
        }
        estimates.push_back(sum / n / (16.0 * 12.0));
    }
    const auto m = test::meanAndError(estimates);
    EXPECT_NEAR(m.mean, 1.0, 4 * m.stderr_);
    EXPECT_LT(m.stderr_, 0.02);
}

TEST(Camera, RasterAndDirectionAreInverse) {
    const Scene scene(builtinScene("cornell"), 40, 30);
    const Camera& cam = scene.camera();
    for (Vec2 r : {Vec2{0.5f, 0.5f}, Vec2{39.5f, 0.1f}, Vec2{20, 15}, Vec2{3.25f, 29.9f}}) {
        const auto back = cam.raster(cam.direction(r));
        ASSERT_TRUE(back);
        EXPECT_NEAR(back->x, r.x, 1e-3f);
        EXPECT_NEAR(back->y, r.y, 1e-3f);
    }
    EXPECT_FALSE(cam.raster(-cam.forward()));
    EXPECT_EQ(cam.importance(-cam.forward()), 0.0f);
}

// smallvcm-5 must be SmallVCM's scene 5 as SmallVCM images it (the peer comparison,
// bench/peers-smallvcm.sh, compares images pixel for pixel). Its camera, restated from its
// description: right = normalize(up × −forward), up' = −forward × right; camera coordinates c of a
// point X are its offsets from the eye along right, up' and −forward; NDC x = f c.x / −c.z and
// y = −f c.y / −c.z with f = 1 / tan(45°/2); raster = (NDC + 1) · size / 2, so raster y grows
// downwards. Points of the scene must land where that projection puts them, and the light, the
// spheres and the walls must be what the peer's description says.
TEST(Scenes, SmallVcm5IsSmallVcmsScene5) {
    const int size = 256;
    const Scene scene(builtinScene("smallvcm-5"), size, size);
    const Vec3 eye(-0.0439815f, -4.12529f, 0.222539f);
    const Vec3 fwd = normalize(Vec3(0.00688625f, 0.998505f, -0.0542161f));
    const Vec3 right = normalize(cross(Vec3(3.73896e-4f, 0.0542148f, 0.998529f), -fwd));
    const Vec3 up = cross(-fwd, right);
    const double f = 1.0 / std::tan(22.5 * kPi / 180.0);
    auto peerRaster = [&](Vec3 x) {
        const Vec3 d = x - eye;
        const double cx = dot(right, d), cy = dot(up, d), depth = dot(fwd, d);
        return Vec2{float((f * cx / depth + 1) * size / 2), float((-f * cy / depth + 1) * size / 2)};
    };
    const Vec3 points[] = {{-0.53885f, 0.02453f, -0.78002f},  // mirror sphere's centre
                           {0.55831f, 0.02453f, -0.78002f},   // glass sphere's centre
                           {0, 0, 1.26002f},                  // the light's centre
                           {-1.27029f, 1.30455f, 1.28002f},   // back wall, top left corner
                           {1.28975f, 1.30455f, -1.28002f}};  // back wall, bottom right corner
    for (const Vec3& x : points) {
        const auto ours = scene.camera().raster(normalize(x - eye));
        ASSERT_TRUE(ours);
        const Vec2 theirs = peerRaster(x);
        EXPECT_NEAR(ours->x, theirs.x, 0.01f) << x.x << " " << x.y << " " << x.z;
        EXPECT_NEAR(ours->y, theirs.y, 0.01f) << x.x << " " << x.y << " " << x.z;
    }
    // What the eye sees at those points: mirror, glass, the light's front, the walls' colours.
    auto seen = [&](Vec3 x) -> const Material& {
        const auto hit = scene.intersect(eye, normalize(x - eye));
        EXPECT_TRUE(hit);
        return scene.materials()[scene.triangles()[hit->triangle].material];
    };
    EXPECT_EQ(seen(points[0]).type, MaterialType::Mirror);
    EXPECT_TRUE(seen(points[0]).albedo == Spectrum(1.0f));
    EXPECT_EQ(seen(points[1]).type, MaterialType::Dielectric);
    EXPECT_EQ(seen(points[1]).ior, 1.6f);
    EXPECT_TRUE(seen(points[2]).emission == Spectrum(25.03329895614464f));
    EXPECT_TRUE(seen({-1.27029f, 0, 0}).albedo == Spectrum(0.156863f, 0.803922f, 0.172549f));  // left: green
    EXPECT_TRUE(seen({1.28975f, 0, 0}).albedo == Spectrum(0.803922f, 0.152941f, 0.152941f));   // right: red
    // The emitter: the 0.5 m square at z = 1.26002, facing down, and nothing else.
    double area = 0;
    for (const Emitter& e : scene.emitters().all()) {
        const Triangle& t = scene.triangles()[e.triangle];
        EXPECT_FALSE(e.twoSided);
        EXPECT_NEAR(t.geometricNormal().z, -1.0f, 1e-6f);
        for (const Vec3& p : t.p) {
            EXPECT_EQ(p.z, 1.26002f);
            EXPECT_EQ(std::abs(p.x), 0.25f);
            EXPECT_EQ(std::abs(p.y), 0.25f);
        }
        area += e.area;
    }
    EXPECT_NEAR(area, 0.25, 1e-6);
    // Spheres of radius 0.5: every vertex of their triangles on the sphere.
    int onSpheres = 0;
    for (const Triangle& t : scene.triangles()) {
        const MaterialType type = scene.materials()[t.material].type;
        if (type == MaterialType::Lambertian) continue;
        const Vec3 c = type == MaterialType::Mirror ? points[0] : points[1];
        for (const Vec3& p : t.p) EXPECT_NEAR(length(p - c), 0.5f, 1e-5f);
        ++onSpheres;
    }
    EXPECT_EQ(onSpheres, 2 * 16128);
}

}  // namespace
}  // namespace tripath
