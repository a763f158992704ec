// How texture images are stored and read back: 8-bit texels in 4 bytes and 16-bit ones in 8,
// each image decoded once however many textures, colour spaces and image entries use it, and
// lookups that give what decoding the whole image to floats gave, value for value: sRGB through
// a table of the 256 bytes' decodings, filtering between decoded values. The loader-level tests
// read PNGs written byte for byte (png_bytes.h) through glTF scenes (textured_scenes.h).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/srgb.h"
#include "geometry/texture.h"
#include "io/gltf_loader.h"
#include "textured_scenes.h"

namespace tripath::test {
namespace {

namespace fs = std::filesystem;

// A byte as OpenImageIO converts it to a float: times the float nearest 1/255.
float byteAsFloat(int b) { return float(b) * (1.0f / 255); }

// The table gives, for every byte, srgbDecode of the float that reading the image as floats gave.
TEST(TextureStorage, SrgbTableIsTheDecodingOfEveryByte) {
    for (int b = 0; b < 256; ++b) EXPECT_EQ(srgbValue(uint8_t(b)), srgbDecode(byteAsFloat(b))) << "byte " << b;
}

// The largest texel under a triangle is found among stored values and read after (maxOver), which
// holds because reading never decreases as the stored value grows: checked for every 8- and
// 16-bit value in both colour spaces.
TEST(TextureStorage, ReadingIsNondecreasingInTheStoredValue) {
    for (int v = 1; v < 256; ++v) {
        EXPECT_LE(srgbValue(uint8_t(v - 1)), srgbValue(uint8_t(v))) << v;
        EXPECT_LE(unitValue(uint8_t(v - 1)), unitValue(uint8_t(v))) << v;
    }
    for (int v = 1; v < 65536; ++v) {
        ASSERT_LE(srgbValue(uint16_t(v - 1)), srgbValue(uint16_t(v))) << v;
        ASSERT_LE(unitValue(uint16_t(v - 1)), unitValue(uint16_t(v))) << v;
    }
}

// Bilinear filtering weighs decoded values: halfway between bytes 0 and 255 of a colour texture
// reads (0 + 1) / 2, not the decoding of the bytes' mean (0.216); the largest value under the
// whole image is the decoded 255.
TEST(TextureStorage, FilteringWeighsDecodedValues) {
    const auto image = std::make_shared<const TextureImage>(2, 1, TexelArray<uint8_t>{{0, 0, 0, 0}, {255, 255, 255, 255}});
    const Texture t(image, TextureWrap::ClampToEdge, TextureWrap::ClampToEdge, TextureFilter::Linear);
    const Texel mid = t.lookup({0.5f, 0.5f}, ColourSpace::Srgb);
    EXPECT_EQ(mid[0], 0.5f);
    EXPECT_EQ(mid[3], 0.5f);
    EXPECT_EQ(t.maxOver({Vec2{0, 0}, Vec2{1, 0}, Vec2{0, 1}}, ColourSpace::Srgb)[0], 1.0f);
}

class StoredTextures : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("tripath_texture_storage_" +
                std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path file(const std::string& name) const { return dir_ / name; }
    // The materials of scene s, loaded as a user's file is.
    std::vector<Material> load(TexturedScene& s) const {
        return loadGltf(s.write(file("scene.gltf")), [](const std::string&) {}).materials;
    }
    fs::path dir_;
};

nlohmann::json plainMaterial() {
    return {{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 1}, {"roughnessFactor", 1}}}};
}

// Every byte of a grey 8-bit PNG reads exactly as decoding the image to floats read it: as a
// colour texture, srgbDecode of the float; as data, the float itself.
TEST_F(StoredTextures, EightBitTexelsReadAsTheImageDecodedToFloatsDid) {
    std::vector<uint8_t> grey(256);
    for (int b = 0; b < 256; ++b) grey[size_t(b)] = uint8_t(b);
    writePng(file("grey.png"), 256, 1, 1, grey);
    TexturedScene s;
    nlohmann::json m = plainMaterial();
    const int texture = s.addTexture("grey.png");
    m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", texture}};
    m["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", texture}};
    s.addQuad({.material = s.addMaterial(m)});
    const std::vector<Material> materials = load(s);
    const MaterialTextures& t = *materials[0].textures;
    for (int b = 0; b < 256; ++b) {
        const Vec2 uv{(b + 0.5f) / 256, 0.5f};
        const Texel colour = t.baseColor.lookup({uv, uv}), data = t.metallicRoughness.lookup({uv, uv});
        for (size_t c = 0; c < 3; ++c) {
            EXPECT_EQ(colour[c], srgbDecode(byteAsFloat(b))) << "byte " << b;
            EXPECT_EQ(data[c], byteAsFloat(b)) << "byte " << b;
        }
        EXPECT_EQ(colour[3], 1.0f);
    }
}

// One PNG used by a texture as colour and as data, by a second texture (another sampler) and by
// a second image entry naming the same file is decoded once, into 4 bytes a texel; a 16-bit PNG
// takes 8 bytes a texel and reads its values as fractions of 65535.
TEST_F(StoredTextures, AnImageIsDecodedOnceIntoItsFilesPrecision) {
    const int w = 8, h = 4;
    std::vector<uint8_t> rgb(size_t(3 * w * h));
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = uint8_t(7 * i);
    writePng(file("shared.png"), w, h, 3, rgb);
    std::vector<uint16_t> deep(size_t(w * h), 40000);
    writePng(file("deep.png"), w, h, 1, deep);
    TexturedScene s;
    const int colour = s.addTexture("shared.png");
    const int linear = s.addTextureSharingImage(colour, false);
    const int again = s.addTexture("shared.png");
    const int sixteen = s.addTexture("deep.png");
    nlohmann::json m = plainMaterial();
    m["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", colour}};
    m["normalTexture"] = {{"index", colour}};
    m["pbrMetallicRoughness"]["metallicRoughnessTexture"] = {{"index", linear}};
    m["emissiveTexture"] = {{"index", again}};
    nlohmann::json deepMaterial = plainMaterial();
    deepMaterial["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", sixteen}};
    s.addQuad({.material = s.addMaterial(m)});
    s.addQuad({.z = 1, .material = s.addMaterial(deepMaterial)});
    const std::vector<Material> materials = load(s);
    const MaterialTextures& t = *materials[0].textures;
    EXPECT_EQ(t.baseColor.texture, t.normal.texture);  // one texture, read in two colour spaces
    EXPECT_EQ(t.baseColor.texture->image(), t.metallicRoughness.texture->image());
    EXPECT_EQ(t.baseColor.texture->image(), t.emissive.texture->image());
    EXPECT_EQ(t.baseColor.texture->image()->bytes(), size_t(4 * w * h));
    const TextureSlot& deepSlot = materials[1].textures->baseColor;
    EXPECT_EQ(deepSlot.texture->image()->bytes(), size_t(8 * w * h));
    const Vec2 uv{0.5f, 0.5f};
    EXPECT_EQ(deepSlot.lookup({uv, uv})[0], srgbDecode(40000 * (1.0f / 65535)));
}

}  // namespace
}  // namespace tripath::test
