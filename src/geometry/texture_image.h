// A texture's image: its texels stored in the precision of the file they come from (8-bit or
// 16-bit unsigned RGBA; float RGBA for built-in scenes' own textures), and the values they read
// as. What the stored numbers mean is up to whoever reads them: colour textures decode the colour
// channels from sRGB, data textures (normals, metallic-roughness) read them as they are, and alpha
// is always read as it is. An image used both ways is stored once (geometry/texture.h reads it;
// io/gltf_textures.cpp decodes files into it).
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <variant>
#include <vector>

#include "core/srgb.h"

namespace tripath {

using Texel = std::array<float, 4>;  // RGBA as read: linear values

// How a texture's colour channels are read: as the values stored (data, and alpha always), or
// as sRGB-encoded colour decoded to linear (glTF's base colour and emission).
enum class ColourSpace { Linear, Srgb };

// Texels of channel type T, four channels each, row by row from the image's top row.
template <class T>
using TexelArray = std::vector<std::array<T, 4>>;

// An unsigned stored value as a fraction of its type's largest, v × (1 / max) rounded to float as
// OpenImageIO converts integer texels (it differs from v / max in the last bit for 126 of the 256
// bytes); a float as it is.
inline float unitValue(uint8_t v) { return float(v) * (1.0f / 255); }
inline float unitValue(uint16_t v) { return float(v) * (1.0f / 65535); }
inline float unitValue(float v) { return v; }

// srgbDecode(unitValue(b)) for each byte b, at index b: 8-bit colour channels decode through it.
inline const std::array<float, 256> kSrgbDecodedBytes = [] {
    std::array<float, 256> table{};
    for (size_t b = 0; b < table.size(); ++b) table[b] = srgbDecode(unitValue(uint8_t(b)));
    return table;
}();

// A stored colour value decoded from sRGB.
inline float srgbValue(uint8_t v) { return kSrgbDecodedBytes[v]; }
inline float srgbValue(uint16_t v) { return srgbDecode(unitValue(v)); }
inline float srgbValue(float v) { return srgbDecode(v); }

// A stored texel as it reads in colour space `space`.
template <class T>
Texel decodedTexel(const std::array<T, 4>& t, ColourSpace space) {
    if (space == ColourSpace::Srgb) return {srgbValue(t[0]), srgbValue(t[1]), srgbValue(t[2]), unitValue(t[3])};
    return {unitValue(t[0]), unitValue(t[1]), unitValue(t[2]), unitValue(t[3])};
}

class TextureImage {
public:
    // width × height texels (as many as that), row by row from the image's top row.
    TextureImage(int width, int height, TexelArray<uint8_t> texels);
    TextureImage(int width, int height, TexelArray<uint16_t> texels);
    TextureImage(int width, int height, TexelArray<float> texels);
    int width() const { return width_; }
    int height() const { return height_; }
    // The memory its texels take: 4, 8 or 16 bytes a texel.
    size_t bytes() const;
    // f(texels) for the stored TexelArray, whichever its type.
    template <class F>
    decltype(auto) visit(F&& f) const {
        return std::visit(std::forward<F>(f), texels_);
    }
    // Per channel, the largest value any texel reads as in colour space `space`, and 0 if none
    // reads above 0. (Reading is nondecreasing in the stored value, so this is the largest stored
    // value read; the tests check it exhaustively for 8- and 16-bit texels.)
    const Texel& largest(ColourSpace space) const { return largest_[space == ColourSpace::Srgb]; }

private:
    int width_, height_;
    std::array<Texel, 2> largest_;  // Linear, Srgb; found before texels_ takes the texels
    std::variant<TexelArray<uint8_t>, TexelArray<uint16_t>, TexelArray<float>> texels_;
};

// Per channel, the larger of two stored texels.
template <class T>
std::array<T, 4> channelMax(const std::array<T, 4>& a, const std::array<T, 4>& b) {
    return {std::max(a[0], b[0]), std::max(a[1], b[1]), std::max(a[2], b[2]), std::max(a[3], b[3])};
}

}  // namespace tripath
