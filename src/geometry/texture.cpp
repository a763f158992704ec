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

// Whether the triangle t (texel units) and the box [x0, x1] × [y0, y1] overlap, by separating
// axes: the box's own (the caller's range) and each edge's normal. Conservative: a degenerate
// edge separates nothing, and the box is widened by a thousandth of a texel against rounding.
bool overlaps(const std::array<Vec2, 3>& t, double x0, double y0, double x1, double y1) {
    constexpr double kMargin = 1e-3;
    x0 -= kMargin, y0 -= kMargin, x1 += kMargin, y1 += kMargin;
    for (int e = 0; e < 3; ++e) {
        const Vec2 a = t[size_t(e)], b = t[size_t(e + 1) % 3], c = t[size_t(e + 2) % 3];
        const double nx = double(a.y) - b.y, ny = double(b.x) - a.x;  // the edge's normal
        auto side = [&](double x, double y) { return nx * (x - a.x) + ny * (y - a.y); };
        const double inside = side(c.x, c.y);
        if (inside == 0) continue;
        const bool separated = inside > 0 ? std::max({side(x0, y0), side(x1, y0), side(x0, y1), side(x1, y1)}) < 0
                                          : std::min({side(x0, y0), side(x1, y0), side(x0, y1), side(x1, y1)}) > 0;
        if (separated) return false;
    }
    return true;
}

Texel lerp(const Texel& a, const Texel& b, float t) {
    Texel r;
    for (int c = 0; c < 4; ++c) r[c] = a[c] + (b[c] - a[c]) * t;
    return r;
}

}  // namespace

Texture::Texture(std::shared_ptr<const TextureImage> image, TextureWrap wrapU, TextureWrap wrapV, TextureFilter filter)
    : image_(std::move(image)), wrapU_(wrapU), wrapV_(wrapV), filter_(filter) {}

Texture::Texture(int width, int height, std::vector<Texel> texels, TextureWrap wrapU, TextureWrap wrapV,
                 TextureFilter filter)
    : Texture(std::make_shared<const TextureImage>(width, height, std::move(texels)), wrapU, wrapV, filter) {}

Texel Texture::lookup(Vec2 uv, ColourSpace space) const {
    return image_->visit([&](const auto& texels) { return lookupIn(texels, uv, space); });
}

template <class T>
Texel Texture::lookupIn(const TexelArray<T>& texels, Vec2 uv, ColourSpace space) const {
    const int w = width(), h = height();
    // The texel at x, y (already wrapped into the image), as it reads.
    auto at = [&](int x, int y) { return decodedTexel(texels[size_t(y) * size_t(w) + size_t(x)], space); };
    const double x = texelCoordinate(uv.x, w), y = texelCoordinate(uv.y, h);
    if (filter_ == TextureFilter::Nearest)
        return at(wrapIndex(int64_t(std::floor(x)), w, wrapU_), wrapIndex(int64_t(std::floor(y)), h, wrapV_));
    const double x0 = std::floor(x - 0.5), y0 = std::floor(y - 0.5);
    const float fx = float(x - 0.5 - x0), fy = float(y - 0.5 - y0);
    const int xa = wrapIndex(int64_t(x0), w, wrapU_), xb = wrapIndex(int64_t(x0) + 1, w, wrapU_);
    const int ya = wrapIndex(int64_t(y0), h, wrapV_), yb = wrapIndex(int64_t(y0) + 1, h, wrapV_);
    return lerp(lerp(at(xa, ya), at(xb, ya), fx), lerp(at(xa, yb), at(xb, yb), fx), fy);
}

Texel Texture::maxOver(const std::array<Vec2, 3>& corners, ColourSpace space) const {
    return image_->visit([&](const auto& texels) { return maxIn(texels, corners, space); });
}

// The largest stored values first, then read: reading is nondecreasing (texture_image.h).
template <class T>
Texel Texture::maxIn(const TexelArray<T>& texels, const std::array<Vec2, 3>& corners, ColourSpace space) const {
    const int w = width(), h = height();
    std::array<Vec2, 3> t;  // the corners in texel units
    double x0 = 0x1p40, y0 = 0x1p40, x1 = -0x1p40, y1 = -0x1p40;
    for (size_t k = 0; k < 3; ++k) {
        if (!std::isfinite(corners[k].x) || !std::isfinite(corners[k].y)) return image_->largest(space);
        t[k] = {float(texelCoordinate(corners[k].x, w)), float(texelCoordinate(corners[k].y, h))};
        x0 = std::min(x0, double(t[k].x)), x1 = std::max(x1, double(t[k].x));
        y0 = std::min(y0, double(t[k].y)), y1 = std::max(y1, double(t[k].y));
    }
    // Texel i is read by nearest lookups in [i, i + 1), by bilinear ones in [i − ½, i + 1½).
    const double widen = filter_ == TextureFilter::Linear ? 0.5 : 0.0;
    const auto i0 = int64_t(std::floor(x0 - widen)), i1 = int64_t(std::floor(x1 + widen));
    const auto j0 = int64_t(std::floor(y0 - widen)), j1 = int64_t(std::floor(y1 + widen));
    const double cells = double(i1 - i0 + 1) * double(j1 - j0 + 1);
    if (cells > std::min(4.0 * w * h + 64, 0x1p20)) return image_->largest(space);
    std::array<T, 4> m{};
    for (int64_t j = j0; j <= j1; ++j)
        for (int64_t i = i0; i <= i1; ++i)
            if (overlaps(t, double(i) - widen, double(j) - widen, double(i) + 1 + widen, double(j) + 1 + widen))
                m = channelMax(m, texels[size_t(wrapIndex(j, h, wrapV_)) * size_t(w) + size_t(wrapIndex(i, w, wrapU_))]);
    return decodedTexel(m, space);
}

Texel TextureSlot::maxOver(const TexCoords corners[3]) const {
    return texture->maxOver({transformed(corners[0]), transformed(corners[1]), transformed(corners[2])}, colourSpace);
}

Vec2 TextureSlot::transformed(const TexCoords& uv) const {
    const Vec2 c = uv[size_t(texCoord)];
    const auto& m = transform;
    return {m[0] * c.x + m[1] * c.y + m[2], m[3] * c.x + m[4] * c.y + m[5]};
}

Texel TextureSlot::lookup(const TexCoords& uv) const { return texture->lookup(transformed(uv), colourSpace); }

// The texture's axes on the surface are ∂P/∂u' and ∂P/∂v', the columns of ∂P/∂(u, v) · A⁻¹ with A
// the transform's linear part; with y up the image on both sides, (x, y) → F A⁻¹ F (x, y),
// F = diag(1, −1). A scale that is not uniform skews those axes: the lean keeps its length and
// takes the direction.
Vec2 TextureSlot::leanInMeshFrame(Vec2 lean) const {
    const auto& m = transform;
    if (m[0] == 1 && m[1] == 0 && m[3] == 0 && m[4] == 1) return lean;
    const float det = m[0] * m[4] - m[1] * m[3];
    const Vec2 turned{(m[4] * lean.x + m[1] * lean.y) / det, (m[3] * lean.x + m[0] * lean.y) / det};
    const float before = std::hypot(lean.x, lean.y), after = std::hypot(turned.x, turned.y);
    if (!(after > 0)) return lean;
    return {turned.x * (before / after), turned.y * (before / after)};
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

Spectrum MaterialTextures::emissionAt(Spectrum factor, const TexCoords& uv, float vertexAlpha) const {
    if (holeAt(uv, vertexAlpha)) return Spectrum(0.0f);
    if (!emissive) return factor;
    const Texel t = emissive.lookup(uv);
    return factor * Spectrum(t[0], t[1], t[2]);
}

Spectrum MaterialTextures::emissionBound(Spectrum factor, const TexCoords corners[3], float maxVertexAlpha) const {
    if (masks() && baseAlpha * (baseColor ? baseColor.maxOver(corners)[3] : 1.0f) * maxVertexAlpha < alphaCutoff)
        return Spectrum(0.0f);
    if (!emissive) return factor;
    const Texel t = emissive.maxOver(corners);
    return factor * Spectrum(t[0], t[1], t[2]);
}

bool MaterialTextures::holeAt(const TexCoords& uv, float vertexAlpha) const {
    if (!masks()) return false;
    const float alpha = baseAlpha * (baseColor ? baseColor.lookup(uv)[3] : 1.0f) * vertexAlpha;
    return alpha < alphaCutoff;
}

Vec3 MaterialTextures::tangentNormalAt(const TexCoords& uv) const {
    if (!normal) return {0, 0, 1};
    const Texel t = normal.lookup(uv);
    const Vec2 lean = normal.leanInMeshFrame({(2 * t[0] - 1) * normalScale, (2 * t[1] - 1) * normalScale});
    return {lean.x, lean.y, 2 * t[2] - 1};
}

}  // namespace tripath
