// Textures and what a textured material reads from them (glTF 2.0 §3.8 and §5.29, the
// KHR_texture_transform extension). A Texture is an image (texture_image.h: texels as the file
// stores them) with a sampler: looked up at glTF texture coordinates (u to the right, v downward
// from the image's top-left corner) with the sampler's wrap modes and a nearest or bilinear
// filter, which weighs texels as they read in the colour space asked for. A TextureSlot is one
// use of a texture by a material: which coordinate set, the affine transform to apply first, and
// the colour space its colour channels are read in. MaterialTextures gathers a material's slots
// and turns them into the parameters at a point.
//
// Everything here is plain data built by the io layer; the geometry layer only reads it.
#pragma once
#include <array>
#include <memory>
#include <vector>

#include "geometry/material.h"
#include "geometry/texture_image.h"
#include "core/vec.h"

namespace tripath {

enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };
enum class TextureFilter { Nearest, Linear };

class Texture {
public:
    Texture(std::shared_ptr<const TextureImage> image, TextureWrap wrapU, TextureWrap wrapV, TextureFilter filter);
    // A texture of linear float texels: width × height, row by row from the image's top row.
    Texture(int width, int height, std::vector<Texel> texels, TextureWrap wrapU, TextureWrap wrapV,
            TextureFilter filter);
    int width() const { return image_->width(); }
    int height() const { return image_->height(); }
    const std::shared_ptr<const TextureImage>& image() const { return image_; }
    // The filtered texel at texture coordinates uv, its texels read in colour space `space`.
    Texel lookup(Vec2 uv, ColourSpace space = ColourSpace::Linear) const;
    // Per channel, the largest value a lookup in colour space `space` anywhere on the triangle of
    // texture coordinates `corners` can return: the largest among the texels it can read (those
    // whose cell, widened by half a texel for bilinear filtering, the triangle overlaps); the
    // whole image's largest when the triangle's bounds span more cells than four images' worth
    // (or 2^20), where finding them would cost more than the answer is worth.
    Texel maxOver(const std::array<Vec2, 3>& corners, ColourSpace space = ColourSpace::Linear) const;

private:
    template <class T>
    Texel lookupIn(const TexelArray<T>& texels, Vec2 uv, ColourSpace space) const;
    template <class T>
    Texel maxIn(const TexelArray<T>& texels, const std::array<Vec2, 3>& corners, ColourSpace space) const;

    std::shared_ptr<const TextureImage> image_;
    TextureWrap wrapU_, wrapV_;
    TextureFilter filter_;
};

// The two texture coordinate sets (TEXCOORD_0, TEXCOORD_1) at one point.
using TexCoords = std::array<Vec2, 2>;

// A material's use of one texture: glTF's textureInfo with its KHR_texture_transform.
struct TextureSlot {
    std::shared_ptr<const Texture> texture;  // null: the slot is unused
    int texCoord = 0;                        // 0 or 1
    // uv' = M · (u, v, 1): the extension's translation · rotation · scale, identity without it.
    std::array<float, 6> transform{1, 0, 0, 0, 1, 0};
    ColourSpace colourSpace = ColourSpace::Linear;  // of the colour channels; alpha reads linear

    explicit operator bool() const { return texture != nullptr; }
    Texel lookup(const TexCoords& uv) const;
    // Texture::maxOver for the triangle whose corners have the coordinates `corners`.
    Texel maxOver(const TexCoords corners[3]) const;
    // The coordinates this slot reads the texture at: its set of uv, transformed.
    Vec2 transformed(const TexCoords& uv) const;
    // A normal texel's lean, (x, y) in the texture's tangent space (x toward +u', y up its image,
    // toward −v'), in the mesh's (toward +u and −v): turned by the inverse of the transform's
    // linear part, whose axes the texture's tangent space follows, its length kept.
    Vec2 leanInMeshFrame(Vec2 lean) const;
};

// The vertex colour (COLOR_0) multiplies what these give, where a mesh has one: its RGB the base
// colour (Scene::bsdfAt), its alpha the alpha a mask compares with the cutoff (`vertexAlpha`, 1
// without one).
struct MaterialTextures {
    TextureSlot baseColor;          // RGB × BsdfParams::albedo; A × baseAlpha
    TextureSlot metallicRoughness;  // B × metallic, G × roughness
    TextureSlot normal;             // tangent-space normal, (2 t − 1) with x, y × normalScale
    TextureSlot emissive;           // RGB × Material::emission
    float baseAlpha = 1.0f;         // baseColorFactor's alpha
    float normalScale = 1.0f;
    float alphaCutoff = -1.0f;      // alphaMode MASK: alpha below it is a hole; negative when opaque

    bool masks() const { return alphaCutoff >= 0; }
    // The BSDF parameters at a point of coordinates uv, the material's factors being `factors`.
    BsdfParams at(const BsdfParams& factors, const TexCoords& uv) const;
    // Whether the emission varies over the surface: an emissive texture, or holes that emit nothing.
    bool variesEmission() const { return emissive || masks(); }
    // The emitted radiance at a point, the material's emission being `factor`: 0 in a hole.
    Spectrum emissionAt(Spectrum factor, const TexCoords& uv, float vertexAlpha) const;
    // Per channel, a bound on emissionAt over the triangle of corner coordinates `corners`, whose
    // vertex alpha is at most `maxVertexAlpha`: 0 only where no point of it can emit (its emissive
    // texels there are black, or its alpha is below the cutoff throughout).
    Spectrum emissionBound(Spectrum factor, const TexCoords corners[3], float maxVertexAlpha) const;
    // Whether the surface is a hole at a point (alpha below the cutoff); false unless masking.
    bool holeAt(const TexCoords& uv, float vertexAlpha) const;
    // The tangent-space normal (x, y, z) the normal texture gives at a point; (0, 0, 1) without one.
    Vec3 tangentNormalAt(const TexCoords& uv) const;
};

}  // namespace tripath
