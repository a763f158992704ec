// Where textured materials meet the triangles: the texture coordinates and tangents of every
// triangle whose material has textures, kept apart from Triangle so that untextured meshes pay
// nothing, and found from a triangle's index by the range of triangles its mesh became.
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

class SurfaceTextures {
public:
    // Adds the records of triangles [first, first + records.size()), whose material's textures
    // are `material`; ranges must be added in increasing order of `first`.
    void add(uint32_t first, const MaterialTextures* material, std::vector<TriangleTexCoords> records);
    // The record of a triangle, or null when its material has no textures.
    const TriangleTexCoords* find(uint32_t triangle) const;
    // The textures of a triangle's material, or null.
    const MaterialTextures* materialOf(uint32_t triangle) const;
    bool anyMasks() const;

private:
    struct Range {
        uint32_t first, end;
        size_t offset;  // of its first record
        const MaterialTextures* material;
    };
    const Range* rangeOf(uint32_t triangle) const;
    std::vector<Range> ranges_;
    std::vector<TriangleTexCoords> records_;
};

// The tangent of a triangle of corners p with texture coordinates uv (one set) from the uv
// derivatives, MikkTSpace's per-triangle construction: dp/du, and the sign that makes
// sign · (n × tangent) point along −dp/dv (up the image: glTF's v runs down it). False when the
// mapping is degenerate (the tangent is then any direction in the plane).
bool triangleTangent(const Vec3 p[3], const Vec2 uv[3], Vec3 ng, Vec3& tangent, float& sign);

// The normal a normal texture gives: the tangent-space normal t (x, y scaled) mapped through the
// frame of the shading normal n and the tangent, orthonormalised against n (Gram-Schmidt).
Vec3 perturbNormal(Vec3 n, Vec3 tangent, float bitangentSign, Vec3 t);

// The power weight of a textured emitter triangle: its area times the average luminance of its
// emission over it, from the emission at the centres of a 16 × 16 stratified grid of points
// uniform by area (sampleUniformTriangle of the cell centres). Where every point is dark but the
// texels under the triangle can emit (one bright texel between the points), the weight is as if
// one point had seen the brightest of them, so that every triangle that emits anywhere keeps a
// choice probability above 0; 0 only for a triangle that emits nowhere.
double texturedEmitterPower(const MaterialTextures& textures, Spectrum factor, const TriangleTexCoords& uv,
                            float area);

}  // namespace tripath
