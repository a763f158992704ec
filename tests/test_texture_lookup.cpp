// Texture lookups and the tangent frame of normal textures, checked against values worked out by
// hand: texel (x, y) covers [x/w, (x+1)/w] × [y/h, (y+1)/h]; bilinear weights from the texel
// centres; the three wrap modes; the tangent frame from texture coordinates. (KHR_texture_transform,
// which the loader turns into a slot's matrix, is checked where it is read: test_textures.cpp.)
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "geometry/surface_textures.h"
#include "geometry/texture.h"

namespace tripath {
namespace {

// A w × 1 texture whose texel x has red x (and green, blue, alpha 0, 0, 1).
std::shared_ptr<const Texture> ramp(int w, TextureWrap wrap, TextureFilter filter) {
    std::vector<Texel> texels;
    for (int x = 0; x < w; ++x) texels.push_back({float(x), 0, 0, 1});
    return std::make_shared<const Texture>(w, 1, texels, wrap, wrap, filter);
}

float red(const Texture& t, float u) { return t.lookup({u, 0.5f})[0]; }

TEST(TextureLookup, NearestTakesTheTexelUnderTheCoordinate) {
    const auto t = ramp(4, TextureWrap::ClampToEdge, TextureFilter::Nearest);
    EXPECT_EQ(red(*t, 0.0f), 0.0f);
    EXPECT_EQ(red(*t, 0.24f), 0.0f);
    EXPECT_EQ(red(*t, 0.26f), 1.0f);
    EXPECT_EQ(red(*t, 0.99f), 3.0f);
}

TEST(TextureLookup, LinearWeighsTheNeighbouringTexelCentres) {
    const auto t = ramp(4, TextureWrap::ClampToEdge, TextureFilter::Linear);
    EXPECT_FLOAT_EQ(red(*t, 0.125f), 0.0f);   // texel 0's centre
    EXPECT_FLOAT_EQ(red(*t, 0.375f), 1.0f);   // texel 1's centre
    EXPECT_FLOAT_EQ(red(*t, 0.25f), 0.5f);    // halfway between them
    EXPECT_FLOAT_EQ(red(*t, 0.3125f), 0.75f);
    EXPECT_FLOAT_EQ(red(*t, 0.0f), 0.0f);     // clamped: texel 0 on both sides
    EXPECT_FLOAT_EQ(red(*t, 1.0f), 3.0f);
}

TEST(TextureLookup, WrapModes) {
    const auto repeat = ramp(4, TextureWrap::Repeat, TextureFilter::Nearest);
    const auto clamp = ramp(4, TextureWrap::ClampToEdge, TextureFilter::Nearest);
    const auto mirror = ramp(4, TextureWrap::MirroredRepeat, TextureFilter::Nearest);
    // u = 1.3: texel 5 of the infinite row; u = −0.1: texel −1; u = 2.6: texel 10.
    EXPECT_EQ(red(*repeat, 1.3f), 1.0f);
    EXPECT_EQ(red(*repeat, -0.1f), 3.0f);
    EXPECT_EQ(red(*clamp, 1.3f), 3.0f);
    EXPECT_EQ(red(*clamp, -0.1f), 0.0f);
    EXPECT_EQ(red(*mirror, 1.3f), 2.0f);   // 4..7 read 3, 2, 1, 0
    EXPECT_EQ(red(*mirror, -0.1f), 0.0f);  // −1 mirrors onto 0
    EXPECT_EQ(red(*mirror, 2.6f), 2.0f);   // 8..11 read 0, 1, 2, 3
    const auto linearRepeat = ramp(4, TextureWrap::Repeat, TextureFilter::Linear);
    EXPECT_FLOAT_EQ(red(*linearRepeat, 0.0f), 1.5f);  // between texel 3 (left, wrapped) and 0
    EXPECT_TRUE(std::isfinite(red(*repeat, 1e30f)));
    EXPECT_TRUE(std::isfinite(red(*repeat, std::nanf(""))));
}

TEST(TextureLookup, RowsRunDownTheImage) {
    const std::vector<Texel> texels = {{1, 0, 0, 1}, {2, 0, 0, 1}};  // 1 × 2: the top texel first
    const Texture t(1, 2, texels, TextureWrap::ClampToEdge, TextureWrap::ClampToEdge, TextureFilter::Nearest);
    EXPECT_EQ(t.lookup({0.5f, 0.1f})[0], 1.0f);
    EXPECT_EQ(t.lookup({0.5f, 0.9f})[0], 2.0f);
}

// An upright mapping (u along +x, v down the image along −y) has tangent +x and a bitangent
// n × t = +y, up the image: sign +1. Mirroring u flips the tangent and keeps the bitangent: −1.
TEST(TextureLookup, TangentsFromTheTextureCoordinates) {
    const Vec3 p[3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    const Vec3 n(0, 0, 1);
    Vec3 tangent;
    float sign = 0;
    const Vec2 upright[3] = {{0, 1}, {1, 1}, {0, 0}};
    ASSERT_TRUE(triangleTangent(p, upright, n, tangent, sign));
    EXPECT_NEAR(tangent.x, 1.0f, 1e-6f);
    EXPECT_EQ(sign, 1.0f);
    const Vec2 mirrored[3] = {{1, 1}, {0, 1}, {1, 0}};
    ASSERT_TRUE(triangleTangent(p, mirrored, n, tangent, sign));
    EXPECT_NEAR(tangent.x, -1.0f, 1e-6f);
    EXPECT_EQ(sign, -1.0f);
    const Vec2 degenerate[3] = {{0, 0}, {0, 0}, {0, 0}};
    EXPECT_FALSE(triangleTangent(p, degenerate, n, tangent, sign));
    EXPECT_TRUE(isFinite(tangent));
}

// A texel (x, y, z) bends the normal to x t + y b + z n (normalised): +x toward the tangent, +y
// toward the bitangent (up the image), and a tangent not orthogonal to n is made so first.
TEST(TextureLookup, PerturbedNormalFollowsTheTangentFrame) {
    const Vec3 n(0, 0, 1), tangent = normalize(Vec3(1, 0, 0.5f));
    const Vec3 a = perturbNormal(n, tangent, 1.0f, {0.6f, 0, 0.8f});
    EXPECT_NEAR(a.x, 0.6f, 1e-6f);
    EXPECT_NEAR(a.z, 0.8f, 1e-6f);
    const Vec3 b = perturbNormal(n, tangent, -1.0f, {0, 0.6f, 0.8f});
    EXPECT_NEAR(b.y, -0.6f, 1e-6f);  // a mirrored mapping's bitangent is −(n × t)
    const Vec3 flat = perturbNormal(n, tangent, 1.0f, {0, 0, 1});
    EXPECT_EQ(flat.z, 1.0f);
}

}  // namespace
}  // namespace tripath
