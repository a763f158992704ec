// The kernels of the three-point form (tests/oracle.h) at hand-made points, against values
// worked out by hand from the definitions in docs/design.md §1 -- not from the code's own formulas:
//   ε(x0 → x1)      = Le · |cos θ0| · |cos θ1|   (cosines of the segment x0–x1 at both ends)
//   ρ(x″ → x′ → x)  = f_r · |cos θ′| · |cos θ|   (cosines of the OUTGOING segment x′–x), f_r = R/π
//   G(x, x′)        = |cos θ| |cos θ′| / r²      g(x, x′) = V / r²
//
// The scene, built here with scene_builder:
//   light     square of half-size 0.25 centred at (0, 2, 0), facing down (0, −1, 0), one-sided,
//             Le = (4, 2, 1)
//   floor     y = 0, facing up, Lambertian R = (0.6, 0.4, 0.2)
//   wall      x = 3, facing −x
//   ceiling   y = 3, facing down (above the light, which does not emit upwards)
//   occluder  square at y = 1 over x ∈ [−1.5, −0.5], z ∈ [−0.5, 0.5]
// and the points
//   L = (0, 2, 0) on the light, n = (0, −1, 0)     F = (1, 0, 0) on the floor, n = (0, 1, 0)
//   W = (3, 1, 0) on the wall,  n = (−1, 0, 0)     C = (0.5, 3, 0) on the ceiling, n = (0, −1, 0)
//   S = (−2, 0, 0) on the floor, hidden from L by the occluder (the segment crosses y = 1 at x = −1)
//   B = (2, −1, 0), a point below the floor's plane
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include "geometry/scene.h"
#include "scenes/scene_builder.h"
#include "oracle.h"

namespace tripath {
namespace {

using namespace build;

constexpr double kPiD = std::numbers::pi;
const Spectrum kLe(4.0f, 2.0f, 1.0f);
const Spectrum kFloorAlbedo(0.6f, 0.4f, 0.2f);

struct KernelScene {
    std::unique_ptr<Scene> scene;
    int floorMaterial = 0;
};

KernelScene makeKernelScene() {
    SceneDesc d;
    d.name = "kernels";
    const int floor = addMaterial(d, lambertian("floor", kFloorAlbedo));
    const int grey = addMaterial(d, lambertian("grey", Spectrum(0.5f)));
    const int light = addMaterial(d, emitter("light", kLe));
    addSquare(d, "floor", floor, {0, 0, 0}, {0, 1, 0}, 3.0f);
    addSquare(d, "wall", grey, {3, 1.5f, 0}, {-1, 0, 0}, 1.5f);
    addSquare(d, "ceiling", grey, {0, 3, 0}, {0, -1, 0}, 3.0f);
    addSquare(d, "occluder", grey, {-1, 1, 0}, {0, 1, 0}, 0.5f);
    addSquare(d, "light", light, {0, 2, 0}, {0, -1, 0}, 0.25f);
    d.camera = lookAt({0, 1.5f, 8}, {0, 1, 0}, 0.8f);
    return {std::make_unique<Scene>(d, 4, 4, [](const std::string&) {}), floor};
}

Vertex surfacePoint(const Scene& scene, int material, Vec3 p, Vec3 n) {
    Vertex v;
    v.kind = Vertex::Kind::Surface;
    v.p = p;
    v.ng = v.ns = n;
    v.material = &scene.materials()[material];
    return v;
}

Vertex lightPoint(const Scene& scene) {
    Vertex v;
    v.kind = Vertex::Kind::Emitter;
    v.p = {0, 2, 0};
    v.ng = v.ns = {0, -1, 0};
    v.emitter = 0;  // the light's two triangles are the only emitters, both of radiance Le
    EXPECT_EQ(scene.emitters().all().size(), 2u);
    return v;
}

void expectSpectrum(Spectrum got, double r, double g, double b, const char* what) {
    const double want[3] = {r, g, b};
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-5 * std::abs(want[c]) + 1e-9) << what << " channel " << c;
}

class Kernels : public ::testing::Test {
protected:
    KernelScene ks = makeKernelScene();
    const Scene& scene = *ks.scene;
    const Vertex L = lightPoint(scene);
    const Vertex F = surfacePoint(scene, ks.floorMaterial, {1, 0, 0}, {0, 1, 0});
    const Vertex W = surfacePoint(scene, 1, {3, 1, 0}, {-1, 0, 0});
    const Vertex C = surfacePoint(scene, 1, {0.5f, 3, 0}, {0, -1, 0});
    const Vertex S = surfacePoint(scene, ks.floorMaterial, {-2, 0, 0}, {0, 1, 0});
    const Vertex B = surfacePoint(scene, 1, {2, -1, 0}, {0, 1, 0});
};

// L → W: d = (3, −1, 0), r² = 10; cos θ_L = |(0,−1,0)·d|/√10 = 1/√10, cos θ_W = |(−1,0,0)·d|/√10
// = 3/√10, so ε = Le · 3/10 = (1.2, 0.6, 0.3).
// L → F: d = (1, −2, 0), r² = 5; both cosines 2/√5, so ε = Le · 4/5 = (3.2, 1.6, 0.8).
// Catches: a cosine left out (Le·3/√10 or Le·1/√10), one end's cosine used twice (Le/10 or
// Le·9/10), the cosines taken against the wrong normal, 1/r² folded into ε (Le·3/100).
TEST_F(Kernels, EmittanceIsLeTimesTheCosinesAtBothEnds) {
    expectSpectrum(emittance(scene, L, W), 1.2, 0.6, 0.3, "ε(L→W)");
    expectSpectrum(emittance(scene, L, F), 3.2, 1.6, 0.8, "ε(L→F)");
}

// C lies above the light, which emits only downwards: ε(L → C) = 0. Catches a one-sided emitter
// made two-sided (Le taken with |cos| on both faces).
TEST_F(Kernels, OneSidedEmitterSendsNothingBehindIt) { expectSpectrum(emittance(scene, L, C), 0, 0, 0, "ε(L→C)"); }

// ρ at F with the floor's Lambertian f_r = R/π, cosines of the OUTGOING segment:
//   ρ(L → F → W): F → W = (2, 1, 0), r² = 5, cos θ_F = 1/√5, cos θ_W = 2/√5: ρ = R/π · 2/5
//   ρ(W → F → L): F → L = (−1, 2, 0), r² = 5, cos θ_F = 2/√5, cos θ_L = 2/√5: ρ = R/π · 4/5
// Catches: the cosines of the incoming segment instead (the two values swap), f_r without the
// 1/π or as the albedo alone, a cosine missing (R/π · 2/5 · √5/2 …), channels mixed up.
TEST_F(Kernels, ReflectanceIsLambertTimesTheOutgoingSegmentsCosines) {
    const double r = 0.6 / kPiD, g = 0.4 / kPiD, b = 0.2 / kPiD;
    expectSpectrum(rho(scene, L, F, W), r * 0.4, g * 0.4, b * 0.4, "ρ(L→F→W)");
    expectSpectrum(rho(scene, W, F, L), r * 0.8, g * 0.8, b * 0.8, "ρ(W→F→L)");
}

// Light arriving at the floor from above cannot leave it below (B is under the floor's plane):
// an opaque Lambertian reflects only. Catches a BSDF evaluated with |cos| on both sides, which
// would give the floor transmission R/π · |cos||cos| = R/π · 1/√5 · 1/√5 ≠ 0.
TEST_F(Kernels, OpaqueSurfaceTransmitsNothing) { expectSpectrum(rho(scene, L, F, B), 0, 0, 0, "ρ(L→F→B)"); }

// G without visibility: G(L, W) = (1/√10)(3/√10)/10 = 0.03; G(L, F) = (2/√5)²/5 = 0.16;
// G(L, S) = (2/√8)²/8 = 1/16 (the occluder does not matter to G).
// g with visibility: g(L, W) = 1/10, g(L, F) = 1/5, and 0 both ways between L and S, which the
// occluder hides. Catches: g without 1/r² or with 1/r, visibility ignored (g(L,S) = 1/8), the
// shadow ray tested in one direction only or stopping short of its end, G with cos θ at one end.
TEST_F(Kernels, GeometryTermIsVisibilityOverDistanceSquared) {
    EXPECT_NEAR(geometricFactor(L, W).x, 0.03, 1e-7);
    EXPECT_NEAR(geometricFactor(W, L).x, 0.03, 1e-7);
    EXPECT_NEAR(geometricFactor(L, F).x, 0.16, 1e-7);
    EXPECT_NEAR(geometricFactor(L, S).x, 1.0 / 16, 1e-7);
    EXPECT_NEAR(g(scene, L, W).x, 0.1, 1e-7);
    EXPECT_NEAR(g(scene, W, L).x, 0.1, 1e-7);
    EXPECT_NEAR(g(scene, L, F).x, 0.2, 1e-7);
    EXPECT_NEAR(g(scene, F, W).x, 0.2, 1e-7);  // F → W: r² = 5, nothing between
    EXPECT_TRUE(isBlack(g(scene, L, S)));
    EXPECT_TRUE(isBlack(g(scene, S, L)));
}

}  // namespace
}  // namespace tripath
