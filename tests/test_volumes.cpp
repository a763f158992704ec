// Absorbing volumes (KHR_materials_volume: Material::absorption) against Beer–Lambert's law,
// exp(−σ_a d) over a length d inside the volume, in every integrator that can sample the light,
// and the glTF extension read as −ln(attenuationColor) / attenuationDistance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "io/gltf_loader.h"
#include "scenes/scene_builder.h"
#include "support.h"
#include "textured_scenes.h"

namespace tripath {
namespace {

// A camera looks through a slab of absorbing glass of index 1 (no Fresnel reflection, no
// refraction: light goes straight through it) at an emitting wall of radiance L behind it. Every
// pixel's path crosses the slab perpendicularly to within the camera's 2.3° field, over a length
// of d / cos θ with d = 1, so it reads L exp(−σ_a d / cos θ) (computed per pixel centre here).
// Catches transmittance left out of a walk's step or of a connection (the strategies then
// disagree, and the ones that omit it read L), applied twice, or along a segment outside.
TEST(Volumes, ASlabOfAbsorbingGlassTransmitsExpOfMinusSigmaD) {
    SceneDesc s;
    Material slab = build::glass("absorbing glass");
    slab.ior = 1.0f;
    const Spectrum sigma(0.5f, 1.0f, 2.0f);
    slab.absorption = sigma;
    build::addBox(s, "slab", build::addMaterial(s, slab), {-3, -3, -0.5f}, {3, 3, 0.5f});
    const Spectrum L(1.0f, 2.0f, 4.0f);
    build::addSquare(s, "wall", build::addMaterial(s, build::emitter("wall", L)), {0, 0, -2}, {0, 0, 1}, 4);
    s.camera = build::lookAt({0, 0, 3}, {0, 0, 0}, 0.08f);
    constexpr int kSize = 8;
    const Scene scene(s, kSize, kSize);
    double expected[3] = {0, 0, 0};  // the image's mean, by pixel centres
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const Vec3 d = scene.camera().direction({x + 0.5f, y + 0.5f});
            for (int c = 0; c < 3; ++c) expected[c] += L[c] * std::exp(-sigma[c] / std::abs(d.z)) / (kSize * kSize);
        }
    // Every path of a pixel carries the same value but for the pixel's spread of angles: one run
    // of pt, bdpt or vcm reads it to 0.2 %. mlt's image is scaled by its bootstrap's estimate of
    // the brightness, exact only over runs: its mean over 16 is held within 5 standard errors.
    for (const char* integrator : {"pt", "bdpt", "vcm", "mlt"}) {
        RenderRequest r = test::smallRequest();
        r.integrator = integrator;
        r.width = r.height = kSize;
        r.spp = 16;
        const bool chains = std::string(integrator) == "mlt";
        const std::vector<Image> images = test::renderRuns(scene, r, chains ? 16 : 1, 900);
        for (int c = 0; c < 3; ++c) {
            std::vector<double> means;
            for (const Image& img : images) means.push_back(test::blockMean(img, 0, 0, kSize, kSize, c));
            const test::MeanError m = test::meanAndError(means);
            EXPECT_NEAR(m.mean, expected[c], chains ? 5 * m.stderr_ : 2e-3 * expected[c]) << integrator << " channel " << c;
        }
    }
}

// KHR_materials_volume on a transmissive material: σ_a = −ln(attenuationColor) /
// attenuationDistance per channel; without a distance (infinite), none; on an opaque material,
// ignored with a warning naming it.
TEST(Volumes, TheExtensionGivesMinusLnColourOverDistance) {
    const auto dir = std::filesystem::temp_directory_path() / "tripath_volumes";
    std::filesystem::create_directories(dir);
    test::TexturedScene t;
    auto glassWith = [](nlohmann::json volume) {
        return nlohmann::json{{"pbrMetallicRoughness", {{"metallicFactor", 0}, {"roughnessFactor", 0}}},
                              {"extensions",
                               {{"KHR_materials_transmission", {{"transmissionFactor", 1}}},
                                {"KHR_materials_volume", std::move(volume)}}}};
    };
    const int tinted = t.addMaterial(glassWith({{"attenuationColor", {0.5, 0.25, 1.0}}, {"attenuationDistance", 2.0}}));
    const int clear = t.addMaterial(glassWith({{"attenuationColor", {0.5, 0.5, 0.5}}}));
    nlohmann::json opaque = {{"name", "opaque"},
                             {"extensions", {{"KHR_materials_volume", {{"attenuationDistance", 1.0}}}}}};
    const int ignored = t.addMaterial(opaque);
    for (int m : {tinted, clear, ignored}) t.addQuad({.z = float(m), .material = m});
    t.addGlowingBox(5, 1);
    std::vector<std::string> warnings;
    const SceneDesc desc = loadGltf(t.write(dir / "volume.gltf"), [&](const std::string& w) { warnings.push_back(w); });
    std::filesystem::remove_all(dir);
    EXPECT_NEAR(desc.materials[size_t(tinted)].absorption.x, std::log(2.0) / 2, 1e-6);
    EXPECT_NEAR(desc.materials[size_t(tinted)].absorption.y, std::log(4.0) / 2, 1e-6);
    EXPECT_EQ(desc.materials[size_t(tinted)].absorption.z, 0.0f);
    EXPECT_TRUE(isBlack(desc.materials[size_t(clear)].absorption));
    EXPECT_TRUE(isBlack(desc.materials[size_t(ignored)].absorption));
    bool warned = false;
    for (const std::string& w : warnings) warned = warned || (w.find("KHR_materials_volume without transmission") !=
                                                                   std::string::npos && w.find("opaque") != std::string::npos);
    EXPECT_TRUE(warned);
}

}  // namespace
}  // namespace tripath
