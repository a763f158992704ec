// Where textured materials and vertex colours meet the triangles: the texture coordinates and
// tangents of every triangle whose material has textures, and the corner colours (glTF's COLOR_0)
// of every triangle whose mesh has them, kept apart from Triangle so that meshes without either
// pay nothing, in ranges of triangles, one per mesh. Each triangle up to the last range's end
// names its range, so that a lookup (the alpha-mask filter's, on every candidate hit) is one read
// rather than a search: 4 bytes per triangle, in scenes that have a range at all.
//
// Shared (shared_ptr) by a Scene and its copies at other image sizes, since Embree's alpha-mask
// filter (scene.cpp) reads it through the BVH they share.
#pragma once
#include <cstdint>
#include <vector>

#include "geometry/texture.h"
#include "core/vec.h"

namespace tripath {

// A textured triangle's per-corner texture coordinates and tangent frame.
struct TriangleTexCoords {
    TexCoords corner[3];
    Vec3 tangent[3];             // per corner; only set for a material with a normal texture
    float bitangentSign = 1.0f;  // bitangent = sign · (n × tangent): the uv mapping's handedness

    // The texture coordinates at barycentrics b (of corners 1 and 2).
    TexCoords at(Vec2 b) const;
};

// A coloured triangle's per-corner vertex colour: linear RGBA in [0, 1].
struct TriangleColours {
    Texel corner[3];

    // The colour at barycentrics b, interpolated linearly.
    Texel at(Vec2 b) const;
    // The largest alpha anywhere on the triangle: its corners' (the interpolation is convex).
    float maxAlpha() const;
};

// What varies over one triangle besides its normals; each part null where it has none.
struct TriangleSurface {
    const MaterialTextures* textures = nullptr;    // its material's
    const TriangleTexCoords* texCoords = nullptr;  // set whenever `textures` is
    const TriangleColours* colours = nullptr;      // its mesh's COLOR_0

    // The texture coordinates at barycentrics b; zero without texture coordinates.
    TexCoords uvAt(Vec2 b) const { return texCoords ? texCoords->at(b) : TexCoords{}; }
    // The vertex colour's alpha at b (1 without colours), and its largest on the triangle.
    float alphaAt(Vec2 b) const { return colours ? colours->at(b)[3] : 1.0f; }
    float maxAlpha() const { return colours ? colours->maxAlpha() : 1.0f; }
    // Whether the surface is a hole at b: the material masks and its alpha there, the vertex
    // colour's included, is below the cutoff.
    bool holeAt(Vec2 b) const;
};

class SurfaceTextures {
public:
    // Adds triangles [first, first + count): `material` the textures of their material (null when
    // it has none), `texCoords` one record per triangle when it has, `colours` one per triangle
    // when their mesh has vertex colours, else empty. Ranges must be added in increasing order of
    // `first`; a range with neither records is not kept.
    void add(uint32_t first, uint32_t count, const MaterialTextures* material, std::vector<TriangleTexCoords> texCoords,
             std::vector<TriangleColours> colours);
    // A triangle's textures, texture coordinates and colours, each null where it has none.
    TriangleSurface find(uint32_t triangle) const {
        if (triangle >= rangeOf_.size() || rangeOf_[triangle] == kNoRange) return {};
        const Range& r = ranges_[rangeOf_[triangle]];
        const uint32_t i = triangle - r.first;
        return {r.material, r.texCoords == kNone ? nullptr : &texCoords_[r.texCoords + i],
                r.colours == kNone ? nullptr : &colours_[r.colours + i]};
    }
    bool anyMasks() const;
    bool anyColours() const { return !colours_.empty(); }
    // The memory its per-triangle records take (the texture images are the materials').
    size_t bytes() const {
        return ranges_.capacity() * sizeof(Range) + texCoords_.capacity() * sizeof(TriangleTexCoords) +
               colours_.capacity() * sizeof(TriangleColours);
    }

private:
    static constexpr size_t kNone = ~size_t(0);
    static constexpr uint32_t kNoRange = ~uint32_t(0);
    struct Range {
        uint32_t first;
        size_t texCoords, colours;  // the offsets of its first records, or kNone
        const MaterialTextures* material;
    };
    std::vector<Range> ranges_;
    std::vector<uint32_t> rangeOf_;  // per triangle up to the last range's end: its range in ranges_, or kNoRange
    std::vector<TriangleTexCoords> texCoords_;
    std::vector<TriangleColours> colours_;
};

// The tangent of a triangle of corners p with texture coordinates uv (one set) from the uv
// derivatives, MikkTSpace's per-triangle construction: dp/du, and the sign that makes
// sign · (n × tangent) point along −dp/dv (up the image: glTF's v runs down it). False when the
// mapping is degenerate (the tangent is then any direction in the plane).
bool triangleTangent(const Vec3 p[3], const Vec2 uv[3], Vec3 ng, Vec3& tangent, float& sign);

// The normal a normal texture gives: the tangent-space normal t (x, y scaled) mapped through the
// frame of the shading normal n and the tangent, orthonormalised against n (Gram-Schmidt).
Vec3 perturbNormal(Vec3 n, Vec3 tangent, float bitangentSign, Vec3 t);

// The emitted radiance of a textured emitter triangle at barycentrics b, its material's emission
// being `factor`: MaterialTextures::emissionAt there, 0 in a hole.
Spectrum emissionAt(const TriangleSurface& surface, Spectrum factor, Vec2 b);

// The power weight of a textured emitter triangle: its area times the average luminance of its
// emission over it, from the emission at the centres of a 16 × 16 stratified grid of points
// uniform by area (sampleUniformTriangle of the cell centres). Where every point is dark but the
// texels under the triangle can emit (one bright texel between the points), the weight is as if
// one point had seen the brightest of them, so that every triangle that emits anywhere keeps a
// choice probability above 0; 0 only for a triangle that emits nowhere.
double texturedEmitterPower(const TriangleSurface& surface, Spectrum factor, float area);

}  // namespace tripath
