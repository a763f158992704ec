// Vertex colours (glTF's COLOR_0) rendered: each test writes its own small scene with
// textured_scenes.h, loads it as a user's file would be loaded, and checks the image against what
// the colours say in closed form. COLOR_0 multiplies the base colour, interpolated linearly over
// each triangle, and its alpha the alpha that alphaMode MASK compares with the cutoff.
//
// The radiance scenes are those of the texture tests (test_textures.cpp): a quad in the plane
// z = 0 under a camera whose view spans [−1, 1]² there, inside a closed box whose faces emit L and
// reflect nothing. The radiance field in the box is uniform, so a Lambertian quad of albedo ρ reads
// ρ L wherever it is seen, with every integrator: the closed form each test holds them to.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "io/gltf_loader.h"
#include "io/gltf_writer.h"
#include "support.h"
#include "textured_scenes.h"

namespace tripath::test {
namespace {

namespace fs = std::filesystem;

constexpr int kSize = 8;
constexpr float kL = 2;  // the box's radiance

class VertexColours : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("tripath_vertex_colours_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path file(const std::string& name) const { return dir_ / name; }
    SceneDesc loadDesc(TexturedScene& s) { return loadGltf(s.write(file("scene.gltf")), [](const std::string&) {}); }
    std::unique_ptr<Scene> load(TexturedScene& s) { return std::make_unique<Scene>(loadDesc(s), kSize, kSize); }
    // A quad of base colour factor `factor` (Lambertian) whose corners (−h, −h), (h, −h), (h, h),
    // (−h, h) have the colours `corners`, stored as `format`, in the box of radiance kL, seen by the
    // camera; h = 2, so that the quad's edges lie outside the view and the merging integrators'
    // discs never cross them.
    std::unique_ptr<Scene> colouredQuadInTheBox(Spectrum factor, std::vector<std::array<float, 4>> corners,
                                                ColourFormat format = {});

    fs::path dir_;
};

// A Lambertian material of base colour factor `factor` (metallic 0, roughness 1), alpha `alpha`.
nlohmann::json lambertian(Spectrum factor, float alpha = 1) {
    return {{"pbrMetallicRoughness",
             {{"baseColorFactor", {factor.x, factor.y, factor.z, alpha}}, {"metallicFactor", 0}, {"roughnessFactor", 1}}}};
}

nlohmann::json emitter(float radiance) {
    nlohmann::json m = lambertian(Spectrum(0.0f));
    m["emissiveFactor"] = {1, 1, 1};
    m["extensions"] = {{"KHR_materials_emissive_strength", {{"emissiveStrength", radiance}}}};
    return m;
}

std::unique_ptr<Scene> VertexColours::colouredQuadInTheBox(Spectrum factor, std::vector<std::array<float, 4>> corners,
                                                           ColourFormat format) {
    TexturedScene s;
    s.setColourFormat(format);
    s.addGlowingBox(3, kL);
    s.addQuad({.h = 2, .material = s.addMaterial(lambertian(factor)), .colours = std::move(corners)});
    s.setCamera(2);
    return load(s);
}

RenderRequest request(const std::string& integrator, int spp = 16) {
    RenderRequest r = smallRequest();
    r.integrator = integrator;
    r.width = r.height = kSize;
    r.spp = spp;
    return r;
}

// The samples per pixel that hold an integrator's standard error on a quarter of the image under
// 3 % of the signal in the box (measured: 16 spp give pt, bdpt, vcm and bpm 0.6 %, lt 10 %, ppm
// 13 %, mlt 3 %). Light tracing and ppm see the quad only by the light paths that reach its
// quarter in view, ppm through a radius of 0.75 pixels; mlt's chains are correlated.
int sppFor(const std::string& integrator) {
    if (integrator == "lt") return 512;
    if (integrator == "ppm") return 1024;
    if (integrator == "mlt") return 64;
    return 16;
}

// For every integrator (mlt included), the mean over 32 independent runs of each block's pixels,
// per channel, against `expected` (of the block's index and the channel): within 5 standard
// errors (t with 31 degrees of freedom: a false alarm among a test's comparisons has probability
// about 0.002), the standard error itself under 5 % of the value, so that a colour lost or
// misplaced (a change of 20 % or more in some block here) cannot pass as noise. Each run of mlt
// is unbiased (its bootstrap's b_k and start, metropolis_render.h), so the mean of its runs is
// held to the same bound.
void expectBlockMeans(const Scene& scene, const std::vector<Block>& blocks,
                      const std::function<double(size_t block, int channel)>& expected) {
    for (const std::string& integrator : kIntegratorNames) {
        const std::vector<Image> images = renderRuns(scene, request(integrator, sppFor(integrator)), 32, 100);
        for (size_t k = 0; k < blocks.size(); ++k)
            for (int c = 0; c < 3; ++c) {
                std::vector<double> means;
                for (const Image& img : images) means.push_back(blockMean(img, blocks[k].x, blocks[k].y, blocks[k].w, blocks[k].h, c));
                const MeanError e = meanAndError(means);
                const double want = expected(k, c);
                EXPECT_NEAR(e.mean, want, 5 * e.stderr_ + 1e-6) << integrator << " block " << k << " channel " << c;
                EXPECT_LT(e.stderr_, 0.05 * want) << integrator << " block " << k << " channel " << c;
            }
    }
}

// One colour (0.5, 0.25, 1) at every vertex of a Lambertian quad of base colour factor
// (0.8, 0.6, 0.4) (float VEC3): the quad reads factor × colour × L in each quadrant of the image.
// Fails with the colour ignored (the factor alone: 2 and 4 times too bright in red and green).
TEST_F(VertexColours, AUniformColourMultipliesTheBaseColour) {
    const Spectrum factor(0.8f, 0.6f, 0.4f), colour(0.5f, 0.25f, 1.0f);
    const std::array<float, 4> c{colour.x, colour.y, colour.z, 1};
    const auto scene = colouredQuadInTheBox(factor, {c, c, c, c}, {.componentType = 5126, .components = 3});
    expectBlockMeans(*scene, blockGrid(kSize, kSize, 2, 2),
                     [&](size_t, int channel) { return double(factor[channel] * colour[channel] * kL); });
}

// Colours that differ from left to right (the quad's two left corners one colour, its two right
// ones another; float VEC4, alpha not 1, which an opaque material ignores) blend linearly across
// the quad: each quarter of the image's width reads L × the colour at its centre's x (the camera
// sees the plane head-on, so a block averages the linear blend over a footprint symmetric about its
// centre). Fails with the colour ignored, and with a corner's colour taken for the whole triangle.
TEST_F(VertexColours, ColoursBlendLinearlyAcrossATriangle) {
    const std::array<float, 4> left{0.2f, 0.9f, 0.5f, 0.3f}, right{0.9f, 0.1f, 0.5f, 0.6f};
    const auto scene = colouredQuadInTheBox(Spectrum(1.0f), {left, right, right, left});
    const std::vector<Block> columns = blockGrid(kSize, kSize, 4, 1);
    expectBlockMeans(*scene, columns, [&](size_t column, int channel) {
        const double x = -1 + (2 * double(column) + 1) / 4;  // the block's centre, on the plane z = 0
        const double t = (x + 2) / 4;                        // from the quad's left edge (−2) to its right (2)
        return kL * ((1 - t) * left[size_t(channel)] + t * right[size_t(channel)]);
    });
}

// Normalized unsigned bytes (VEC4) and shorts (VEC3) are linear fractions of 255 and 65535, as
// floats are: a uniform colour of bytes (64, 128, 255) reads (64, 128, 255) / 255 × L, and of
// shorts (16384, 32768, 65535) / 65535 × L. Fails where the integers are decoded as sRGB (64 reads
// 0.05 instead of 0.25) or not scaled. pt alone: the loader decodes them, and the rendering of a
// colour is what AUniformColourMultipliesTheBaseColour holds every integrator to.
TEST_F(VertexColours, NormalizedIntegersAreLinearFractions) {
    struct Format {
        ColourFormat format;
        std::array<double, 3> stored;
        double largest;
    };
    const Format formats[] = {{{5121, 4}, {64, 128, 255}, 255}, {{5123, 3}, {16384, 32768, 65535}, 65535}};
    for (const Format& f : formats) {
        SCOPED_TRACE(f.format.componentType == 5121 ? "unsigned byte" : "unsigned short");
        const std::array<float, 4> c{float(f.stored[0] / f.largest), float(f.stored[1] / f.largest),
                                     float(f.stored[2] / f.largest), 1};
        const auto scene = colouredQuadInTheBox(Spectrum(1.0f), {c, c, c, c}, f.format);
        const std::vector<Image> images = renderRuns(*scene, request("pt"), 16, 300);
        for (int channel = 0; channel < 3; ++channel) {
            std::vector<double> means;
            for (const Image& img : images) means.push_back(blockMean(img, 0, 0, kSize, kSize, channel));
            const MeanError e = meanAndError(means);
            const double expected = f.stored[size_t(channel)] / f.largest * kL;
            EXPECT_NEAR(e.mean, expected, 5 * e.stderr_ + 1e-6) << "channel " << channel;
            EXPECT_LT(e.stderr_, 0.05 * expected) << "channel " << channel;
        }
    }
}

// alphaMode MASK reads the vertex colour's alpha times the factor's: a black quad of factor alpha
// 0.8 whose vertex alpha runs from 0.25 (left) to 1 (right) has alpha 0.8 × (0.25 + 0.75 t),
// below the cutoff 0.5 exactly left of x = 0, in front of an emitter of radiance 3 that fills the
// view: the camera sees 3 through the left half of the image and 0 in the right. Fails with the
// vertex alpha ignored (no hole) and with the factor's alpha left out (the hole ends at x = −1/3).
TEST_F(VertexColours, MaskedHolesFollowTheVertexAlpha) {
    TexturedScene s;
    nlohmann::json m = lambertian(Spectrum(0.0f), 0.8f);
    m["alphaMode"] = "MASK";
    m["alphaCutoff"] = 0.5;
    const std::array<float, 4> left{1, 1, 1, 0.25f}, right{1, 1, 1, 1};
    s.addQuad({.material = s.addMaterial(m), .colours = {left, right, right, left}});
    s.addQuad({.z = -1, .h = 4, .material = s.addMaterial(emitter(3))});
    s.setCamera(2);
    const auto scene = load(s);
    const Image img = renderScene(*scene, request("pt")).image();
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const float expected = x < kSize / 2 ? 3.0f : 0.0f;
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(img.at(x, y)[c], expected, 1e-5f) << x << "," << y;
        }
}

// The holes a vertex alpha makes in a masked emitter emit nothing, however a point in them is
// reached (next-event estimation and light paths sample points by area): a floor under an emitter
// quad [−1, 1]² whose vertex alpha runs from 0 (left) to 1 (right), cutoff 0.5, renders as one lit
// by the emitter's right half [0, 1] × [−1, 1] alone, block by block, for pt and lt. Fails with
// the vertex alpha left out of the emission (the whole quad emits).
TEST_F(VertexColours, HolesOfAMaskedEmitterEmitNothing) {
    std::vector<std::unique_ptr<Scene>> scenes;
    for (bool masked : {true, false}) {
        TexturedScene s;
        s.addQuad({.h = 2, .material = s.addMaterial(lambertian(Spectrum(0.9f, 0.7f, 0.5f)))});
        nlohmann::json light = emitter(10);
        if (masked) {
            light["alphaMode"] = "MASK";
            const std::array<float, 4> left{1, 1, 1, 0}, right{1, 1, 1, 1};
            s.addQuad({.z = 1, .h = 1, .material = s.addMaterial(light), .facingDown = true,
                       .colours = {left, right, right, left}});
        } else {
            const int material = s.addMaterial(light);
            for (float y : {-0.5f, 0.5f})
                s.addQuad({.z = 1, .h = 0.5f, .material = material, .facingDown = true, .x = 0.5f, .y = y});
        }
        s.setCamera(0.9f, 1);
        scenes.push_back(load(s));
    }
    expectLitAlikeByPtAndLt(*scenes[0], *scenes[1], request("pt"), "masked vs right half");
}

// `tripath export` writes a scene's vertex colours back (COLOR_0, float VEC4): loaded again, every
// mesh has the colours it had, bit for bit.
TEST_F(VertexColours, ExportWritesTheColoursBack) {
    TexturedScene s;
    s.setColourFormat({.componentType = 5121, .components = 4});
    const std::array<float, 4> a{0.2f, 0.4f, 0.6f, 0.8f}, b{1, 0.5f, 0, 1};
    s.addQuad({.material = s.addMaterial(lambertian(Spectrum(1.0f))), .colours = {a, b, a, b}});
    s.addQuad({.z = 1, .material = s.addMaterial(emitter(1)), .facingDown = true});
    const SceneDesc original = loadDesc(s);
    ASSERT_EQ(original.meshes.size(), 2u);
    EXPECT_EQ(original.meshes[0].colours.size(), 4u);
    EXPECT_TRUE(original.meshes[1].colours.empty());
    const std::string out = file("exported.glb").string();
    writeGltf(original, out, nullptr);
    const SceneDesc loaded = loadGltf(out, nullptr);
    ASSERT_EQ(loaded.meshes.size(), original.meshes.size());
    for (size_t m = 0; m < loaded.meshes.size(); ++m) EXPECT_EQ(loaded.meshes[m].colours, original.meshes[m].colours);
}

}  // namespace
}  // namespace tripath::test
