// Vertex merging (vcm, bpm, ppm): the range search it rests on, and its images against bdpt's --
// unbiased up to a bias that must shrink with the merge radius.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "scenes/builtin_scenes.h"
#include "paths/point_grid.h"
#include "core/rng.h"
#include "integrators/pixel_sample_integrator.h"
#include "integrators/light_phase.h"
#include "support.h"

namespace tripath {
namespace {

using test::meanAndError;

// ---- the range search -------------------------------------------------------------------------

// Every point within the radius, each once, and no other: against a brute-force scan, on clustered
// points (many per cell, many hash collisions), points on cell boundaries and exactly at distance r,
// negative and large coordinates.
TEST(PointGrid, FindsExactlyThePointsWithinTheRadius) {
    Rng rng(3, static_cast<uint64_t>(StreamDomain::Test), 0);
    for (float radius : {0.01f, 0.1f, 1.0f}) {
        std::vector<PointGrid<uint32_t>::Entry> points;
        for (int i = 0; i < 3000; ++i) {
            const float a = rng.uniform(), b = rng.uniform(), c = rng.uniform();
            // A cube of side 4 around −1000 and a tight cluster, plus grid-aligned points.
            const uint32_t i32 = static_cast<uint32_t>(i);
            if (i % 3 == 0) points.push_back({Vec3(-1000.0f) + Vec3(4 * a, 4 * b, 4 * c), i32});
            else if (i % 3 == 1) points.push_back({Vec3(0.01f * a, 0.01f * b, 0.01f * c), i32});
            else points.push_back({Vec3(2 * radius * std::floor(8 * a), 2 * radius * std::floor(8 * b), 0.0f), i32});
        }
        points.push_back({Vec3(radius, 0, 0), static_cast<uint32_t>(points.size())});  // exactly at distance r from the origin
        const PointGrid<uint32_t> grid(points, radius);
        std::vector<Vec3> queries = {Vec3(0.0f), Vec3(-998, -998, -998), Vec3(2 * radius, 2 * radius, 0)};
        for (int q = 0; q < 200; ++q) queries.push_back(points[(q * 37) % points.size()].p + Vec3(0.5f * radius * rng.uniform()));
        for (const Vec3 q : queries) {
            std::vector<int> found(points.size(), 0);
            grid.forEachWithin(q, [&](uint32_t i) { ++found[i]; });
            for (size_t i = 0; i < points.size(); ++i) {
                const bool inside = lengthSquared(points[i].p - q) <= radius * radius;
                ASSERT_EQ(found[i], inside ? 1 : 0) << "radius " << radius << " point " << i;
            }
        }
    }
}

// A table of few buckets: nearly every query's rows of cells wrap past the table's end (split in
// two intervals) and overlap other rows' intervals (merged). Each point within the radius is still
// found exactly once, against a brute-force scan. Catches a wrapped row read only up to the end,
// a second piece starting past bucket 0, and overlapping intervals read twice or merged short.
TEST(PointGrid, RowsWrappingPastTheTableEndAreReadOnce) {
    Rng rng(7, static_cast<uint64_t>(StreamDomain::Test), 0);
    const float radius = 0.1f;
    std::vector<PointGrid<uint32_t>::Entry> points;
    for (uint32_t i = 0; i < 7; ++i) points.push_back({Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 0.4f, i});
    const PointGrid<uint32_t> grid(points, radius);
    int within = 0;
    for (int q = 0; q < 4000; ++q) {
        const Vec3 query = points[size_t(q) % points.size()].p + (Vec3(rng.uniform(), rng.uniform(), rng.uniform()) - Vec3(0.5f)) * 0.25f;
        std::vector<int> found(points.size(), 0);
        grid.forEachWithin(query, [&](uint32_t i) { ++found[i]; });
        for (size_t i = 0; i < points.size(); ++i) {
            const bool inside = lengthSquared(points[i].p - query) <= radius * radius;
            within += inside;
            ASSERT_EQ(found[i], inside ? 1 : 0) << "query " << q << " point " << i;
        }
    }
    EXPECT_GT(within, 1000);  // the queries do find points
}

// A grid built from several parts (the light phase's chunks) finds what the grid of their
// concatenation finds, in the same order: the parts are one sequence, an empty part included.
TEST(PointGrid, PartsIndexAsTheirConcatenation) {
    Rng rng(9, static_cast<uint64_t>(StreamDomain::Test), 0);
    const float radius = 0.05f;
    std::vector<PointGrid<uint32_t>::Entry> all;
    for (uint32_t i = 0; i < 3000; ++i) all.push_back({Vec3(rng.uniform(), rng.uniform(), 0.1f * rng.uniform()), i});
    const std::span<const PointGrid<uint32_t>::Entry> whole(all);
    const std::vector<std::span<const PointGrid<uint32_t>::Entry>> parts = {whole.subspan(0, 1000), whole.subspan(1000, 0),
                                                                            whole.subspan(1000)};
    const PointGrid<uint32_t> one(whole, radius), pieces(parts, radius);
    size_t found = 0;
    for (int q = 0; q < 300; ++q) {
        const Vec3 query(rng.uniform(), rng.uniform(), 0.05f);
        std::vector<uint32_t> a, b;
        one.forEachWithin(query, [&](uint32_t i) { a.push_back(i); });
        pieces.forEachWithin(query, [&](uint32_t i) { b.push_back(i); });
        EXPECT_EQ(a, b) << "query " << q;
        found += a.size();
    }
    EXPECT_GT(found, 300u);
}

// Queries asked together (as a camera path's vertices are) find for each query exactly the points
// a brute-force scan finds within the radius, in the order the query finds them alone: 203 queries
// span several of the grid's batches and end in a partial one, and neighbouring queries share
// buckets. Catches a found point credited to the wrong query, a batch's bounds read from another's
// buckets, or a batch that reorders what one query reports (sums over merges would then depend on
// how the camera path's vertices were grouped). The scan is the oracle, not the one-point search,
// which runs through the same code as a batch of one.
TEST(PointGrid, QueriesAskedTogetherFindWhatEachFindsAlone) {
    Rng rng(5, static_cast<uint64_t>(StreamDomain::Test), 0);
    const float radius = 0.05f;
    std::vector<PointGrid<uint32_t>::Entry> points;
    for (uint32_t i = 0; i < 4000; ++i) points.push_back({Vec3(rng.uniform(), rng.uniform(), 0.1f * rng.uniform()), i});
    const PointGrid<uint32_t> grid(points, radius);
    std::vector<Vec3> queries;
    for (int q = 0; q < 203; ++q) queries.push_back(Vec3(rng.uniform(), rng.uniform(), 0.05f));
    std::vector<std::vector<uint32_t>> alone(queries.size()), together(queries.size());
    for (size_t q = 0; q < queries.size(); ++q) grid.forEachWithin(queries[q], [&](uint32_t i) { alone[q].push_back(i); });
    grid.forEachWithin(std::span<const Vec3>(queries), [&](int q, uint32_t i) { together[size_t(q)].push_back(i); });
    size_t found = 0;
    for (size_t q = 0; q < queries.size(); ++q) {
        std::vector<uint32_t> scan;
        for (const auto& e : points)
            if (lengthSquared(e.p - queries[q]) <= radius * radius) scan.push_back(e.payload);
        std::vector<uint32_t> sorted = together[q];
        std::sort(sorted.begin(), sorted.end());
        EXPECT_EQ(sorted, scan) << "query " << q;
        EXPECT_EQ(together[q], alone[q]) << "query " << q;
        found += scan.size();
    }
    EXPECT_GT(found, queries.size());  // the queries do find points (about 6 each)
}

// Grids of one, two and three points, some sharing a cell, far from the origin: a table of one or
// two buckets, smaller than the three cells a query may span along x where p ± r round across two
// cell boundaries (at x = 1e6 a float's spacing is 0.06 and r = 0.1: a fifth of the queries). Each
// point within the radius is found exactly once, against a brute-force scan, and no payload is
// made up. Catches a row of cells wider than the table read past its end: begin_[2] of a
// one-bucket table, a garbage bound that scripts/test-sanitized.sh reports (the plain build may
// read a bound that happens to be harmless).
TEST(PointGrid, TablesSmallerThanAQueryRowFindEachPointOnce) {
    Rng rng(11, static_cast<uint64_t>(StreamDomain::Test), 0);
    const float radius = 0.1f;
    const Vec3 far(1e6f, 0.0f, 0.0f);
    const std::vector<std::vector<Vec3>> layouts = {
        {far},
        {far, far + Vec3(0.125f, 0, 0)},
        {far, far + Vec3(0.0625f, 0.02f, 0), far + Vec3(-0.125f, 0.05f, 0.03f)},
        {far, far, far + Vec3(0.0f, 0.0f, 0.01f)},  // one cell holds all three
    };
    for (const std::vector<Vec3>& layout : layouts) {
        std::vector<PointGrid<uint32_t>::Entry> points;
        for (const Vec3& p : layout) points.push_back({p, static_cast<uint32_t>(points.size())});
        const PointGrid<uint32_t> grid(points, radius);
        int within = 0;
        for (int q = 0; q < 4000; ++q) {
            const Vec3 query = layout[size_t(q) % layout.size()] + (Vec3(rng.uniform(), rng.uniform(), rng.uniform()) - Vec3(0.5f)) * 0.3f;
            std::vector<int> found(points.size(), 0);
            bool madeUp = false;
            grid.forEachWithin(query, [&](uint32_t i) {
                if (i < found.size()) ++found[i];
                else madeUp = true;
            });
            ASSERT_FALSE(madeUp) << layout.size() << " points, query " << q;
            for (size_t i = 0; i < points.size(); ++i) {
                const bool inside = lengthSquared(points[i].p - query) <= radius * radius;
                within += inside;
                ASSERT_EQ(found[i], inside ? 1 : 0) << layout.size() << " points, query " << q << " point " << i;
            }
        }
        EXPECT_GT(within, 400) << layout.size() << " points";  // the queries do find points
    }
}

TEST(PointGrid, EmptyFindsNothing) {
    const std::vector<PointGrid<uint32_t>::Entry> none;
    const PointGrid<uint32_t> grid(none, 0.5f);
    int n = 0;
    grid.forEachWithin(Vec3(0.0f), [&](uint32_t) { ++n; });
    EXPECT_EQ(n, 0);
}

// ---- the default radius ----------------------------------------------------------------------

float defaultRadius(const std::string& scene, int size) {
    const Scene s(builtinScene(scene), size, size);
    return makeIntegrator("vcm", IntegratorSettings{})->pixelSamples()->firstMergeRadius(s);
}

// The default first-pass radius is a number of pixel widths on what the camera sees: half the
// radius at twice the resolution; 500 times the radius in the Cornell box scaled 500×; and in
// degenerate-tiny (a 1 mm cube seen from 4 mm on a 10 km ground) a fraction of a millimetre, where
// a fraction of the scene's radius would be metres and every camera vertex would merge with every
// light vertex of the pass.
TEST(MergeRadius, TheDefaultFollowsThePixelNotTheSceneExtent) {
    EXPECT_NEAR(defaultRadius("cornell", 64) / defaultRadius("cornell", 128), 2.0, 0.04);
    EXPECT_NEAR(defaultRadius("degenerate-far", 64) / defaultRadius("cornell", 64), 500.0, 10.0);
    const Scene tiny(builtinScene("degenerate-tiny"), 64, 64);
    const float sceneRadius = 0.5f * length(tiny.boundsMax() - tiny.boundsMin());
    EXPECT_GT(sceneRadius, 1000.0f);
    EXPECT_LT(defaultRadius("degenerate-tiny", 64), 1e-4f) << "a 3 mm view over 64 pixels";
}

// Seen in a mirror, a surface's pixel is as wide as at the unfolded distance. In sds-mirrors the
// camera at (−1.5, 0.35, −0.8) looks at the panel's image (0.4, 0.35, −2) in the wall mirror z = −1:
// the mirror is 0.37 away along the ray, the panel 2.247 (|(1.9, 0, −1.2)|). A pixel of a 128-pixel
// image with a vertical field of view of 0.3 rad subtends 2 tan(0.15) / 128 near the centre, so the
// default radius is 0.75 × 2.247 × that = 4.0 mm (at the mirror it would be 0.67 mm: 36 times
// fewer light vertices per merge).
TEST(MergeRadius, TheDefaultMeasuresThePixelBeyondMirrors) {
    const double expected = 0.75 * std::sqrt(1.9 * 1.9 + 1.2 * 1.2) * 2 * std::tan(0.15) / 128;
    EXPECT_NEAR(defaultRadius("sds-mirrors", 128), expected, 0.03 * expected);
}

// A pass's light phase makes its constants (paths/pass_constants.h) and traces that many light
// paths: N_L as given, or one per pixel (32² here); the radius of its index, r_1 (i + 1)^((α−1)/2)
// (0.1 / √2 for pass 3 at α = 0.5); η = π r² N_L. Catches a pass that falls back to one light path
// per pixel when a count is given, or traces a count other than its constants say, a radius of the
// wrong index, and an η that leaves out N_L.
TEST(MergeRadius, APassCarriesItsLightPathsRadiusAndEta) {
    const Scene scene(builtinScene("cornell"), 32, 32);
    for (const std::optional<int64_t> given : {std::optional<int64_t>(300), std::optional<int64_t>()})
        for (const std::string name : {"vcm", "bdpt"}) {
            IntegratorSettings is;
            is.lightPaths = given;
            is.merge.radius = 0.1f;
            is.merge.alpha = 0.5f;
            LightPhase phase;
            const auto integrator = makeIntegrator(name, is);
            const PassConstants c = phase.run(scene, *integrator->pixelSamples(), 3, {1, StreamDomain::Test}).mis.constants;
            const double lightPaths = given ? 300.0 : 1024.0, radius = name == "vcm" ? 0.1 / std::sqrt(2.0) : 0.0;
            const std::string what = name + (given ? " with 300 light paths" : "");
            EXPECT_EQ(c.lightPaths, lightPaths) << what;
            EXPECT_EQ(phase.store().paths(), size_t(lightPaths)) << what;
            EXPECT_NEAR(c.radius, radius, 1e-7) << what;
            EXPECT_NEAR(c.mergeEta, kPi * radius * radius * lightPaths, 1e-5 * lightPaths) << what;
        }
}

// ---- images against bdpt ---------------------------------------------------------------------

// Luminance means over `runs` independent runs (seeds 300, 301, …): of the whole image, and of
// each of its 4×4 blocks.
struct Runs {
    std::vector<double> image;
    test::BlockRuns blocks;
};

Runs renderRuns(const SceneDesc& desc, const RenderRequest& r, int runs) {
    std::vector<test::Block> blocks = test::blockGrid(r.width, r.height, 4, 4);
    blocks.push_back({0, 0, r.width, r.height});
    test::BlockRuns means = test::blockRuns(Scene(desc, r.width, r.height), r, runs, 300, blocks);
    Runs out{means.back(), {}};
    means.pop_back();
    out.blocks = std::move(means);
    return out;
}

RenderRequest request(const std::string& integrator, int spp, float radiusFactor, float alpha) {
    RenderRequest r = test::smallRequest();
    r.integrator = integrator;
    r.width = r.height = 32;
    r.spp = spp;
    r.maxDepth = 8;
    r.merge.radiusFactor = radiusFactor;
    r.merge.alpha = alpha;
    return r;
}

// vcm with a small radius agrees with bdpt on every block within statistical error: merges only
// add strategies, and where connections sample a path well, MIS gives merges little weight (and
// their bias with it). Catches merges whose weights do not compete with the connections' (a merge
// weight fixed at 0.5 fails all three) and a vcm that pairs or connects its subpaths otherwise
// than bdpt. Too weak for the connections ignoring the merges' terms (merges counted twice): at
// this radius their share is under the noise; the furnace and Merging.BiasShrinksWithTheRadius*
// catch that one.
void expectVcmAgreesWithBdpt(const std::string& name) {
    const SceneDesc desc = builtinScene(name);
    const Runs bdpt = renderRuns(desc, request("bdpt", 8, 0, 1), 16);
    const Runs vcm = renderRuns(desc, request("vcm", 8, 0.005f, 0.75f), 16);
    test::BlockAgreement agreement;  // Holm's first threshold, 0.01/16, is |t| ≈ 4
    agreement.compare(bdpt.blocks, vcm.blocks, name + ": bdpt against vcm");
    agreement.expectNoBias();
}

TEST(Merging, VcmAgreesWithBdptOnCornell) { expectVcmAgreesWithBdpt("cornell"); }

// With N_L other than the 1024 pixels -- 341 light paths a pass, and 2560 -- bdpt and vcm still
// agree with bdpt at one per pixel on every block, and lt with lt at one per pixel (it cannot see
// the light or the spheres' reflections); the 96 comparisons are judged together. Catches the
// count entering the MIS weights, the splats or the merges' η inconsistently (the furnace, whose
// light is uniform, cannot see a weight that is off in one direction and compensated in another),
// and camera samples connecting with a light path other than their own index modulo N_L.
TEST(Merging, AnyNumberOfLightPathsAgreesWithOnePerPixel) {
    const SceneDesc desc = builtinScene("cornell-spheres");
    const Runs bdpt = renderRuns(desc, request("bdpt", 8, 0, 1), 16);
    const Runs lt = renderRuns(desc, request("lt", 8, 0, 1), 16);
    test::BlockAgreement agreement;
    for (const int lightPaths : {341, 2560})
        for (const std::string integrator : {"lt", "bdpt", "vcm"}) {
            RenderRequest r = request(integrator, 8, 0.005f, 0.75f);
            r.lightPaths = lightPaths;
            r.lightPathsGiven = true;
            const Runs& reference = integrator == "lt" ? lt : bdpt;
            const std::string what = "one per pixel against " + integrator + " with " + std::to_string(lightPaths);
            agreement.compare(reference.blocks, renderRuns(desc, r, 16).blocks, what + " light paths");
        }
    agreement.expectNoBias();
}
TEST(Merging, VcmAgreesWithBdptOnCornellSpheres) { expectVcmAgreesWithBdpt("cornell-spheres"); }
TEST(Merging, VcmAgreesWithBdptOnVeachMis) { expectVcmAgreesWithBdpt("veach-mis"); }

// A density estimate over a disc of radius r loses the light near the box's edges and corners (the
// disc reaches over them, where no light vertex can be) and blurs the light's falloff: in the
// Cornell box the image comes out darker by an amount about proportional to r. For each merging
// integrator, against bdpt:
// - the whole image's difference must be significant at a large radius (5σ) and fall by more than
//   half when the radius is a quarter (to a quarter, if the bias is linear in r);
// - per 8×8 block, Σ_b (Δ_b² − σ_b²) -- an unbiased estimate of the blocks' squared bias, the
//   noise's share taken out -- must fall below a quarter (a sixteenth, if linear).
// The large radius is a fraction of the scene's radius where the bias is still about linear in r.
void expectBiasShrinksWithTheRadius(const std::string& scene, const std::vector<std::string>& integrators, float largeFactor, int vcmSpp) {
    const SceneDesc desc = builtinScene(scene);
    const Runs reference = renderRuns(desc, request("bdpt", 32, 0, 1), 8);
    const auto whole = meanAndError(reference.image);
    for (const std::string& integrator : integrators) {
        // bpm and ppm take their direct light from merges too: noisier, so more samples.
        const int spp = integrator == "vcm" ? vcmSpp : 32;
        std::vector<double> bias, blockBias2;
        for (float factor : {largeFactor, largeFactor / 4}) {
            const Runs runs = renderRuns(desc, request(integrator, spp, factor, 1), 8);
            const auto m = meanAndError(runs.image);
            bias.push_back(m.mean - whole.mean);
            double b2 = 0;
            for (int b = 0; b < 16; ++b) {
                const auto x = meanAndError(runs.blocks[b]), y = meanAndError(reference.blocks[b]);
                b2 += (x.mean - y.mean) * (x.mean - y.mean) - x.stderr_ * x.stderr_ - y.stderr_ * y.stderr_;
            }
            blockBias2.push_back(b2);
            std::cout << scene << ", " << integrator << " radius factor " << factor << ": " << m.mean << " ± " << m.stderr_ << " vs bdpt "
                      << whole.mean << " ± " << whole.stderr_ << "; blocks' squared bias " << b2 << "\n";
            if (factor == largeFactor) {
                EXPECT_GT(std::abs(bias.back()), 5 * std::hypot(m.stderr_, whole.stderr_)) << scene << " " << integrator << ": the bias must show";
            }
        }
        EXPECT_LT(std::abs(bias[1]), 0.5 * std::abs(bias[0])) << scene << " " << integrator;
        EXPECT_LT(blockBias2[1], 0.25 * blockBias2[0]) << scene << " " << integrator;
    }
}

TEST(Merging, BiasShrinksWithTheRadiusOnCornell) { expectBiasShrinksWithTheRadius("cornell", {"vcm", "bpm", "ppm"}, 0.2f, 16); }
// With a mirror ball and a glass ball: ppm's camera walks go through them to the walls and floor,
// and the caustic under the glass ball is a density estimate for all three.
TEST(Merging, BiasShrinksWithTheRadiusOnCornellSpheres) { expectBiasShrinksWithTheRadius("cornell-spheres", {"vcm", "bpm", "ppm"}, 0.2f, 16); }
// The plates are narrow strips: at 0.2 R the disc reaches over a whole plate and onto the next,
// and the bias is not yet linear (vcm: −0.0075 at 0.1 R, −0.0088 at 0.05 R, −0.0038 at 0.025 R).
// bpm and ppm are left out here. ppm's only estimate of the lights' reflections in the plates is a
// density estimate under a glossy lobe, which is heavy-tailed (at 0.003 R, 8 runs of 2048 spp,
// those pixels read 0 but for a rare sample 40 times their mean), so at a test's sample counts
// the block means are not normal and a 5σ test would judge their tails, not their bias. bpm
// agrees with bdpt at 0.003 R (whole image 0.2262 against 0.2259 at 512 spp), but between the
// radii a test can resolve its bias is not linear in r (−0.012 at 0.05 R, −0.0067 at 0.0125 R,
// ± 0.002 over 8 runs of 1024 spp): the share MIS gives its merges moves with r.
TEST(Merging, BiasShrinksWithTheRadiusOnVeachMis) { expectBiasShrinksWithTheRadius("veach-mis", {"vcm"}, 0.05f, 32); }

// The progressive schedule r_i = r_1 i^((α−1)/2) makes the same bias vanish. With α = 0.25 the
// radius of pass i is r_1 / i^⅜ (0.21 r_1 at pass 64, 0.37 r_1 on average over 64 passes): the
// image of 64 passes carries well under the bias of its first 4 passes (radii 0.6–1 r_1) and
// about a third of that of 64 passes at the fixed radius r_1. vcm, whose connections keep the
// noise low, resolves the bias best.
TEST(Merging, ProgressiveRadiusShrinksTheBias) {
    const SceneDesc desc = builtinScene("cornell");
    const auto reference = meanAndError(renderRuns(desc, request("bdpt", 64, 0, 1), 8).image);
    const auto early = meanAndError(renderRuns(desc, request("vcm", 4, 0.2f, 0.25f), 16).image);
    const auto late = meanAndError(renderRuns(desc, request("vcm", 64, 0.2f, 0.25f), 4).image);
    const auto fixed = meanAndError(renderRuns(desc, request("vcm", 64, 0.2f, 1.0f), 4).image);
    std::cout << "vcm, alpha 0.25: 4 passes " << early.mean << " ± " << early.stderr_ << ", 64 passes " << late.mean
              << " ± " << late.stderr_ << "; alpha 1, 64 passes " << fixed.mean << " ± " << fixed.stderr_ << "; bdpt "
              << reference.mean << " ± " << reference.stderr_ << "\n";
    EXPECT_GT(std::abs(early.mean - reference.mean), 5 * std::hypot(early.stderr_, reference.stderr_));
    EXPECT_LT(std::abs(late.mean - reference.mean), 0.67 * std::abs(early.mean - reference.mean));
    EXPECT_LT(std::abs(late.mean - reference.mean), 0.5 * std::abs(fixed.mean - reference.mean));
}

}  // namespace
}  // namespace tripath
