// Emitters and how a point on them is sampled: emissive triangles (area lights), point and spot
// lights (deltas in position), directional lights (deltas in direction) and the environment
// (radiance from every direction, environment.h). One is chosen in proportion to its power Φ:
//     triangle     Φ = π A Le (per emitting face)     point        Φ = 4π I
//     (Le textured: its mean over the triangle)
//     spot         Φ = I ∫ t² dω over its cone         directional  Φ = π R² E
//     environment  Φ = π R² ∫ L(ω) dω
// (luminance of each; R the radius of the scene's bounding sphere, whose disc of area π R² every
// ray from an emitter at infinity crosses).
//
// Measures (docs/design.md §2, the vertex at infinity). A point on a triangle is measured by area,
// so its pdf is picking probability × 1/area; a point or spot light's "area pdf" is its picking
// probability alone (a delta in position). An emitter at infinity is a direction, measured in
// solid angle: the environment's pdf is picking probability × its map's solid-angle density; a
// directional light's is the picking probability (a delta in direction). Light leaving an emitter
// at infinity crosses the bounding disc, facing it, at a point drawn uniformly: its density is
// 1/(π R²) per unit area across the beam, which becomes an area density at the first surface by
// that surface's cosine, as a solid-angle density does with cos / r² at a finite emitter.
#pragma once
#include <memory>
#include <vector>

#include "geometry/environment.h"
#include "geometry/material.h"
#include "geometry/surface_textures.h"
#include "core/sampling.h"
#include "core/vec.h"

namespace tripath {

struct Triangle;

struct Emitter {
    enum class Kind { Triangle, Point, Spot, Directional, Environment } kind = Kind::Triangle;
    uint32_t triangle = 0;   // Triangle
    Vec3 position;           // Point, Spot
    Vec3 axis;               // Spot: unit direction of its beam; Directional: unit direction toward the light
    Spectrum radiance;       // Le (Triangle); I in W/sr (Point, Spot); E in W/m² (Directional); unused (Environment: its map)
    float cosInner = 1, cosOuter = 0;  // Spot: full intensity inside the inner cone, none outside the outer
    bool twoSided = false;
    float area = 0;          // Triangle
    double power = 0;        // Φ, for the choice distribution
    // A triangle whose material has an emissive texture or alpha holes (surface.textures set): Le
    // = radiance × the texture there, 0 in a hole (where its vertex colours' alpha counts too).
    TriangleSurface surface;
    bool atInfinity() const { return kind == Kind::Directional || kind == Kind::Environment; }
    bool delta() const { return kind == Kind::Point || kind == Kind::Spot || kind == Kind::Directional; }
};

struct EmitterSample {
    Vec3 p;                  // the point (finite emitters)
    Vec3 n;                  // surface normal (front face) of a triangle emitter; zero for the others
    Vec3 towardLight;        // unit direction toward an emitter at infinity; zero for the others
    uint32_t emitter = 0;    // index into Emitters::all()
    Vec2 bary;               // barycentrics of p on a triangle emitter (corners 1 and 2)
    float pdfA = 0;          // its pdf in the emitter's measure (area, or solid angle at infinity)
};

// The sphere around the scene's bounds that light from infinity is aimed at.
struct BoundingSphere {
    Vec3 centre;
    float radius = 0;
};

class Emitters {
public:
    Emitters() = default;
    // `triangles` must outlive this object's use of emitterOfTriangle; `textures` (the triangles'
    // texture coordinates and colours, null when none has any) and the materials' textures its
    // use of Le.
    // A triangle whose material has an emissive texture or alpha holes is weighed by its textured
    // power, and is no emitter where that is 0.
    Emitters(const std::vector<Triangle>& triangles, const std::vector<Material>& materials,
             const std::vector<Emitter>& lights, std::shared_ptr<const Environment> environment, BoundingSphere bounds,
             const SurfaceTextures* textures = nullptr);

    bool empty() const { return all_.empty(); }
    const std::vector<Emitter>& all() const { return all_; }
    // Index of the emitter a triangle belongs to, or -1.
    int emitterOfTriangle(uint32_t triangle) const { return byTriangle_[triangle]; }
    // Index of the environment emitter, or -1: what a ray that leaves the scene reaches.
    int environment() const { return environment_; }
    // Its map, null without one.
    const Environment* environmentMap() const { return environmentMap_.get(); }

    // Samples an emitter by power, then a point on it uniformly by area, or a direction from the
    // environment's map. u in [0,1)², uc in [0,1).
    EmitterSample sample(float uc, Vec2 u, const std::vector<Triangle>& triangles) const;
    // The pdf with which sample() produces a given point on emitter e (in its measure), or, for an
    // emitter at infinity, the direction `towardLight`.
    float pdfA(int e, Vec3 towardLight) const {
        return e == environment_ ? pdfA_[size_t(e)] * environmentMap_->pdf(towardLight) : pdfA_[size_t(e)];
    }

    // A direction for light to leave a point of finite emitter e (front normal n): cosine-weighted
    // over the emitting hemisphere(s) of a triangle, uniform over the sphere for a point light,
    // over the outer cone for a spot.
    Vec3 sampleDirection(int e, Vec3 frontNormal, Vec2 u, float uc) const;
    // A point on the bounding disc facing unit direction `towardLight`, where light from an emitter
    // at infinity starts toward the scene (along −towardLight); u in [0, 1)².
    Vec3 beamOrigin(Vec3 towardLight, Vec2 u) const;
    // The density with which emitter e generates the next vertex's direction: per unit solid angle
    // (sampleDirection) at a finite emitter, per unit area across the beam (beamOrigin) at infinity.
    float directionPdf(int e, Vec3 frontNormal, Vec3 omega) const;

    // Emitted radiance Le(x → ω) of emitter e leaving along unit ω (front face only unless
    // two-sided), x at barycentrics `bary` of a triangle emitter; I(ω) for point and spot lights, E
    // for a directional light.
    Spectrum Le(int e, Vec3 frontNormal, Vec3 omega, Vec2 bary) const {
        const Emitter& em = all_[size_t(e)];
        if (em.kind == Emitter::Kind::Triangle && !em.surface.textures)  // the common case, inline
            return em.twoSided || dot(frontNormal, omega) > 0 ? em.radiance : Spectrum(0.0f);
        return otherLe(em, frontNormal, omega, bary);
    }

private:
    // Le of a textured triangle or of an emitter that is not a triangle.
    Spectrum otherLe(const Emitter& em, Vec3 frontNormal, Vec3 omega, Vec2 bary) const;
    // Φ of a light that is not a triangle (the table above).
    double lightPower(const Emitter& e) const;

    std::vector<Emitter> all_;
    std::vector<int> byTriangle_;
    std::shared_ptr<const Environment> environmentMap_;
    int environment_ = -1;
    BoundingSphere bounds_;
    Distribution1D choice_;
    std::vector<float> pdfA_;  // per emitter, found once: next-event estimation asks at every vertex
};

}  // namespace tripath
