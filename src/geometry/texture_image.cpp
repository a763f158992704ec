// A texture's stored texels and their largest values (texture_image.h).
#include "geometry/texture_image.h"

namespace tripath {

namespace {

// Per channel, the largest value any of `texels` reads as in each colour space (Linear, Srgb),
// found among the stored values first: reading is nondecreasing, so it commutes with the maximum.
template <class T>
std::array<Texel, 2> largestRead(const TexelArray<T>& texels) {
    std::array<T, 4> m{};
    for (const std::array<T, 4>& t : texels) m = channelMax(m, t);
    return {decodedTexel(m, ColourSpace::Linear), decodedTexel(m, ColourSpace::Srgb)};
}

}  // namespace

TextureImage::TextureImage(int width, int height, TexelArray<uint8_t> texels)
    : width_(width), height_(height), largest_(largestRead(texels)), texels_(std::move(texels)) {}

TextureImage::TextureImage(int width, int height, TexelArray<uint16_t> texels)
    : width_(width), height_(height), largest_(largestRead(texels)), texels_(std::move(texels)) {}

TextureImage::TextureImage(int width, int height, TexelArray<float> texels)
    : width_(width), height_(height), largest_(largestRead(texels)), texels_(std::move(texels)) {}

size_t TextureImage::bytes() const {
    return visit([](const auto& texels) { return texels.size() * sizeof(texels[0]); });
}

}  // namespace tripath
