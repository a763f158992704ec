// Texture coordinates, tangents and vertex colours of triangles (surface_textures.h).
#include "geometry/surface_textures.h"

#include <algorithm>
#include <cmath>

#include "core/sampling.h"

namespace tripath {

TexCoords TriangleTexCoords::at(Vec2 b) const {
    const float w0 = 1.0f - b.x - b.y;
    TexCoords uv;
    for (size_t set = 0; set < 2; ++set)
        uv[set] = {corner[0][set].x * w0 + corner[1][set].x * b.x + corner[2][set].x * b.y,
                   corner[0][set].y * w0 + corner[1][set].y * b.x + corner[2][set].y * b.y};
    return uv;
}

Texel TriangleColours::at(Vec2 b) const {
    const float w0 = 1.0f - b.x - b.y;
    Texel c;
    for (size_t k = 0; k < 4; ++k) c[k] = corner[0][k] * w0 + corner[1][k] * b.x + corner[2][k] * b.y;
    return c;
}

float TriangleColours::maxAlpha() const { return std::max({corner[0][3], corner[1][3], corner[2][3]}); }

bool TriangleSurface::holeAt(Vec2 b) const { return textures && textures->holeAt(uvAt(b), alphaAt(b)); }

void SurfaceTextures::add(uint32_t first, uint32_t count, const MaterialTextures* material,
                          std::vector<TriangleTexCoords> texCoords, std::vector<TriangleColours> colours) {
    if (count == 0 || (texCoords.empty() && colours.empty())) return;
    ranges_.push_back({first, texCoords.empty() ? kNone : texCoords_.size(), colours.empty() ? kNone : colours_.size(),
                       material});
    texCoords_.insert(texCoords_.end(), texCoords.begin(), texCoords.end());
    colours_.insert(colours_.end(), colours.begin(), colours.end());
    rangeOf_.resize(size_t(first) + count, kNoRange);
    std::fill(rangeOf_.begin() + first, rangeOf_.end(), uint32_t(ranges_.size() - 1));
}

bool SurfaceTextures::anyMasks() const {
    return std::any_of(ranges_.begin(), ranges_.end(), [](const Range& r) { return r.material && r.material->masks(); });
}

bool triangleTangent(const Vec3 p[3], const Vec2 uv[3], Vec3 ng, Vec3& tangent, float& sign) {
    const Vec3 dp1 = p[1] - p[0], dp2 = p[2] - p[0];
    const Vec2 d1{uv[1].x - uv[0].x, uv[1].y - uv[0].y}, d2{uv[2].x - uv[0].x, uv[2].y - uv[0].y};
    const float det = d1.x * d2.y - d2.x * d1.y;
    const Vec3 dpdu = (dp1 * d2.y - dp2 * d1.y) / det, dpdv = (dp2 * d1.x - dp1 * d2.x) / det;
    const Vec3 t = dpdu - ng * dot(ng, dpdu);
    if (!(det != 0) || !isFinite(t) || !(lengthSquared(t) > 0) || !isFinite(dpdv)) {
        tangent = Frame(ng).s;
        sign = 1.0f;
        return false;
    }
    tangent = normalize(t);
    sign = dot(cross(ng, tangent), -dpdv) < 0 ? -1.0f : 1.0f;
    return true;
}

Vec3 perturbNormal(Vec3 n, Vec3 tangent, float bitangentSign, Vec3 t) {
    Vec3 s = tangent - n * dot(n, tangent);
    s = lengthSquared(s) > 0 ? normalize(s) : Frame(n).s;
    const Vec3 b = cross(n, s) * bitangentSign;
    const Vec3 mapped = s * t.x + b * t.y + n * t.z;
    if (!isFinite(mapped) || !(lengthSquared(mapped) > 0)) return n;
    return normalize(mapped);
}

Spectrum emissionAt(const TriangleSurface& surface, Spectrum factor, Vec2 b) {
    return surface.textures->emissionAt(factor, surface.uvAt(b), surface.alphaAt(b));
}

double texturedEmitterPower(const TriangleSurface& surface, Spectrum factor, float area) {
    constexpr int kGrid = 16;
    double sum = 0;
    for (int j = 0; j < kGrid; ++j)
        for (int i = 0; i < kGrid; ++i) {
            const Vec2 b = sampleUniformTriangle({(i + 0.5f) / kGrid, (j + 0.5f) / kGrid});
            sum += std::max(0.0f, luminance(emissionAt(surface, factor, b)));
        }
    if (!(sum > 0))
        sum = std::max(0.0f, luminance(surface.textures->emissionBound(factor, surface.texCoords->corner,
                                                                      surface.maxAlpha())));
    return double(area) * sum / (kGrid * kGrid);
}

}  // namespace tripath
