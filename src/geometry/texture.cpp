// Texture lookups and a textured material's parameters at a point (texture.h).
//
// Texel (x, y) covers [x/w, (x+1)/w] × [y/h, (y+1)/h] in texture coordinates, so nearest
// filtering takes the texel under uv and bilinear filtering weighs the four texels whose centres
// surround it (OpenGL's convention, which glTF's samplers name).
#include "geometry/texture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace tripath {

namespace {

// Wraps an integer texel index into [0, n) by the sampler's mode.
int wrapIndex(int64_t i, int n, TextureWrap mode) {
    switch (mode) {
    case TextureWrap::ClampToEdge: return int(std::clamp<int64_t>(i, 0, n - 1));
    case TextureWrap::MirroredRepeat: {
        const int64_t m = ((i % (2 * int64_t(n))) + 2 * int64_t(n)) % (2 * int64_t(n));
        return int(m < n ? m : 2 * int64_t(n) - 1 - m);
    }
    case TextureWrap::Repeat: break;
    }
    return int(((i % n) + n) % n);
}

// A texture coordinate scaled to texels, as a float index kept within int64's range (coordinates
// beyond ±2^40 texels repeat or clamp all the same); a non-finite one reads as 0.
double texelCoordinate(float c, int n) {
    const double x = double(c) * n;
    return std::isfinite(x) ? std::clamp(x, -0x1p40, 0x1p40) : 0.0;
}

Texel lerp(const Texel& a, const Texel& b, float t) {
    Texel r;
    for (int c = 0; c < 4; ++c) r[c] = a[c] + (b[c] - a[c]) * t;
    return r;
}

}  // namespace

Texture::Texture(int width, int height, std::vector<Texel> texels, TextureWrap wrapU, TextureWrap wrapV,
                 TextureFilter filter)
    : width_(width), height_(height), texels_(std::move(texels)), wrapU_(wrapU), wrapV_(wrapV), filter_(filter) {}

Texel Texture::texel(int x, int y) const { return texels_[size_t(y) * size_t(width_) + size_t(x)]; }

Texel Texture::lookup(Vec2 uv) const {
    const double x = texelCoordinate(uv.x, width_), y = texelCoordinate(uv.y, height_);
    if (filter_ == TextureFilter::Nearest)
        return texel(wrapIndex(int64_t(std::floor(x)), width_, wrapU_),
                     wrapIndex(int64_t(std::floor(y)), height_, wrapV_));
    const double x0 = std::floor(x - 0.5), y0 = std::floor(y - 0.5);
    const float fx = float(x - 0.5 - x0), fy = float(y - 0.5 - y0);
    const int xa = wrapIndex(int64_t(x0), width_, wrapU_), xb = wrapIndex(int64_t(x0) + 1, width_, wrapU_);
    const int ya = wrapIndex(int64_t(y0), height_, wrapV_), yb = wrapIndex(int64_t(y0) + 1, height_, wrapV_);
    return lerp(lerp(texel(xa, ya), texel(xb, ya), fx), lerp(texel(xa, yb), texel(xb, yb), fx), fy);
}

Texel TextureSlot::lookup(const TexCoords& uv) const {
    const Vec2 c = uv[size_t(texCoord)];
    const auto& m = transform;
    return texture->lookup({m[0] * c.x + m[1] * c.y + m[2], m[3] * c.x + m[4] * c.y + m[5]});
}

BsdfParams MaterialTextures::at(const BsdfParams& factors, const TexCoords& uv) const {
    BsdfParams p = factors;
    if (baseColor) {
        const Texel t = baseColor.lookup(uv);
        p.albedo = p.albedo * Spectrum(t[0], t[1], t[2]);
    }
    if (metallicRoughness) {
        const Texel t = metallicRoughness.lookup(uv);
        p.roughness = std::clamp(p.roughness * t[1], 0.0f, 1.0f);
        p.metallic = std::clamp(p.metallic * t[2], 0.0f, 1.0f);
    }
    return p;
}

Spectrum MaterialTextures::emissionAt(Spectrum factor, const TexCoords& uv) const {
    if (holeAt(uv)) return Spectrum(0.0f);
    if (!emissive) return factor;
    const Texel t = emissive.lookup(uv);
    return factor * Spectrum(t[0], t[1], t[2]);
}

bool MaterialTextures::holeAt(const TexCoords& uv) const {
    if (!masks()) return false;
    const float alpha = baseAlpha * (baseColor ? baseColor.lookup(uv)[3] : 1.0f);
    return alpha < alphaCutoff;
}

Vec3 MaterialTextures::tangentNormalAt(const TexCoords& uv) const {
    if (!normal) return {0, 0, 1};
    const Texel t = normal.lookup(uv);
    return {(2 * t[0] - 1) * normalScale, (2 * t[1] - 1) * normalScale, 2 * t[2] - 1};
}

}  // namespace tripath
