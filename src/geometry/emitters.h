// Emitters and how a point on them is sampled: emissive triangles (area lights) chosen in
// proportion to their power, points uniform by area; and point lights (delta in position).
// Every pdf is in area measure: picking probability × 1/area (DESIGN.md §1). A point light's
// "area pdf" is its picking probability alone: a delta in position (Vertex::isDeltaLight).
#pragma once
#include <vector>

#include "geometry/material.h"
#include "core/sampling.h"
#include "core/vec.h"

namespace tripath {

struct Triangle;
class SurfaceTextures;
struct MaterialTextures;
struct TriangleTexCoords;

struct Emitter {
    enum class Kind { Triangle, Point } kind = Kind::Triangle;
    uint32_t triangle = 0;   // for Kind::Triangle
    Vec3 position;           // for Kind::Point
    Spectrum radiance;       // Le for triangles; radiant intensity I (W/sr) for point lights
    bool twoSided = false;
    float area = 0;          // triangle area
    double power = 0;        // Φ, for the choice distribution
    // A triangle whose material has an emissive texture or alpha holes: Le = radiance × the
    // texture there, 0 in a hole.
    const MaterialTextures* textures = nullptr;
    const TriangleTexCoords* texCoords = nullptr;
};

struct EmitterSample {
    Vec3 p;
    Vec3 n;                  // surface normal (front face) of a triangle emitter; zero for a point light
    uint32_t emitter = 0;    // index into Emitters::all()
    Vec2 bary;               // barycentrics of p on a triangle emitter (corners 1 and 2)
    float pdfA = 0;          // area-measure pdf of p (picking probability for a point light)
};

class Emitters {
public:
    Emitters() = default;
    // `triangles` must outlive this object's use of emitterOfTriangle; `textures` (the triangles'
    // texture coordinates, null when none has any) and the materials' textures its use of Le.
    // A triangle whose material has an emissive texture or alpha holes is weighed by its textured
    // power, and is no emitter where that is 0.
    Emitters(const std::vector<Triangle>& triangles, const std::vector<Material>& materials,
             const std::vector<Emitter>& pointLights, const SurfaceTextures* textures = nullptr);

    bool empty() const { return all_.empty(); }
    const std::vector<Emitter>& all() const { return all_; }
    // Index of the emitter a triangle belongs to, or -1.
    int emitterOfTriangle(uint32_t triangle) const { return byTriangle_[triangle]; }

    // Samples an emitter by power, then a point on it uniformly by area. u in [0,1)², uc in [0,1).
    EmitterSample sample(float uc, Vec2 u, const std::vector<Triangle>& triangles) const;
    // The area pdf with which sample() produces a given point on emitter e.
    float pdfA(int e) const { return pdfA_[e]; }

    // A direction for light to leave a point of emitter e (front normal n): cosine-weighted over
    // the emitting hemisphere(s) of a triangle, uniform over the sphere for a point light.
    Vec3 sampleDirection(int e, Vec3 frontNormal, Vec2 u, float uc) const;
    // Solid-angle pdf of sampleDirection producing ω.
    float directionPdf(int e, Vec3 frontNormal, Vec3 omega) const;

    // Emitted radiance Le(x → ω) of emitter e leaving along unit ω (front face only unless
    // two-sided), x at barycentrics `bary` of a triangle emitter.
    Spectrum Le(int e, Vec3 frontNormal, Vec3 omega, Vec2 bary) const;

private:
    std::vector<Emitter> all_;
    std::vector<int> byTriangle_;
    Distribution1D choice_;
    std::vector<float> pdfA_;  // per emitter, found once: next-event estimation asks at every vertex
};

}  // namespace tripath
