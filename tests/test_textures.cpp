// Textured glTF materials rendered: each test writes its own small scene and PNG textures
// (textured_scenes.h), loads it as a user's file would be loaded, and checks the image against
// what the texels say in closed form.
//
// Scenes: a quad filling the view exactly (the camera's frustum spans [−1, 1]² at z = 0), so that
// with a 4 × 4 nearest-filtered texture at 8 × 8 pixels each texel covers exactly 2 × 2 pixels;
// and, for reflection, a closed box whose inner faces emit L and reflect nothing, in which the
// radiance field is uniform: a surface of directional albedo ρ(ωo) seen inside it reads ρ(ωo) · L
// (for a Lambertian one, its albedo times L).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "io/gltf_loader.h"
#include "scenes/scene_builder.h"
#include "support.h"
#include "textured_scenes.h"

namespace tripath::test {
namespace {

namespace fs = std::filesystem;

constexpr int kSize = 8, kTexels = 4;

class Textures : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("tripath_textures_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path file(const std::string& name) const { return dir_ / name; }

    // The scene s describes, under `sky` if given (as --environment gives one).
    std::unique_ptr<Scene> load(TexturedScene& s, const EnvironmentDesc& sky = {}) {
        SceneDesc desc = loadGltf(s.write(file("scene.gltf")), [](const std::string&) {});
        desc.environment = sky;
        return std::make_unique<Scene>(desc, kSize, kSize);
    }
    fs::path dir_;
};

// A 4 × 4 RGBA texture whose texels all differ: texel (x, y) from the image's top-left.
std::vector<uint8_t> distinctTexels() {
    std::vector<uint8_t> bytes;
    for (int y = 0; y < kTexels; ++y)
        for (int x = 0; x < kTexels; ++x)
            bytes.insert(bytes.end(), {uint8_t(20 + 60 * x), uint8_t(30 + 70 * y), uint8_t(250 - 15 * (x + y)), 255});
    return bytes;
}

Spectrum decodedTexel(const std::vector<uint8_t>& bytes, int x, int y) {
    const size_t i = 4 * size_t(y * kTexels + x);
    return {srgbByteToLinear(bytes[i]), srgbByteToLinear(bytes[i + 1]), srgbByteToLinear(bytes[i + 2])};
}

nlohmann::json blackMaterial() {
    return {{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 1}}}};
}

// An emissive textured quad seen head-on reads emissiveFactor × strength × the decoded texel, pixel
// for pixel: a flipped u or v, a missing sRGB decoding or a factor not applied each move values.
TEST_F(Textures, EmissiveTextureIsSeenTexelForTexel) {
    const std::vector<uint8_t> texels = distinctTexels();
    writePng(file("glow.png"), kTexels, kTexels, 4, texels);
    TexturedScene s;
    nlohmann::json m = blackMaterial();
    const Spectrum factor(0.5f, 1.0f, 0.25f);
    const float strength = 4;
    m["emissiveFactor"] = {factor.x, factor.y, factor.z};
    m["emissiveTexture"] = {{"index", s.addTexture("glow.png")}};
    m["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", strength}}}};
    s.addQuad({.material = s.addMaterial(m)});
    s.setCamera(2);
    const auto scene = load(s);
    RenderRequest r = smallRequest();
    r.width = r.height = kSize;
    const Image img = renderScene(*scene, r).image();
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const Spectrum expected = factor * strength * decodedTexel(texels, x / 2, y / 2);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(img.at(x, y)[c], expected[c], 1e-5f * expected[c]) << x << "," << y;
        }
}

// A textured emitter is weighed by what it emits: of a quad whose texture is black but for its
// bottom-right texel, the triangle (−1,−1) (1,−1) (1,1) holding that texel is an emitter and the
// other, black wherever its texture is read, is none.
TEST_F(Textures, TrianglesOfABlackPartOfAnEmissiveTextureAreNoEmitters) {
    std::vector<uint8_t> texels(4 * kTexels * kTexels, 0);
    const size_t bottomRight = 4 * (kTexels * kTexels - 1);
    texels[bottomRight] = texels[bottomRight + 1] = texels[bottomRight + 2] = 255;
    for (int i = 3; i < int(texels.size()); i += 4) texels[size_t(i)] = 255;
    writePng(file("corner.png"), kTexels, kTexels, 4, texels);
    TexturedScene s;
    nlohmann::json m = blackMaterial();
    m["emissiveFactor"] = {1, 1, 1};
    m["emissiveTexture"] = {{"index", s.addTexture("corner.png")}};
    s.addQuad({.material = s.addMaterial(m)});
    s.setCamera(2);
    const auto scene = load(s);
    EXPECT_GE(scene->emitters().emitterOfTriangle(0), 0);
    EXPECT_EQ(scene->emitters().emitterOfTriangle(1), -1);
    EXPECT_EQ(scene->emitters().all().size(), 1u);
}

// A triangle whose emissive texture is black but for one texel that none of the power estimate's
// 256 points falls on still emits: it stays an emitter, so light tracing (which starts only from
// emitters) sees the quad as it is, the texel's pixel reading its radiance L (the quad fills a
// 64 × 64 image, a texel a pixel) and every other pixel 0. Catches an emitter dropped because its
// estimate found nothing (the file is then refused as having no emitter, or renders black).
TEST_F(Textures, OneBrightTexelBetweenThePowerEstimatesPointsStillEmits) {
    constexpr int kSide = 64, kX = 40, kY = 45;  // (40, 45) lies in triangle 0, u + v > 1
    std::vector<uint8_t> texels(3 * kSide * kSide, 0);
    for (int c = 0; c < 3; ++c) texels[size_t(3 * (kY * kSide + kX) + c)] = 255;
    writePng(file("dot.png"), kSide, kSide, 3, texels);
    TexturedScene s;
    nlohmann::json m = blackMaterial();
    const float L = 8;
    m["emissiveFactor"] = {1, 1, 1};
    m["emissiveTexture"] = {{"index", s.addTexture("dot.png")}};
    m["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", L}}}};
    s.addQuad({.material = s.addMaterial(m)});
    s.setCamera(2);
    const Scene scene(loadGltf(s.write(file("scene.gltf")), [](const std::string&) {}), kSide, kSide);
    EXPECT_GE(scene.emitters().emitterOfTriangle(0), 0);
    EXPECT_EQ(scene.emitters().emitterOfTriangle(1), -1);  // no texel under it emits
    RenderRequest r = smallRequest();
    r.integrator = "lt";
    r.width = r.height = kSide;
    r.spp = 64;
    const std::vector<Image> images = renderRuns(scene, r, 16, 700);
    std::vector<double> texel, elsewhere;
    for (const Image& img : images) {
        texel.push_back(blockMean(img, kX, kY, 1, 1));
        elsewhere.push_back(blockMean(img, 0, 0, kSide, kSide) * kSide * kSide - texel.back());
    }
    const MeanError e = meanAndError(texel);
    EXPECT_NEAR(e.mean, L, 5 * e.stderr_);
    EXPECT_LT(5 * e.stderr_, 0.25 * L);  // the check has power
    EXPECT_NEAR(meanAndError(elsewhere).mean, 0.0, 1e-9);
}

// The mean over independent runs of each texel's pixels, per channel, against `expected` (of
// texel x, y and channel c): within 5 standard errors of 32 runs (t with 31 degrees of freedom:
// a false alarm among the 96 comparisons of a test has probability about 0.002).
template <class Expected>
void expectTexelMeans(const Scene& scene, RenderRequest r, Expected expected) {
    const std::vector<Image> images = renderRuns(scene, r, 32, 100);
    for (int y = 0; y < kTexels; ++y)
        for (int x = 0; x < kTexels; ++x)
            for (int c = 0; c < 3; ++c) {
                std::vector<double> means;
                for (const Image& img : images) means.push_back(blockMean(img, 2 * x, 2 * y, 2, 2, c));
                const MeanError e = meanAndError(means);
                EXPECT_NEAR(e.mean, expected(x, y, c), 5 * e.stderr_ + 1e-6)
                    << r.integrator << " texel " << x << "," << y << " channel " << c;
            }
}

RenderRequest texelRequest(const char* integrator) {
    RenderRequest r = smallRequest();
    r.integrator = integrator;
    r.width = r.height = kSize;
    r.spp = 16;
    return r;
}

// A Lambertian quad with a base colour texture, inside a glowing box: each texel's pixels read
// decoded base colour × L, for pt, bdpt and mlt.
TEST_F(Textures, BaseColourTextureUnderUniformRadiance) {
    const std::vector<uint8_t> texels = distinctTexels();
    writePng(file("base.png"), kTexels, kTexels, 4, texels);
    TexturedScene s;
    const float L = 2;
    s.addGlowingBox(3, L);
    nlohmann::json m = blackMaterial();
    m["pbrMetallicRoughness"]["baseColorFactor"] = {1, 1, 1, 1};
    m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", s.addTexture("base.png")}};
    s.addQuad({.material = s.addMaterial(m)});
    s.setCamera(2);
    const auto scene = load(s);
    for (const char* integrator : {"pt", "bdpt", "mlt"})
        expectTexelMeans(*scene, texelRequest(integrator),
                         [&](int x, int y, int c) { return decodedTexel(texels, x, y)[c] * L; });
}

// The same under a constant sky L alone: the quad's front sees the sky over its whole hemisphere,
// so each texel reads decoded base colour × L, in the integrators whose estimate stays within a
// texel (light tracing's splats and bdpt's too; the merging ones blur across texel edges).
TEST_F(Textures, BaseColourTextureUnderAConstantSky) {
    const std::vector<uint8_t> texels = distinctTexels();
    writePng(file("base.png"), kTexels, kTexels, 4, texels);
    TexturedScene s;
    nlohmann::json m = blackMaterial();
    m["pbrMetallicRoughness"]["baseColorFactor"] = {1, 1, 1, 1};
    m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", s.addTexture("base.png")}};
    s.addQuad({.material = s.addMaterial(m)});
    s.setCamera(2);
    EnvironmentDesc sky;
    sky.width = sky.height = 1;
    const float L = 1.5f;
    sky.texels = {Spectrum(L)};
    const auto scene = load(s, sky);
    for (const char* integrator : {"pt", "lt", "bdpt"})
        expectTexelMeans(*scene, texelRequest(integrator),
                         [&](int x, int y, int c) { return decodedTexel(texels, x, y)[c] * L; });
}

nlohmann::json whiteMaterial(float metallic = 0, float roughness = 1) {
    return {{"pbrMetallicRoughness",
             {{"baseColorFactor", {0.9, 0.7, 0.5, 1}}, {"metallicFactor", metallic}, {"roughnessFactor", roughness}}}};
}

nlohmann::json emitterMaterial(float radiance) {
    nlohmann::json m = blackMaterial();
    m["emissiveFactor"] = {1, 1, 1};
    m["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", radiance}}}};
    return m;
}

// A quad whose normal texture is lean.png (beside `gltf`, which is written), under an emitter, its
// TANGENT attribute, its node's rotation and its u mirrored as given, at kSize × kSize.
Scene leaningQuad(const fs::path& gltf, std::optional<std::array<float, 4>> tangent,
                  std::optional<std::array<float, 4>> rotation, bool mirroredU) {
    TexturedScene s;
    nlohmann::json m = whiteMaterial();
    m["normalTexture"] = {{"index", s.addTexture("lean.png")}};
    s.addQuad({.material = s.addMaterial(m), .mirroredU = mirroredU});
    s.addQuad({.z = 1, .material = s.addMaterial(emitterMaterial(1)), .facingDown = true});
    if (tangent) s.setTangent(*tangent);
    if (rotation) s.setMeshRotation(*rotation);
    s.setCamera(2);
    return Scene(loadGltf(s.write(gltf), [](const std::string&) {}), kSize, kSize);
}

// Under a uniform field a surface reads ρ(ωo) L, and glTF's BRDF is linear in metallic: metallic
// 0.5 reads the mean of metallic 0 and 1, pixel block by pixel block (each scene's 32 runs).
TEST_F(Textures, HalfMetallicLiesHalfwayUnderUniformRadiance) {
    std::vector<std::vector<MeanError>> byMetallic;
    for (float metallic : {0.0f, 0.5f, 1.0f}) {
        TexturedScene s;
        s.addGlowingBox(3, 1);
        s.addQuad({.material = s.addMaterial(whiteMaterial(metallic, 0.4f))});
        s.setCamera(2);
        const auto scene = load(s);
        RenderRequest r = texelRequest("pt");
        r.spp = 128;  // the ends differ by the coat's few percent: enough samples to tell them apart
        const std::vector<Image> images = renderRuns(*scene, r, 32, 200);
        byMetallic.emplace_back();
        for (const Block& b : blockGrid(kSize, kSize, 4, 4)) {
            std::vector<double> means;
            for (const Image& img : images) means.push_back(blockMean(img, b, luminance));
            byMetallic.back().push_back(meanAndError(means));
        }
    }
    for (size_t k = 0; k < byMetallic[0].size(); ++k) {
        const MeanError &m0 = byMetallic[0][k], &half = byMetallic[1][k], &m1 = byMetallic[2][k];
        const double sigma =
            std::sqrt(half.stderr_ * half.stderr_ + 0.25 * (m0.stderr_ * m0.stderr_ + m1.stderr_ * m1.stderr_));
        EXPECT_NEAR(half.mean, 0.5 * (m0.mean + m1.mean), 5 * sigma) << "block " << k;
        EXPECT_GT(std::abs(m1.mean - m0.mean), 8 * sigma) << "block " << k << ": the ends do not differ";
    }
}

// A smooth metal (metallic 1, roughness 0) seen at 45° through a normal map tilted 30° away from
// the camera, inside a box of uniform radiance L = 1: about the shading normal its mirror
// direction would leave 15° below the geometric surface, which a plain leak mask drops (a black
// rim). The shading normal bends back just enough to keep the reflection above the surface
// (shading_normal.h), so the quad, which fills the view, reads its Fresnel reflectance times L:
// between F0 = 0.9 and 1 over the image, for pt, bdpt and mlt. Catches a walk that masks the
// reflection instead of bending it. The whole image, since mlt's total over it is its bootstrap's
// estimate (a standard error of 0.004 over the 16 runs), while the share its Markov chains give
// a block of 16 pixels would need some 700 steps per pixel, not 32, to come under 0.01.
TEST_F(Textures, SmoothMetalThroughATiltedNormalMapKeepsItsReflection) {
    writePng(file("tilt.png"), 1, 1, 3, std::vector<uint8_t>{128, 191, 238});  // (0, sin 30°, cos 30°)
    TexturedScene s;
    s.addGlowingBox(3, 1);
    nlohmann::json m = whiteMaterial(1, 0);
    m["pbrMetallicRoughness"]["baseColorFactor"] = {0.9, 0.9, 0.9, 1};
    m["normalTexture"] = {{"index", s.addTexture("tilt.png")}};
    s.addQuad({.material = s.addMaterial(m)});
    s.setCamera(2);
    SceneDesc desc = loadGltf(s.write(file("scene.gltf")), [](const std::string&) {});
    desc.camera = build::lookAt({0, -2, 2}, {0, 0, 0}, 0.2f);  // 45° from the quad's normal, from −y
    const Scene scene(desc, kSize, kSize);
    for (const char* integrator : {"pt", "bdpt", "mlt"}) {
        RenderRequest r = texelRequest(integrator);
        r.spp = 32;
        std::vector<double> means;
        for (const Image& img : renderRuns(scene, r, 16, 800)) means.push_back(blockMean(img, 0, 0, kSize, kSize, 1));
        const MeanError e = meanAndError(means);
        EXPECT_GT(e.mean, 0.9 - 5 * e.stderr_) << integrator;
        EXPECT_LT(e.mean, 1.0 + 5 * e.stderr_) << integrator;
        EXPECT_LT(e.stderr_, 0.01) << integrator;
    }
}

// A normal texel (128, 218, 218) leans the normal 45° toward its image's +Y (up the image: glTF
// reads the green channel so), in the world along the bitangent glTF defines as
// cross(normal, tangent.xyz) · tangent.w. The shading normal at the quad's point under the camera
// must lean: up the image (+y) with tangents derived from the uv mapping, with a TANGENT attribute
// (1, 0, 0, +1), and with u mirrored (the derived bitangent keeps pointing up the image); down
// (−y) with TANGENT w = −1; and along −x when the node turns the mesh a quarter about z (the
// tangent turns with it). Catches a green channel read upside down, a tangent's w ignored, a
// mirrored mapping's handedness lost, or a TANGENT left in the mesh's own space.
TEST_F(Textures, NormalMapLeansAsTheTangentFrameAndGreenChannelSay) {
    writePng(file("lean.png"), 1, 1, 3, std::vector<uint8_t>{128, 218, 218});
    const float c = 0.7098f;  // 2 · 218/255 − 1
    struct Case {
        const char* what;
        std::optional<std::array<float, 4>> tangent, rotation;
        bool mirroredU;
        Vec3 lean;  // the world direction the normal leans toward
    };
    const float q = std::sqrt(0.5f);
    const Case cases[] = {
        {"tangents from the uv mapping", {}, {}, false, {0, 1, 0}},
        {"TANGENT (1, 0, 0, +1)", std::array<float, 4>{1, 0, 0, 1}, {}, false, {0, 1, 0}},
        {"TANGENT (1, 0, 0, -1)", std::array<float, 4>{1, 0, 0, -1}, {}, false, {0, -1, 0}},
        {"u mirrored, tangents from the mapping", {}, {}, true, {0, 1, 0}},
        {"TANGENT (1, 0, 0, +1), node turned 90 degrees about z", std::array<float, 4>{1, 0, 0, 1},
         std::array<float, 4>{0, 0, q, q}, false, {-1, 0, 0}},
    };
    for (const Case& k : cases) {
        const Scene scene = leaningQuad(file("scene.gltf"), k.tangent, k.rotation, k.mirroredU);
        const auto hit = scene.intersect({0.3f, 0.2f, 0.5f}, {0, 0, -1});
        ASSERT_TRUE(hit.has_value()) << k.what;
        const Vec3 expected = normalize(k.lean * c + Vec3(0, 0, c));
        EXPECT_GT(dot(hit->ns, expected), 0.999f) << k.what << ": the normal is (" << hit->ns.x << ", " << hit->ns.y
                                                   << ", " << hit->ns.z << ")";
    }
}

// A normal texel (255, 128, 64) tilts the mapped normal 27° past the surface's plane, toward +x
// (the tangent). The shading normal keeps that lean, raised to just above the plane, rather than
// being flipped to lean toward −x (the bump turned the other way), and stays above the surface.
TEST_F(Textures, ANormalMappedPastThePlaneKeepsItsLean) {
    writePng(file("lean.png"), 1, 1, 3, std::vector<uint8_t>{255, 128, 64});
    const Scene scene = leaningQuad(file("scene.gltf"), {}, {}, false);
    const auto hit = scene.intersect({0.3f, 0.2f, 0.5f}, {0, 0, -1});
    ASSERT_TRUE(hit.has_value());
    EXPECT_GT(hit->ns.x, 0.99f);
    EXPECT_GT(hit->ns.z, 0.0f);
}

// A metallic-roughness texture is linear data (B metallic, G roughness) times the factors: a
// uniform texture of bytes (G, B) = (100, 128) with factors 1 renders as factors 100/255 and 128/255.
TEST_F(Textures, MetallicRoughnessTextureIsLinearTimesTheFactors) {
    writePng(file("mr.png"), 1, 1, 3, std::vector<uint8_t>{0, 100, 128});
    std::vector<Image> images;
    for (bool textured : {true, false}) {
        TexturedScene s;
        s.addGlowingBox(3, 1);
        nlohmann::json m = textured ? whiteMaterial(1, 1) : whiteMaterial(128 / 255.0f, 100 / 255.0f);
        if (textured) m["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", s.addTexture("mr.png")}};
        s.addQuad({.material = s.addMaterial(m)});
        s.setCamera(2);
        images.push_back(renderScene(*load(s), texelRequest("pt")).image());
    }
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(images[0].at(x, y)[c], images[1].at(x, y)[c], 1e-4f * images[1].at(x, y)[c]) << x << "," << y;
}

// alphaMode MASK: a black quad masked by its base colour's alpha × the factor's alpha (0.9),
// cutoff 0.5, in front of an emitter of radiance 3 that fills the view: the camera sees 3 exactly
// through the texels whose alpha falls below the cutoff and 0 elsewhere. Alpha bytes 140 (0.494
// with the factor: a hole, which it would not be without) and 160 (0.565: opaque, which it would
// not be were alpha decoded as sRGB) stand beside 0 and 255.
TEST_F(Textures, MaskedQuadIsAHoleWhereAlphaIsBelowTheCutoff) {
    const uint8_t alphas[4] = {0, 140, 160, 255};
    std::vector<uint8_t> texels;
    for (int y = 0; y < kTexels; ++y)
        for (int x = 0; x < kTexels; ++x) texels.insert(texels.end(), {255, 255, 255, alphas[(x + y) % 4]});
    writePng(file("alpha.png"), kTexels, kTexels, 4, texels);
    TexturedScene s;
    nlohmann::json m = blackMaterial();
    m["pbrMetallicRoughness"]["baseColorFactor"] = {0, 0, 0, 0.9};
    m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", s.addTexture("alpha.png")}};
    m["alphaMode"] = "MASK";
    m["alphaCutoff"] = 0.5;
    s.addQuad({.material = s.addMaterial(m)});
    s.addQuad({.z = -1, .h = 4, .material = s.addMaterial(emitterMaterial(3))});
    s.setCamera(2);
    const auto scene = load(s);
    const Image img = renderScene(*scene, texelRequest("pt")).image();
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const int alpha = alphas[(x / 2 + y / 2) % 4];
            const float expected = alpha < 0.5 * 255 / 0.9 ? 3.0f : 0.0f;
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(img.at(x, y)[c], expected, 1e-5f) << x << "," << y;
        }
}

// Shadow rays see the mask too: a floor lit through an occluder that is a hole everywhere renders
// as the floor with no occluder at all (the same paths, so the same image).
TEST_F(Textures, ShadowRaysPassThroughMaskedHoles) {
    writePng(file("clear.png"), 1, 1, 4, std::vector<uint8_t>{255, 255, 255, 0});
    std::vector<Image> images;
    const std::vector<const char*> integrators = {"pt", "bdpt", "mlt"};
    for (bool occluder : {true, false})
        for (const char* integrator : integrators) {
            TexturedScene s;
            s.addQuad({.material = s.addMaterial(whiteMaterial())});
            s.addQuad({.z = 2, .h = 0.5f, .material = s.addMaterial(emitterMaterial(5)), .facingDown = true});
            if (occluder) {
                nlohmann::json m = blackMaterial();
                m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", s.addTexture("clear.png")}};
                m["alphaMode"] = "MASK";
                s.addQuad({.z = 1, .h = 2, .material = s.addMaterial(m)});
            }
            s.setCamera(0.9f, 1);
            images.push_back(renderScene(*load(s), texelRequest(integrator)).image());
        }
    const size_t n = integrators.size();
    for (size_t i = 0; i < n; ++i) {
        EXPECT_GT(blockMean(images[i + n], 0, 0, kSize, kSize), 0.05);
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                for (int c = 0; c < 3; ++c)
                    EXPECT_NEAR(images[i].at(x, y)[c], images[i + n].at(x, y)[c], 1e-5f * images[i + n].at(x, y)[c] + 1e-7f)
                        << integrators[i] << " " << x << "," << y;
    }
}

// A floor lit from one side by a small emitter, with a normal texture (or none), seen from above:
// the scene of the normal-map tests. `normalTexture`: the PNG's file name, or empty for none.
std::unique_ptr<Scene> normalMappedFloor(TexturedScene& s, const std::string& normalTexture,
                                         const std::function<std::unique_ptr<Scene>(TexturedScene&)>& load) {
    nlohmann::json m = whiteMaterial(0, 1);
    if (!normalTexture.empty()) m["normalTexture"] = {{"index", s.addTexture(normalTexture, false)}};
    s.addQuad({.material = s.addMaterial(m)});
    s.addQuad({.z = 1.5f, .h = 0.3f, .material = s.addMaterial(emitterMaterial(20)), .facingDown = true, .x = -1.2f});
    s.setCamera(2);
    return load(s);
}

// A flat normal texture ((0.5, 0.5, 1): 16-bit, so 2t − 1 is 1.5e-5 from 0) renders as no normal
// texture; a tilted one ((0.8, 0.5, 0.85)) changes the image.
TEST_F(Textures, FlatNormalTextureChangesNothingATiltedOneDoes) {
    writePng(file("flat.png"), 1, 1, 3, std::vector<uint16_t>{32768, 32768, 65535});
    writePng(file("tilted.png"), 1, 1, 3, std::vector<uint8_t>{204, 128, 217});
    auto loader = [this](TexturedScene& s) { return load(s); };
    std::vector<Image> images;
    for (const char* texture : {"", "flat.png", "tilted.png"}) {
        TexturedScene s;
        images.push_back(renderScene(*normalMappedFloor(s, texture, loader), texelRequest("pt")).image());
    }
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(images[1].at(x, y)[c], images[0].at(x, y)[c], 1e-3f * images[0].at(x, y)[c] + 1e-6f)
                    << x << "," << y;
    // The emitter lies toward −x: a normal tilted toward +x turns the floor away from it.
    EXPECT_LT(blockMean(images[2], 0, 0, kSize, kSize), 0.9 * blockMean(images[0], 0, 0, kSize, kSize));
}

// A normal texture turned by KHR_texture_transform leans along the texture's own axes: turned a
// quarter (the extension's rotation π/2: u' = v, v' = −u), a texel leaning toward +u' leans toward
// +v, down the image, so it shades as an untransformed texel leaning that way (green −129/255
// where the first had red +129/255: bytes 128, 63 for 192, 128). The floor is lit from one side,
// so a lean along u (the untransformed texture, the transform's rotation ignored for the tangent
// frame) shades otherwise. Catches the tangent frame left on the mesh's axes, or turned the wrong way.
TEST_F(Textures, ARotatedNormalTextureLeansAlongItsOwnAxes) {
    writePng(file("along-u.png"), 1, 1, 3, std::vector<uint8_t>{192, 128, 230});
    writePng(file("down-v.png"), 1, 1, 3, std::vector<uint8_t>{128, 63, 230});
    std::vector<Image> images;
    for (int variant = 0; variant < 3; ++variant) {
        TexturedScene s;
        nlohmann::json m = whiteMaterial(0, 1);
        m["normalTexture"] = {{"index", s.addTexture(variant == 1 ? "down-v.png" : "along-u.png", false)}};
        if (variant == 0) m["normalTexture"]["extensions"] = {{"KHR_texture_transform", {{"rotation", 1.5707963267948966}}}};
        s.addQuad({.material = s.addMaterial(m)});
        s.addQuad({.z = 1.5f, .h = 0.3f, .material = s.addMaterial(emitterMaterial(20)), .facingDown = true, .x = -1.2f,
                   .y = -0.6f});
        s.setCamera(2);
        images.push_back(renderScene(*load(s), texelRequest("pt")).image());
    }
    double apart = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(images[0].at(x, y)[c], images[1].at(x, y)[c], 1e-4f * images[1].at(x, y)[c] + 1e-7f)
                    << x << "," << y;
            apart = std::max(apart, double(std::abs(images[2].at(x, y)[0] - images[1].at(x, y)[0]) / images[1].at(x, y)[0]));
        }
    EXPECT_GT(apart, 0.1) << "a lean along u must shade otherwise than one along v";
}

// Light tracing and path tracing agree on the light a normal-mapped floor throws onto a ceiling
// (lit by nothing else: the emitter faces the floor), seen from below: light paths scatter at the
// floor in their walks, camera paths connect or arrive there, so the mapped normal must be a
// shading normal like any other, with the adjoint BSDF (shadingCorrection toward the light side,
// in either transport mode) and the leak masks. mlt is held to pt as well (128 steps per pixel,
// 16 runs: its blocks' standard errors are 3 to 4 % of their means, under the noise ceiling):
// its estimate mixes every bdpt strategy, so a light walk that scatters wrongly at the floor
// shows only in the share its MIS gives the light subpaths. Doubling that scattering moves it by
// about 30 %, and fails; the shading correction dropped from the light walk, which lt is caught
// by (25 % low), moves it less than its noise.
TEST_F(Textures, LightAndPathTracingAgreeOnANormalMappedFloor) {
    writePng(file("tilted.png"), 1, 1, 3, std::vector<uint8_t>{90, 170, 230});
    TexturedScene s;
    nlohmann::json floor = whiteMaterial(0, 1);
    floor["normalTexture"] = {{"index", s.addTexture("tilted.png", false)}};
    s.addQuad({.h = 2, .material = s.addMaterial(floor)});
    s.addQuad({.z = 1, .h = 0.3f, .material = s.addMaterial(emitterMaterial(20)), .facingDown = true, .x = -2.5f});
    s.addQuad({.z = 1.6f, .h = 4, .material = s.addMaterial(whiteMaterial(0, 1)), .facingDown = true});
    s.setCameraLookingUp(0.3f, 0.8f);
    const auto scene = load(s);
    const std::vector<Block> blocks = blockGrid(kSize, kSize, 2, 2);
    RenderRequest pt = texelRequest("pt"), lt = texelRequest("lt"), mlt = texelRequest("mlt");
    pt.spp = lt.spp = mlt.spp = 128;
    const BlockRuns ptRuns = blockRuns(*scene, pt, 16, 300, blocks);
    BlockAgreement agreement;
    agreement.compare(ptRuns, blockRuns(*scene, lt, 16, 400, blocks), "pt vs lt");
    agreement.compare(ptRuns, blockRuns(*scene, mlt, 16, 500, blocks), "pt vs mlt");
    agreement.expectNoBias();
}

// The holes of a masked emitter emit nothing, however a point in them is reached (next-event
// estimation and light paths sample points by area): a floor lit by an emitter quad whose texture
// is a hole but for its top-right quarter renders as one lit by that quarter alone.
TEST_F(Textures, HolesInAMaskedEmitterEmitNothing) {
    std::vector<uint8_t> texels(4 * 4, 255);
    for (int texel : {0, 2, 3}) texels[size_t(4 * texel + 3)] = 0;  // row by row: texel 1 is the top right
    writePng(file("quarter.png"), 2, 2, 4, texels);
    std::vector<std::unique_ptr<Scene>> scenes;
    for (bool masked : {true, false}) {
        TexturedScene s;
        s.addQuad({.h = 2, .material = s.addMaterial(whiteMaterial())});
        nlohmann::json light = emitterMaterial(10);
        if (masked) {
            light["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", s.addTexture("quarter.png")}};
            light["alphaMode"] = "MASK";
            s.addQuad({.z = 1, .h = 1, .material = s.addMaterial(light), .facingDown = true});
        } else {
            s.addQuad({.z = 1, .h = 0.5f, .material = s.addMaterial(light), .facingDown = true, .x = 0.5f, .y = 0.5f});
        }
        s.setCamera(0.9f, 1);
        scenes.push_back(load(s));
    }
    expectLitAlikeByPtAndLt(*scenes[0], *scenes[1], texelRequest("pt"), "masked vs quarter");
}

// Images embedded in the buffer (a bufferView, as in a .glb) or in a data: URI read as a file's do.
TEST_F(Textures, EmbeddedImagesReadAsFilesDo) {
    const std::vector<uint8_t> texels = distinctTexels();
    writePng(file("glow.png"), kTexels, kTexels, 4, texels);
    std::vector<Image> images;
    for (int source = 0; source < 3; ++source) {
        TexturedScene s;
        nlohmann::json m = blackMaterial();
        m["emissiveFactor"] = {1, 1, 1};
        const int texture = source == 0 ? s.addTexture("glow.png") : s.addEmbeddedTexture(file("glow.png"), source == 2);
        m["emissiveTexture"] = {{"index", texture}};
        s.addQuad({.material = s.addMaterial(m)});
        s.setCamera(2);
        images.push_back(renderScene(*load(s), texelRequest("pt")).image());
    }
    for (int source = 1; source < 3; ++source)
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                for (int c = 0; c < 3; ++c) EXPECT_EQ(images[size_t(source)].at(x, y)[c], images[0].at(x, y)[c]);
    EXPECT_GT(blockMean(images[0], 0, 0, kSize, kSize), 0.1);
}

// KHR_texture_transform as its README's example states it: offset [0, 1], rotation π/2 and scale
// [0.5, 0.5] show the image's lower-left quadrant alone, turned a quarter clockwise. The texture
// (4 × 4, nearest, linear data) holds each texel's position in its red and green; the quad's 2 × 2
// cells, read at their centres, must show the quadrant's texels Q (Q[row][column], row 0 its top:
// image texel x = column, y = 2 + row) turned clockwise, so that cell (row r, column c) shows
// Q[1 − c][r]. The transform names coordinate set 1, so set 0 (far off) must not be read. Catches
// a rotation of the other sign (the upper-right quadrant, turned anticlockwise), scale applied
// after the rotation, or the extension's texCoord ignored.
TEST_F(Textures, TextureTransformShowsTheExtensionsExampleQuadrant) {
    std::vector<uint8_t> bytes;
    for (int y = 0; y < kTexels; ++y)
        for (int x = 0; x < kTexels; ++x) bytes.insert(bytes.end(), {uint8_t(16 * x), uint8_t(16 * y), 255});
    writePng(file("where.png"), kTexels, kTexels, 3, bytes);
    TexturedScene s;
    nlohmann::json m = whiteMaterial();
    m["normalTexture"] = {{"index", s.addTexture("where.png", true, true)},
                          {"extensions", {{"KHR_texture_transform",
                                           {{"offset", {0, 1}}, {"rotation", 1.5707963f}, {"scale", {0.5, 0.5}},
                                            {"texCoord", 1}}}}}};
    s.addQuad({.material = s.addMaterial(m)});
    s.addQuad({.z = 1, .material = s.addMaterial(emitterMaterial(1)), .facingDown = true});
    const SceneDesc desc = loadGltf(s.write(file("scene.gltf")), [](const std::string&) {});
    const TextureSlot& slot = desc.materials[0].textures->normal;
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) {
            const Vec2 uv{(c + 0.5f) / 2, (r + 0.5f) / 2};
            const int row = 1 - c, column = r;  // Q[1 − c][r]
            const Texel t = slot.lookup({Vec2{0.6f, 0.1f}, uv});
            EXPECT_EQ(std::lround(t[0] * 255 / 16), column) << "cell " << r << "," << c;
            EXPECT_EQ(std::lround(t[1] * 255 / 16), 2 + row) << "cell " << r << "," << c;
        }
}

// glTF's alpha is independent of the colour beside it: a base colour texel (200, 100, 50, 128)
// reads the sRGB decoding of 200, 100 and 50 and alpha 128/255, and a texel of alpha 0 keeps its
// colour; data textures (a normal map's RGB) read their stored bytes whatever their alpha. The PNG
// is written byte for byte (png_bytes.h). Catches a reader that multiplies colour by alpha (0.127
// instead of 0.578 in red; black wherever alpha is 0).
TEST_F(Textures, RgbaTexelsReadAsStoredNotMultipliedByAlpha) {
    const std::vector<uint8_t> texels{200, 100, 50, 128, 10, 220, 90, 0};
    writePng(file("rgba.png"), 2, 1, 4, texels);
    TexturedScene s;
    nlohmann::json m = whiteMaterial();
    const int texture = s.addTexture("rgba.png");
    m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", texture}};
    m["normalTexture"] = {{"index", texture}};
    s.addQuad({.material = s.addMaterial(m)});
    s.addQuad({.z = 1, .material = s.addMaterial(emitterMaterial(1)), .facingDown = true});
    const SceneDesc desc = loadGltf(s.write(file("scene.gltf")), [](const std::string&) {});
    const MaterialTextures& t = *desc.materials[0].textures;
    for (int x = 0; x < 2; ++x) {
        const Vec2 uv{0.25f + 0.5f * x, 0.5f};
        const Texel colour = t.baseColor.lookup({uv, uv}), data = t.normal.lookup({uv, uv});
        for (int c = 0; c < 3; ++c) {
            const uint8_t byte = texels[size_t(4 * x + c)];
            EXPECT_NEAR(colour[size_t(c)], srgbByteToLinear(byte), 1e-6f) << "texel " << x << " channel " << c;
            EXPECT_NEAR(data[size_t(c)], byte / 255.0f, 1e-6f) << "texel " << x << " channel " << c;
        }
        EXPECT_NEAR(colour[3], texels[size_t(4 * x + 3)] / 255.0f, 1e-6f) << "texel " << x;
    }
}

}  // namespace
}  // namespace tripath::test
