// The specular-diffuse-specular scene with a closed-form answer, `sds-mirrors` (failure_scenes.h):
// a point light in a black hood, a floor mirror that reflects it onto a diffuse panel, and a wall
// mirror in which the camera sees the panel -- the path L S D S E. The image-source method gives
// the panel's irradiance, E(x) = R1 I cos θ / |x − L'|² with L' the light's image in the floor, so
// these tests check the physics against a number, not one method against another:
//
//   - through the wall mirror, pt, lt and bdpt are exactly black: no strategy samples L S D S E;
//   - seen directly (L S D E), lt and bdpt, which are unbiased there, match the closed form: a
//     check of the closed form itself, the units of the point light's intensity included;
//   - through the wall mirror, ppm, bpm and vcm converge to the closed form. For merge radius r
//     their expected value is the closed form averaged over discs of radius r on the panel (the
//     density estimate's bias), computed here by quadrature: the measured means follow it at
//     every radius, and the bias shrinks with r and with the passes (progressive radius).
//
// Bugs these catch: a wrong merge normalisation 1/(π r² N_L) (scaled by any constant factor),
// a mirror's reflectance dropped or applied twice on either subpath, a wrong point-light
// intensity or emission pdf, a missing 1/π at the merged Lambertian vertex, a radius schedule
// other than the documented r_i = r_1 i^((α−1)/2), merges that leak to a surface facing away.
//
// Statistics: R independent runs with fixed seeds; the standard error of a mean comes from the
// spread of the runs (R − 1 = 11 degrees of freedom); a mean agrees with its expected value when
// they differ by less than 4.5 standard errors (two-sided p ≈ 0.001 per comparison).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "scenes/builtin_scenes.h"
#include "scenes/failure_scenes.h"
#include "io/gltf_loader.h"
#include "geometry/scene.h"
#include "scenes/scene_builder.h"
#include "integrators/integrator.h"
#include "integrators/render.h"
#include "support.h"

namespace tripath {
namespace {

const SdsMirrorsLayout& K = kSdsMirrors;
constexpr int kSize = 32;     // image width and height
constexpr int kRuns = 12;     // independent runs per estimate
constexpr double kZ = 4.5;    // agreement: within kZ standard errors

// ---- the closed form, in double precision ------------------------------------------------------

struct D3 {
    double x = 0, y = 0, z = 0;
};
D3 d3(Vec3 v) { return {v.x, v.y, v.z}; }
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator-(D3 a, D3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(D3 a, D3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
D3 unit(D3 a) { return a * (1.0 / std::sqrt(dot(a, a))); }

// The light's image in the floor mirror (the plane y = 0).
D3 lightImage() { return {K.light.x, -double(K.light.y), K.light.z}; }

// Irradiance at the panel point (panelX, y, z), whose normal is −x: the light arrives from L' only,
// through the floor mirror of reflectance R1, so E = R1 I cos θ / d² with cos θ = (panelX − L'x) / d.
double irradiance(double y, double z) {
    const D3 v = D3{K.panelX, y, z} - lightImage();
    const double d2 = dot(v, v);
    return double(K.floorReflectance) * K.intensity * v.x / (d2 * std::sqrt(d2));
}

// Lambertian: Lo = ρ/π E, the same in every direction.
double panelRadiance(double y, double z) { return double(K.panelAlbedo) / std::numbers::pi * irradiance(y, z); }

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n).
struct Gauss {
    std::vector<double> x, w;
    explicit Gauss(int n) : x(n), w(n) {
        for (int i = 0; i < n; ++i) {
            double t = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 0;
            for (int it = 0; it < 100; ++it) {
                double p0 = 1, p1 = t;
                for (int k = 2; k <= n; ++k) {
                    const double p2 = ((2 * k - 1) * t * p1 - (k - 1) * p0) / k;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n * (t * p1 - p0) / (t * t - 1);
                const double step = p1 / dp;
                t -= step;
                if (std::abs(step) < 1e-15) break;
            }
            x[i] = t;
            w[i] = 2 / ((1 - t * t) * dp * dp);
        }
    }
};

// The expected value of a merge of radius r at panel point (y, z): each light vertex within r
// counts, so the estimate is the mean of E over the disc of radius r around (y, z) in the panel's
// plane, where no light vertex lies off the panel. With y' = r sin φ and z' = r cos φ s the disc
// is φ ∈ [−π/2, π/2], s ∈ [−1, 1] with area element r² cos²φ dφ ds; the panel's bottom and top
// edges (y = const) cut φ at asin((y_edge − y)/r), and the integrand stays smooth, so Gauss-
// Legendre is accurate to ~1e-6 here. The sides are kept more than r away (regions' margins).
double discMeanRadiance(double y, double z, double r) {
    static const Gauss g(10);
    auto angle = [&](double edge) { return std::asin(std::clamp((edge - y) / r, -1.0, 1.0)); };
    const double lo = angle(K.panelY0), hi = angle(K.panelY1);
    double sum = 0;
    for (size_t i = 0; i < g.x.size(); ++i) {
        const double phi = 0.5 * (lo + hi) + 0.5 * (hi - lo) * g.x[i];
        const double c = std::cos(phi);
        double inner = 0;
        for (size_t j = 0; j < g.x.size(); ++j) inner += g.w[j] * panelRadiance(y + r * std::sin(phi), z + r * c * g.x[j]);
        sum += g.w[i] * 0.5 * (hi - lo) * c * c * inner;
    }
    return sum / std::numbers::pi;  // (1 / π r²) ∫ ... r² cos²φ dφ ds
}

// ---- where pixels land on the panel ----------------------------------------------------------

// The pinhole as the scene description defines it (raster origin top-left, right = forward × up,
// yfov vertical, square pixels), rebuilt here rather than borrowed from Camera.
struct Pinhole {
    D3 o, forward, right, up;
    double tanX, tanY;
    Pinhole(const CameraDesc& c, int w, int h) : o(d3(c.position)), forward(unit(d3(c.forward))) {
        right = unit(cross(forward, d3(c.up)));
        up = cross(right, forward);
        tanY = std::tan(0.5 * c.yfov);
        tanX = tanY * w / h;
    }
    D3 dir(double px, double py) const {
        const double sx = (2 * px / kSize - 1) * tanX, sy = (1 - 2 * py / kSize) * tanY;
        return unit(forward + right * sx + up * sy);
    }
};

struct PanelPoint {
    double y = 0, z = 0;
};

// Where a ray meets the panel from its front (x increasing toward the plane x = panelX), if it does.
std::optional<PanelPoint> hitPanel(D3 o, D3 d) {
    if (!(d.x > 0)) return std::nullopt;
    const D3 p = o + d * ((K.panelX - o.x) / d.x);
    if (p.y < K.panelY0 || p.y > K.panelY1 || std::abs(p.z) > K.panelHalfZ) return std::nullopt;
    return PanelPoint{p.y, p.z};
}

// The camera ray through raster (px, py), reflected by the wall mirror (plane z = wallZ).
std::optional<PanelPoint> throughWall(const Pinhole& cam, double px, double py) {
    D3 d = cam.dir(px, py);
    if (!(d.z < 0)) return std::nullopt;
    const D3 h = cam.o + d * ((K.wallZ - cam.o.z) / d.z);
    if (h.x < K.wallX0 || h.x > K.wallX1 || h.y < K.wallY0 || h.y > K.wallY1) return std::nullopt;
    d.z = -d.z;
    return hitPanel(h, d);
}

std::optional<PanelPoint> directly(const Pinhole& cam, double px, double py) { return hitPanel(cam.o, cam.dir(px, py)); }

using Mapping = std::function<std::optional<PanelPoint>(const Pinhole&, double, double)>;

// A set of pixels whose whole footprints land on a part of the panel, and points spread evenly
// over those footprints (a pixel is the box-filtered mean over its footprint, so the mean over
// these points is the region's mean pixel value).
struct Region {
    std::vector<int> pixels;  // y * kSize + x
    std::vector<PanelPoint> samples;
};

// The pixels whose footprint (a (n+1)² grid over it, corners included) lies in y ∈ [yLo, yHi],
// |z| ≤ zMax; n² footprint samples per pixel at the centres of the grid's cells.
Region selectPixels(const Pinhole& cam, const Mapping& map, double yLo, double yHi, double zMax, int n = 6) {
    Region r;
    for (int py = 0; py < kSize; ++py)
        for (int px = 0; px < kSize; ++px) {
            bool inside = true;
            for (int i = 0; i <= n && inside; ++i)
                for (int j = 0; j <= n && inside; ++j) {
                    const auto p = map(cam, px + double(i) / n, py + double(j) / n);
                    inside = p && p->y >= yLo && p->y <= yHi && std::abs(p->z) <= zMax;
                }
            if (!inside) continue;
            r.pixels.push_back(py * kSize + px);
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) r.samples.push_back(*map(cam, px + (i + 0.5) / n, py + (j + 0.5) / n));
        }
    return r;
}

// The region's mean of the closed form (scale: R2 through the wall mirror, 1 seen directly).
double exactMean(const Region& r, double scale) {
    double sum = 0;
    for (const PanelPoint& p : r.samples) sum += panelRadiance(p.y, p.z);
    return scale * sum / r.samples.size();
}

// The region's expected mean after each pass count n = 1..passes, for a merge radius
// r_i = r1 i^((α−1)/2) at pass i: the mean over passes of the disc-averaged closed form.
std::vector<double> expectedMeans(const Region& r, double scale, double r1, double alpha, int passes) {
    std::vector<double> out(passes + 1, 0.0);
    double sum = 0, previous = -1;
    double value = 0;
    for (int i = 1; i <= passes; ++i) {
        const double radius = r1 * std::pow(double(i), 0.5 * (alpha - 1));
        if (radius != previous) {
            value = 0;
            for (const PanelPoint& p : r.samples) value += discMeanRadiance(p.y, p.z, radius);
            value *= scale / r.samples.size();
            previous = radius;
        }
        sum += value;
        out[i] = sum / i;
    }
    return out;
}

// ---- rendering -------------------------------------------------------------------------------

// Mean over a region's pixels and the three channels.
double regionMean(const Image& img, const Region& r) {
    double sum = 0;
    for (int p : r.pixels)
        for (int c = 0; c < 3; ++c) sum += img.at(p % kSize, p / kSize)[c];
    return sum / (3.0 * r.pixels.size());
}

// One render of `passes` passes; for each pass count in `at`, the mean of each region.
std::vector<std::vector<double>> renderRegions(const Scene& scene, const std::string& integrator, MergeSettings merge,
                                               uint64_t seed, int passes, const std::vector<int>& at,
                                               const std::vector<const Region*>& regions, Image* last = nullptr) {
    IntegratorSettings is;
    is.merge = merge;
    const auto method = makeIntegrator(integrator, is);
    RenderSettings rs;
    rs.spp = passes;
    rs.seed = seed;
    std::vector<std::vector<double>> out;
    rs.onPass = [&](const Film& film, int done, double) {
        if (std::find(at.begin(), at.end(), done) == at.end()) return;
        const Image img = film.image(done);
        std::vector<double> means;
        for (const Region* r : regions) means.push_back(regionMean(img, *r));
        out.push_back(means);
    };
    const RenderResult result = render(scene, *method, rs);
    EXPECT_EQ(result.droppedSamples, 0u) << integrator;
    if (last) *last = result.image();
    return out;
}

// A relative difference (signed) or a relative error (unsigned) in percent.
std::string percent(double x, bool sign = true) {
    char buf[32];
    std::snprintf(buf, sizeof buf, sign ? "%+.2f %%" : "%.2f %%", 100 * x);
    return buf;
}

// The scene's own camera looks into the wall mirror; this one looks at the panel directly.
SceneDesc directView() {
    SceneDesc desc = builtinScene("sds-mirrors");
    desc.camera = build::lookAt({-0.6f, 0.35f, 0.3f}, {K.panelX, 0.35f, 0.0f}, 0.6f);
    return desc;
}

// Through the wall mirror, the panel away from its edges by more than any merge radius used
// here (so every disc lies on the panel), and a band along its bottom edge, where the discs reach
// over the edge and lose light: a bias of order r, large enough to measure.
constexpr double kMaxRadius = 0.06;
Region interior(const Pinhole& cam) {
    return selectPixels(cam, throughWall, K.panelY0 + kMaxRadius, K.panelY1 - kMaxRadius, K.panelHalfZ - kMaxRadius);
}
Region bottomBand(const Pinhole& cam) {
    return selectPixels(cam, throughWall, K.panelY0, K.panelY0 + 0.04, K.panelHalfZ - kMaxRadius);
}

// ---- the scene is what the closed form assumes -------------------------------------------------

TEST(SdsMirrors, TheSceneIsWhatTheClosedFormAssumes) {
    const SceneDesc desc = builtinScene("sds-mirrors");
    const Scene scene(desc, kSize, kSize);
    const Pinhole cam(desc.camera, kSize, kSize);
    const Region inner = interior(cam), band = bottomBand(cam);
    std::cout << "through the wall mirror: " << inner.pixels.size() << " interior pixels, " << band.pixels.size()
              << " along the bottom edge\n";
    ASSERT_GE(inner.pixels.size(), 100u);
    ASSERT_GE(band.pixels.size(), 8u);

    auto materialAt = [&](const SurfacePoint& h) { return scene.materialOf(h.triangle).name; };
    for (const Material& m : scene.materials()) {
        if (m.name == "floor mirror") {
            EXPECT_TRUE(m.type == MaterialType::Mirror && m.albedo == Spectrum(K.floorReflectance));
        }
        if (m.name == "wall mirror") {
            EXPECT_TRUE(m.type == MaterialType::Mirror && m.albedo == Spectrum(K.wallReflectance));
        }
        if (m.name == "panel") {
            EXPECT_TRUE(m.type == MaterialType::Lambertian && m.albedo == Spectrum(K.panelAlbedo));
        }
        if (m.name == "black hood") {
            EXPECT_TRUE(isBlack(m.albedo) && isBlack(m.emission));
        }
    }
    ASSERT_EQ(scene.emitters().all().size(), 1u);

    // Camera rays of the selected pixels meet the wall mirror first, then the panel, where the
    // closed form's mapping says.
    for (const Region* r : {&inner, &band})
        for (int p : r->pixels) {
            const double px = p % kSize + 0.5, py = p / kSize + 0.5;
            const D3 d = cam.dir(px, py);
            const auto first = scene.intersect(desc.camera.position, Vec3(float(d.x), float(d.y), float(d.z)));
            ASSERT_TRUE(first.has_value());
            ASSERT_EQ(materialAt(*first), "wall mirror") << "pixel " << p;
            const Vec3 reflected(float(d.x), float(d.y), float(-d.z));
            const auto second = scene.intersect(offsetRayOrigin(first->p, first->ng, reflected), reflected);
            ASSERT_TRUE(second.has_value());
            ASSERT_EQ(materialAt(*second), "panel") << "pixel " << p;
            const PanelPoint expected = *throughWall(cam, px, py);
            EXPECT_NEAR(second->p.y, expected.y, 1e-4);
            EXPECT_NEAR(second->p.z, expected.z, 1e-4);
        }

    // Over a grid of the panel: the light cannot see it (the hood), and it sees the light's image
    // through the floor mirror, unobstructed; the wall mirror receives no light, directly or
    // through the floor.
    const D3 image = lightImage();
    auto throughFloor = [&](Vec3 x, Vec3 n) {
        const D3 xd = d3(x);
        const D3 f = image + (xd - image) * (-image.y / (xd.y - image.y));  // where x − L' crosses y = 0
        const bool onMirror = f.x >= K.floorX0 && f.x <= K.floorX1 && std::abs(f.z) <= K.floorHalfZ;
        const Vec3 fv(float(f.x), 0.0f, float(f.z));
        return onMirror && scene.unoccluded(K.light, Vec3(0.0f), fv, Vec3(0, 1, 0)) && scene.unoccluded(fv, Vec3(0, 1, 0), x, n);
    };
    for (int i = 0; i <= 10; ++i)
        for (int j = 0; j <= 10; ++j) {
            const Vec3 x(K.panelX, K.panelY0 + (K.panelY1 - K.panelY0) * (0.005f + 0.099f * i),
                         K.panelHalfZ * (-0.99f + 0.198f * j));
            EXPECT_FALSE(scene.unoccluded(K.light, Vec3(0.0f), x, Vec3(-1, 0, 0))) << "the light sees the panel";
            EXPECT_TRUE(throughFloor(x, Vec3(-1, 0, 0))) << "panel point " << x.y << ", " << x.z << " unlit";
            const Vec3 w(K.wallX0 + (K.wallX1 - K.wallX0) * 0.1f * i, K.wallY0 + (K.wallY1 - K.wallY0) * 0.1f * j, K.wallZ);
            EXPECT_FALSE(scene.unoccluded(K.light, Vec3(0.0f), w, Vec3(0, 0, 1))) << "the light sees the wall mirror";
            EXPECT_FALSE(throughFloor(w, Vec3(0, 0, 1))) << "the wall mirror is lit through the floor";
        }
}

// The quadrature of the disc mean: exact for a constant, and equal to E plus r²/8 ∇²E to leading
// order away from the edges (checked against a finite-difference Laplacian).
TEST(SdsMirrors, DiscMeanQuadrature) {
    const double y = 0.35, z = 0.05, r = 0.02, h = 1e-3;
    const double e = panelRadiance(y, z);
    const double laplacian = (panelRadiance(y + h, z) + panelRadiance(y - h, z) + panelRadiance(y, z + h) +
                              panelRadiance(y, z - h) - 4 * e) / (h * h);
    EXPECT_NEAR(discMeanRadiance(y, z, r), e + r * r / 8 * laplacian, 1e-5 * e);
    // Half a disc beyond the bottom edge (nearly constant E): about half the light.
    EXPECT_NEAR(discMeanRadiance(K.panelY0, 0.0, 1e-4) / panelRadiance(K.panelY0, 0.0), 0.5, 1e-3);
}

// ---- methods that cannot sample the path -------------------------------------------------------

// The wall mirror fills the view, and everything seen in it is the panel (L S D S E), the hood
// (black), the floor mirror showing the panel (L S D S S E) or nothing: every pixel is exactly 0
// for pt, lt and bdpt, however many samples.
TEST(SdsMirrors, PtLtBdptAreBlackThroughTheWallMirror) {
    const Scene scene(builtinScene("sds-mirrors"), kSize, kSize);
    for (const char* integrator : {"pt", "lt", "bdpt"}) {
        Image img;
        renderRegions(scene, integrator, {}, 11, 64, {}, {}, &img);
        int nonzero = 0;
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                for (int c = 0; c < 3; ++c) nonzero += img.at(x, y)[c] != 0.0f;
        EXPECT_EQ(nonzero, 0) << integrator << " sampled L S D S E (or light that should not be there)";
    }
}

// Seen directly the panel is the caustic L S D E: lt and bdpt sample it (t = 1) without bias and
// must match the closed form (without the wall mirror's R2); pt cannot (the shadow ray toward the
// light hits the hood; no walk hits a point) and is exactly 0 on the panel.
TEST(SdsMirrors, LtAndBdptSeeThePanelDirectlyAsTheClosedFormSays) {
    const SceneDesc desc = directView();
    const Scene scene(desc, kSize, kSize);
    const Pinhole cam(desc.camera, kSize, kSize);
    const Region panel = selectPixels(cam, directly, K.panelY0 + 0.01, K.panelY1 - 0.01, K.panelHalfZ - 0.01);
    ASSERT_GE(panel.pixels.size(), 200u);
    const double exact = exactMean(panel, 1.0);
    const char* integrators[] = {"lt", "bdpt"};
    for (int k = 0; k < 2; ++k) {
        const char* integrator = integrators[k];
        std::vector<double> runs;
        for (int i = 0; i < kRuns; ++i)
            runs.push_back(renderRegions(scene, integrator, {}, 100 * (k + 1) + i, 32, {32}, {&panel})[0][0]);
        const auto m = test::meanAndError(runs);
        std::cout << integrator << ", panel seen directly (" << panel.pixels.size() << " pixels, " << kRuns
                  << " runs x 32 passes): " << m.mean << " ± " << m.stderr_ << ", closed form " << exact << " ("
                  << percent(m.mean / exact - 1) << ")\n";
        EXPECT_LT(std::abs(m.mean - exact), kZ * m.stderr_) << integrator;
    }
    Image img;
    renderRegions(scene, "pt", {}, 100, 16, {}, {}, &img);
    EXPECT_EQ(regionMean(img, panel), 0.0) << "pt sampled a caustic from a point light";
}

// ---- vertex merging through the wall mirror --------------------------------------------------

struct Measured {
    test::MeanError m;
    double expected = 0;  // the closed form disc-averaged over the radii used
    double exact = 0;     // the closed form
};

// ppm, bpm and vcm through the wall mirror with a shrinking radius (r_1 = 6 cm, α = 0.5, so
// r_128 = 1.8 cm): at 32 and 128 passes the region means must agree with their expected values
// (the closed form disc-averaged over the passes' radii); the bias, large along the bottom edge,
// must fall from 32 to 128 passes, and the error of the interior with it.
TEST(SdsMirrors, MergingConvergesToTheClosedForm) {
    const SceneDesc desc = builtinScene("sds-mirrors");
    const Scene scene(desc, kSize, kSize);
    const Pinhole cam(desc.camera, kSize, kSize);
    const Region inner = interior(cam), band = bottomBand(cam);
    constexpr int kPasses = 128;
    const MergeSettings merge{.radius = kMaxRadius, .alpha = 0.5f};
    const std::vector<int> at = {8, 32, kPasses};
    const double scale = K.wallReflectance;
    const auto innerExpected = expectedMeans(inner, scale, merge.radius, merge.alpha, kPasses);
    const auto bandExpected = expectedMeans(band, scale, merge.radius, merge.alpha, kPasses);
    const double innerExact = exactMean(inner, scale), bandExact = exactMean(band, scale);

    double squaredN = 0, squared4N = 0;  // relative errors of single runs, interior, pooled
    const char* integrators[] = {"ppm", "bpm", "vcm"};
    for (int k = 0; k < 3; ++k) {
        std::vector<std::vector<double>> innerRuns(at.size()), bandRuns(at.size());
        for (int i = 0; i < kRuns; ++i) {
            const auto out = renderRegions(scene, integrators[k], merge, 1000 * (k + 1) + i, kPasses, at, {&inner, &band});
            for (size_t c = 0; c < at.size(); ++c) {
                innerRuns[c].push_back(out[c][0]);
                bandRuns[c].push_back(out[c][1]);
            }
            squaredN += std::pow(out[1][0] / innerExact - 1, 2);
            squared4N += std::pow(out[2][0] / innerExact - 1, 2);
        }
        std::vector<Measured> innerAt, bandAt;
        for (size_t c = 0; c < at.size(); ++c) {
            innerAt.push_back({test::meanAndError(innerRuns[c]), innerExpected[at[c]], innerExact});
            bandAt.push_back({test::meanAndError(bandRuns[c]), bandExpected[at[c]], bandExact});
            for (const auto& [name, x] : {std::pair{"interior", innerAt.back()}, std::pair{"bottom band", bandAt.back()}})
                std::cout << integrators[k] << ", " << at[c] << " passes, " << name << ": " << x.m.mean << " ± "
                          << x.m.stderr_ << " (" << percent(x.m.stderr_ / x.exact, false) << " s.e.); closed form " << x.exact
                          << ", error " << percent(x.m.mean / x.exact - 1) << "; expected bias "
                          << percent(x.expected / x.exact - 1) << "\n";
        }
        for (size_t c = 1; c < at.size(); ++c) {
            EXPECT_LT(std::abs(innerAt[c].m.mean - innerAt[c].expected), kZ * innerAt[c].m.stderr_)
                << integrators[k] << ", interior, " << at[c] << " passes";
            EXPECT_LT(std::abs(bandAt[c].m.mean - bandAt[c].expected), kZ * bandAt[c].m.stderr_)
                << integrators[k] << ", bottom band, " << at[c] << " passes";
        }
        // The final answer: the closed form within the statistical error plus the bias that the
        // disc averaging predicts for these radii (asserted above to match what was measured).
        const Measured& last = innerAt.back();
        EXPECT_LT(std::abs(last.m.mean - last.exact), kZ * last.m.stderr_ + std::abs(last.expected - last.exact))
            << integrators[k];
        // Along the edge the error is the bias, many standard errors large at 32 passes, and the
        // shrinking radius takes it down by 128.
        EXPECT_GT(std::abs(bandAt[1].m.mean - bandExact), 5 * bandAt[1].m.stderr_) << integrators[k];
        EXPECT_LT(std::abs(bandAt[2].m.mean - bandExact), 0.8 * std::abs(bandAt[1].m.mean - bandExact)) << integrators[k];
    }
    const double rmsN = std::sqrt(squaredN / (3 * kRuns)), rms4N = std::sqrt(squared4N / (3 * kRuns));
    std::cout << "interior, rms relative error of one run (3 methods x " << kRuns << " runs): " << at[1]
              << " passes " << percent(rmsN, false) << ", " << at[2] << " passes " << percent(rms4N, false) << "\n";
    EXPECT_LT(rms4N, 0.8 * rmsN);
}

// The density estimate's bias against the radius, at a fixed radius (α = 1): along the bottom
// edge, where the discs reach over the edge, it is of order r; the measured bias must be what the
// disc-averaged closed form predicts at r = 6 cm and at 3 cm, and halving r must take it down.
TEST(SdsMirrors, MergeBiasShrinksWithTheRadius) {
    const SceneDesc desc = builtinScene("sds-mirrors");
    const Scene scene(desc, kSize, kSize);
    const Pinhole cam(desc.camera, kSize, kSize);
    const Region inner = interior(cam), band = bottomBand(cam);
    const double scale = K.wallReflectance;
    const double innerExact = exactMean(inner, scale), bandExact = exactMean(band, scale);
    std::vector<double> bandBias;
    for (double radius : {kMaxRadius, kMaxRadius / 2}) {
        const MergeSettings merge{.radius = float(radius), .alpha = 1.0f};
        std::vector<double> innerRuns, bandRuns;
        for (int i = 0; i < kRuns; ++i) {
            const auto out = renderRegions(scene, "ppm", merge, 5000 + i, 64, {64}, {&inner, &band});
            innerRuns.push_back(out[0][0]);
            bandRuns.push_back(out[0][1]);
        }
        const auto in = test::meanAndError(innerRuns), edge = test::meanAndError(bandRuns);
        const double innerExpected = expectedMeans(inner, scale, radius, 1.0, 1)[1];
        const double bandExpected = expectedMeans(band, scale, radius, 1.0, 1)[1];
        std::cout << "ppm, radius " << radius << ": bottom band bias " << percent(edge.mean / bandExact - 1) << " ± "
                  << percent(edge.stderr_ / bandExact, false) << " (predicted " << percent(bandExpected / bandExact - 1)
                  << "), interior " << percent(in.mean / innerExact - 1) << " ± " << percent(in.stderr_ / innerExact, false)
                  << " (predicted " << percent(innerExpected / innerExact - 1) << ")\n";
        EXPECT_LT(std::abs(edge.mean - bandExpected), kZ * edge.stderr_) << "radius " << radius;
        EXPECT_LT(std::abs(in.mean - innerExpected), kZ * in.stderr_) << "radius " << radius;
        bandBias.push_back(edge.mean - bandExact);
        if (radius == kMaxRadius) {
            EXPECT_GT(std::abs(bandBias.back()), 5 * edge.stderr_);
        }
    }
    EXPECT_LT(std::abs(bandBias[1]), 0.65 * std::abs(bandBias[0]));
}

// The shipped copy, scenes/sds-mirrors.gltf, is checked with the other failure scenes'
// (GltfExport.ShippedCopiesMatchTheBuiltins).

}  // namespace
}  // namespace tripath
