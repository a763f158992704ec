// Light from infinitely far away and the punctual lights, against exact answers: the map's
// convention and sampling density, a convex Lambertian object under a constant sky and a tilted
// plane under a map (albedo/π · ∫ L(ω) max(0, n·ω) dω, integrated from the texels here), and a
// plane under a directional light and a spot (albedo/π · (E cos θ + I t² cos θ′ / r²)), for every
// integrator that can sample the light.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "geometry/emitters.h"
#include "geometry/environment.h"
#include "integrators/integrator.h"
#include "requests/environment_spec.h"
#include "scenes/scene_builder.h"
#include "support.h"
#include "test_scenes.h"

namespace tripath {
namespace {

using test::meanAndError;

// Every integrator the renderer has.
const std::vector<std::string>& kAllIntegrators = kIntegratorNames;

// The direction of the map's (u, v), by the convention's definition read backwards: φ = 2π(u − ½)
// from −Z toward +X, θ = πv from +Y.
Vec3 directionOfUv(double u, double v) {
    const double phi = 2 * M_PI * (u - 0.5), theta = M_PI * v;
    return Vec3(float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)), float(-std::sin(theta) * std::cos(phi)));
}

Environment environmentOf(const EnvironmentDesc& d) { return Environment(d.width, d.height, d.texels); }

// The convention of geometry/environment.h, exactly: −Z reads u = 0.5 (the middle column), +X
// u = 0.75, +Y the top row, and a texel is read by the directions inside it. A map read with u
// mirrored (atan2 of −x), v from the bottom, or a quarter turn off would read another texel.
TEST(Environment, DirectionsReadTheTexelsOfTheLatitudeLongitudeConvention) {
    const auto near = [](Vec2 a, double u, double v) { return std::abs(a.x - u) < 1e-6 && std::abs(a.y - v) < 1e-6; };
    EXPECT_TRUE(near(Environment::uvOf({0, 0, -1}), 0.5, 0.5));
    EXPECT_TRUE(near(Environment::uvOf({1, 0, 0}), 0.75, 0.5));
    EXPECT_TRUE(near(Environment::uvOf({-1, 0, 0}), 0.25, 0.5));
    EXPECT_NEAR(Environment::uvOf({0, 1, 0}).y, 0.0, 1e-6);  // the pole: any column
    EXPECT_NEAR(Environment::uvOf({0, -1, 0}).y, 1.0, 1e-6);
    const EnvironmentDesc sky = test::testSky();
    const Environment env = environmentOf(sky);
    for (int r = 0; r < sky.height; ++r)
        for (int c = 0; c < sky.width; ++c) {
            const Vec3 d = directionOfUv((c + 0.3) / sky.width, (r + 0.6) / sky.height);
            EXPECT_TRUE(env.radiance(d) == sky.texels[size_t(r * sky.width + c)]) << "texel " << c << ", " << r;
        }
}

// The sampling density integrates to 1 over the sphere, and L/p is constant inside a texel: so the
// mean of luminance(L)/p over samples is ∫ luminance(L) dω to rounding, and that integral is the
// texels' luminance times their solid angles, summed here from the definition. A density without
// the sin θ of the parameterisation, or a pdf of another texel than the one sampled, fails both.
TEST(Environment, TheSamplingDensityIsNormalisedAndProportionalToTheTexelsPower) {
    const EnvironmentDesc sky = test::testSky();
    const Environment env = environmentOf(sky);
    double integral = 0, pdfIntegral = 0;
    constexpr int kSub = 16;
    for (int r = 0; r < sky.height; ++r)
        for (int c = 0; c < sky.width; ++c) {
            const double c0 = std::cos(M_PI * r / sky.height), c1 = std::cos(M_PI * (r + 1) / sky.height);
            const double omega = 2 * M_PI / sky.width * (c0 - c1);
            integral += luminance(sky.texels[size_t(r * sky.width + c)]) * omega;
            for (int i = 0; i < kSub; ++i)  // the density's integral over the texel, by the midpoint rule in (φ, cos θ)
                for (int j = 0; j < kSub; ++j) {
                    const double u = (c + (i + 0.5) / kSub) / sky.width;
                    const double cosTheta = c0 + (c1 - c0) * (j + 0.5) / kSub;
                    pdfIntegral += env.pdf(directionOfUv(u, std::acos(cosTheta) / M_PI)) * omega / (kSub * kSub);
                }
        }
    EXPECT_NEAR(env.luminanceIntegral(), integral, 1e-6 * integral);  // the map keeps cos θ of its rows in float
    EXPECT_NEAR(pdfIntegral, 1.0, 1e-4);
    Rng rng(3, uint64_t(StreamDomain::Test), 0);
    double estimate = 0;
    constexpr int kSamples = 20000;
    for (int i = 0; i < kSamples; ++i) {
        const float a = rng.uniform();
        const EnvironmentSample s = env.sample({a, rng.uniform()});
        EXPECT_NEAR(s.pdf, env.pdf(s.direction), 1e-3 * s.pdf);
        estimate += luminance(env.radiance(s.direction)) / env.pdf(s.direction);
    }
    EXPECT_NEAR(estimate / kSamples, integral, 1e-4 * integral);
}

// The one-line refusals of a bad environment, and a constant's parsing.
TEST(Environment, BadSpecificationsAreRefusedInOneLine) {
    const EnvironmentDesc constant = loadEnvironment(" 1, 0.5 ,0.25", 2.0f);
    ASSERT_EQ(constant.texels.size(), 1u);
    EXPECT_TRUE(constant.texels[0] == Spectrum(2.0f, 1.0f, 0.5f));
    for (const char* bad : {"1,-1,1", "1,nan,1", "/nonexistent/sky.exr"}) {
        try {
            loadEnvironment(bad, 1.0f);
            ADD_FAILURE() << bad << " was accepted";
        } catch (const InputError& e) {
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(loadEnvironment("1,1,1", -1.0f), InputError);
}

// A scene of one object under the sky alone, seen by a 32 × 32 camera from `from`.
SceneDesc underTheSky(SceneDesc s, EnvironmentDesc sky, Vec3 from, Vec3 at) {
    s.environment = std::move(sky);
    s.camera = build::lookAt(from, at, 0.5f);
    return s;
}

// The mean over `runs` runs of a block's channel average in a 32 × 32 image (by default the
// centre 12 × 12 pixels), for one integrator.
test::MeanError blockOf(const Scene& scene, const std::string& integrator, int spp, int runs, test::Block block = {10, 10, 12, 12}) {
    RenderRequest r = test::smallRequest();
    r.integrator = integrator;
    r.width = r.height = 32;
    r.spp = spp;
    r.maxDepth = 8;
    return meanAndError(test::blockRuns(scene, r, runs, 1, {block}, average)[0]);
}

// A convex Lambertian box under a constant sky L sees the sky alone, over a whole hemisphere at
// every point: it reads albedo × L exactly, in every integrator (each strategy of the sky: rays
// that escape, next-event estimation of the map, light paths from the bounding disc, merges).
// Catches a disc pdf off by its cosine, a solid-angle pdf converted with an r² that is not there, or
// light subpaths aimed past the scene.
TEST(Environment, AConvexLambertianObjectUnderAConstantSkyReadsAlbedoTimesL) {
    SceneDesc box;
    const int grey = build::addMaterial(box, build::lambertian("grey", Spectrum(0.5f)));
    build::addBox(box, "box", grey, {-0.5f, -0.5f, -0.5f}, {0.5f, 0.5f, 0.5f}, 0.5f);
    EnvironmentDesc sky;
    sky.width = sky.height = 1;
    sky.texels = {Spectrum(1.0f, 0.5f, 0.25f)};
    const Scene scene(underTheSky(box, sky, {1.5f, 1.2f, 2.0f}, {0, 0, 0}), 32, 32);
    const double expected = 0.5 * (1.0 + 0.5 + 0.25) / 3;
    for (const std::string& integrator : kAllIntegrators) {
        const auto m = blockOf(scene, integrator, 32, 8);
        EXPECT_NEAR(m.mean, expected, 4 * m.stderr_ + 1e-6) << integrator;
        EXPECT_LT(m.stderr_, 0.02 * expected) << integrator << ": too noisy for the test to mean anything";
    }
}

// A scene whose only light would be an environment that is black everywhere is refused with a
// line that says so, rather than being told to add the environment it has.
TEST(Environment, AnAllBlackEnvironmentAsTheOnlyLightIsRefusedAsBlack) {
    SceneDesc box;
    build::addBox(box, "box", build::addMaterial(box, build::lambertian("grey", Spectrum(0.5f))), {-0.5f, -0.5f, -0.5f},
                  {0.5f, 0.5f, 0.5f});
    box.environment.width = box.environment.height = 1;
    box.environment.texels = {Spectrum(0.0f)};
    try {
        const Scene scene(box, 8, 8);
        ADD_FAILURE() << "a scene lit by a black environment alone was accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("environment, which is black everywhere"), std::string::npos) << e.what();
    }
}

// A wide camera that sees nothing but the sky (the scene's one box lies behind it) reads L in every
// pixel, in every integrator: light tracing too, through strategy (1, 1), a direction drawn from the
// map joined to the pinhole, which lands in the pixel that looks that way. Catches the sensor's
// importance or pixel density misread for a direction at infinity, or that strategy's MIS weight
// against the camera rays that escape (bdpt, vcm).
TEST(Environment, ACameraThatSeesOnlyTheSkyReadsItsRadiance) {
    SceneDesc s;
    build::addBox(s, "box behind", build::addMaterial(s, build::lambertian("grey", Spectrum(0.5f))), {-0.1f, -0.1f, 2.0f},
                  {0.1f, 0.1f, 2.2f});
    EnvironmentDesc sky;
    sky.width = sky.height = 1;
    sky.texels = {Spectrum(0.5f, 1.0f, 2.0f)};
    s.environment = sky;
    s.camera = CameraDesc{true, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 2.4f};
    const Scene scene(s, 32, 32);
    for (const std::string& integrator : kAllIntegrators) {
        const auto m = blockOf(scene, integrator, 8, 8, {0, 0, 32, 32});
        EXPECT_NEAR(m.mean, 3.5 / 3, 4 * m.stderr_ + 1e-6) << integrator;
        EXPECT_LT(m.stderr_, 0.02) << integrator << ": too noisy for the test to mean anything";
    }
}

// A tilted Lambertian plane under the test sky reads albedo/π · ∫ L(ω) max(0, n·ω) dω: the
// integral taken here texel by texel (the map is piecewise constant), by the midpoint rule in
// (φ, cos θ) inside each. The sky's colours vary across the map and its sun is off the axes, so
// a mirrored or shifted u or v, or a sun sampled where it is not, changes the answer.
TEST(Environment, ATiltedPlaneUnderAMapReadsTheCosineWeightedIntegralOfItsTexels) {
    const Vec3 n = normalize(Vec3(0.6f, 1.0f, 0.3f));
    const float albedo = 0.7f;
    SceneDesc plane;
    build::addSquare(plane, "plane", build::addMaterial(plane, build::lambertian("plane", Spectrum(albedo))), {0, 0, 0}, n, 1.0f);
    const EnvironmentDesc sky = test::testSky();
    const Scene scene(underTheSky(plane, sky, n * 3.0f + Vec3(0.01f, 0, 0), {0, 0, 0}), 32, 32);
    double irradiance = 0;  // of the channel average
    constexpr int kSub = 32;
    for (int r = 0; r < sky.height; ++r)
        for (int c = 0; c < sky.width; ++c) {
            const double c0 = std::cos(M_PI * r / sky.height), c1 = std::cos(M_PI * (r + 1) / sky.height);
            const double cell = 2 * M_PI / sky.width * (c0 - c1) / (kSub * kSub);
            double projected = 0;
            for (int i = 0; i < kSub; ++i)
                for (int j = 0; j < kSub; ++j) {
                    const double cosTheta = c0 + (c1 - c0) * (j + 0.5) / kSub;
                    const Vec3 w = directionOfUv((c + (i + 0.5) / kSub) / sky.width, std::acos(cosTheta) / M_PI);
                    projected += std::max(0.0f, dot(n, w)) * cell;
                }
            irradiance += average(sky.texels[size_t(r * sky.width + c)]) * projected;
        }
    const double expected = albedo / M_PI * irradiance;
    for (const std::string& integrator : kAllIntegrators) {
        // mlt's chains cross the sun's few texels in correlated runs: more steps for the same error.
        const auto m = blockOf(scene, integrator, integrator == "mlt" ? 64 : 16, 8);
        EXPECT_NEAR(m.mean, expected, 4 * m.stderr_ + 1e-4 * expected) << integrator;
        EXPECT_LT(m.stderr_, 0.02 * expected) << integrator << ": too noisy for the test to mean anything";
    }
}

// Emitters are chosen in proportion to their power: a spot's I ∫ t² dω (integrated here over its
// cone by the midpoint rule), a directional light's π R² E and a constant sky's π R² · 4π L, for
// the bounding sphere's radius R. Catches a spot counted as a point light, or its falloff ring
// counted whole, and a light at infinity weighed without the disc it lights.
TEST(PunctualLights, EmittersAreChosenInProportionToTheirPower) {
    const float R = 3.0f, I = 5.0f, E = 0.5f, L = 0.25f, cosInner = std::cos(0.3f), cosOuter = std::cos(0.6f);
    Emitter spot;
    spot.kind = Emitter::Kind::Spot;
    spot.axis = {0, -1, 0};
    spot.radiance = Spectrum(I);
    spot.cosInner = cosInner;
    spot.cosOuter = cosOuter;
    Emitter sun;
    sun.kind = Emitter::Kind::Directional;
    sun.axis = {0, 1, 0};
    sun.radiance = Spectrum(E);
    const auto sky = std::make_shared<const Environment>(1, 1, std::vector<Spectrum>{Spectrum(L)});
    const Emitters emitters({}, {}, {spot, sun}, sky, BoundingSphere{{0, 0, 0}, R});
    double spotPower = 0;
    constexpr int kSteps = 100000;
    for (int i = 0; i < kSteps; ++i) {  // ∫ t(cos θ)² 2π d(cos θ) over [cos θ_outer, 1]
        const double c = cosOuter + (1.0 - cosOuter) * (i + 0.5) / kSteps;
        const double t = std::clamp((c - cosOuter) / (cosInner - cosOuter), 0.0, 1.0);
        spotPower += I * t * t * 2 * M_PI * (1.0 - cosOuter) / kSteps;
    }
    const double sunPower = M_PI * R * R * E, skyPower = M_PI * R * R * 4 * M_PI * L;
    const double total = spotPower + sunPower + skyPower;
    ASSERT_EQ(emitters.all().size(), 3u);
    EXPECT_NEAR(emitters.pdfA(0, {}), spotPower / total, 1e-5);
    EXPECT_NEAR(emitters.pdfA(1, {}), sunPower / total, 1e-5);
    EXPECT_NEAR(emitters.pdfA(2, {0, 1, 0}) / sky->pdf({0, 1, 0}), skyPower / total, 1e-5);
}

// A Lambertian floor (y = 0, albedo a) under a directional light of irradiance E along d and a spot
// of intensity I at height 1 shining straight down: the floor reads
//     a/π · (E |d_y| + I t(θ′)² cos θ′ / r²),   t = clamp((cos θ′ − cos θ_o) / (cos θ_i − cos θ_o), 0, 1),
// (θ′ the angle at the spot, equal to the floor's angle of incidence), averaged here over each
// 8 × 8 block of pixels by tracing 4 × 4 rays a pixel to the floor. Catches E taken as radiance,
// a spot's falloff linear in t or in the angle, its axis along +Z, or its light sampled outside its
// cone. The merging integrators are held to the blocks the spot does not reach (their density
// estimate blurs its edge by the radius); the others to every block.
TEST(PunctualLights, AFloorUnderADirectionalLightAndASpotReadsTheClosedForm) {
    const float albedo = 0.8f, E = 0.5f, I = 20.0f, inner = 0.2f, outer = 0.4f;
    const Vec3 d = normalize(Vec3(0.3f, -1.0f, 0.2f)), spotAt(0, 1, 0);
    SceneDesc s;
    build::addSquare(s, "floor", build::addMaterial(s, build::lambertian("floor", Spectrum(albedo))), {0, 0, 0}, {0, 1, 0}, 3.0f);
    LightDesc sun;
    sun.kind = LightDesc::Kind::Directional;
    sun.direction = d;
    sun.intensity = Spectrum(E);
    LightDesc spot;
    spot.kind = LightDesc::Kind::Spot;
    spot.position = spotAt;
    spot.direction = {0, -1, 0};
    spot.intensity = Spectrum(I);
    spot.innerConeAngle = inner;
    spot.outerConeAngle = outer;
    s.lights = {sun, spot};
    // Above the spot and looking past it, so that no pixel sees the spot itself (light tracing would
    // splat its point there).
    s.camera = build::lookAt({0, 1.5f, 1.2f}, {0, 0, -0.2f}, 0.6f);
    const Scene scene(s, 32, 32);
    auto exact = [&](Vec3 p) {
        const Vec3 toSpot = spotAt - p;
        const float r2 = lengthSquared(toSpot), cosine = toSpot.y / std::sqrt(r2);
        const float t = std::clamp((cosine - std::cos(outer)) / (std::cos(inner) - std::cos(outer)), 0.0f, 1.0f);
        return albedo / kPi * (E * std::abs(d.y) + I * t * t * cosine / r2);
    };
    const std::vector<test::Block> blocks = test::blockGrid(32, 32, 4, 4);
    std::vector<double> expected;
    std::vector<bool> spotReaches;
    for (const test::Block& b : blocks) {
        double sum = 0;
        bool reaches = false;
        for (int y = b.y; y < b.y + b.h; ++y)
            for (int x = b.x; x < b.x + b.w; ++x)
                for (int i = 0; i < 16; ++i) {
                    const Vec3 dir = scene.camera().direction({x + (i % 4 + 0.5f) / 4, y + (i / 4 + 0.5f) / 4});
                    const Vec3 p = scene.camera().position() + dir * (-scene.camera().position().y / dir.y);
                    sum += exact(p) / 16;
                    reaches = reaches || std::acos(normalize(spotAt - p).y) < outer + 0.1f;
                }
        expected.push_back(sum / (b.w * b.h));
        spotReaches.push_back(reaches);
    }
    int spotBlocks = 0;
    for (bool r : spotReaches) spotBlocks += r;
    ASSERT_GE(spotBlocks, 3) << "the camera must see the spot's pool of light";
    ASSERT_LE(spotBlocks, 13) << "and the floor beyond it (" << spotBlocks << " blocks in the pool)";
    for (const std::string& integrator : kAllIntegrators) {
        RenderRequest r = test::smallRequest();
        r.integrator = integrator;
        r.width = r.height = 32;
        const bool merges = makeIntegrator(integrator, {})->strategies().merges();
        // Light tracing and photon density estimates need more passes for the same error, and
        // mlt's correlated chains more steps still.
        r.spp = integrator == "pt" || integrator == "bdpt" ? 64 : integrator == "mlt" ? 1024 : 256;
        r.maxDepth = 2;  // the floor, lit directly: nothing else reflects
        const test::BlockRuns runs = test::blockRuns(scene, r, 8, 1, blocks, average);
        for (size_t k = 0; k < blocks.size(); ++k) {
            if (merges && spotReaches[k]) continue;
            const auto m = meanAndError(runs[k]);
            EXPECT_NEAR(m.mean, expected[k], 4 * m.stderr_ + 1e-4 * expected[k]) << integrator << " block " << k;
            EXPECT_LT(m.stderr_, 0.04 * expected[k]) << integrator << " block " << k << ": too noisy to mean anything";
        }
    }
}

}  // namespace
}  // namespace tripath
