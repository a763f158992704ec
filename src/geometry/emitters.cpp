#include "geometry/emitters.h"

#include <algorithm>

#include "geometry/triangle.h"
#include "core/stats.h"

namespace tripath {

namespace {

constexpr Counter kEmitterSamples{Event::EmitterSamples};

// A spot's falloff t² with t = clamp((cos θ − cos θ_outer) / (cos θ_inner − cos θ_outer), 0, 1),
// KHR_lights_punctual's reference cone.
float spotFalloff(const Emitter& e, float cosTheta) {
    if (e.cosInner <= e.cosOuter) return cosTheta >= e.cosOuter ? 1.0f : 0.0f;
    const float t = std::clamp((cosTheta - e.cosOuter) / (e.cosInner - e.cosOuter), 0.0f, 1.0f);
    return t * t;
}

}  // namespace

Emitters::Emitters(const std::vector<Triangle>& triangles, const std::vector<Material>& materials,
                   const std::vector<Emitter>& lights, std::shared_ptr<const Environment> environment, BoundingSphere bounds,
                   const SurfaceTextures* textures)
    : byTriangle_(triangles.size(), -1), environmentMap_(std::move(environment)), bounds_(bounds) {
    for (uint32_t i = 0; i < triangles.size(); ++i) {
        const Material& m = materials[triangles[i].material];
        if (isBlack(m.emission)) continue;
        Emitter e;
        e.kind = Emitter::Kind::Triangle;
        e.triangle = i;
        e.radiance = m.emission;
        e.twoSided = m.twoSidedEmission;
        e.area = triangles[i].area();
        // Φ = π · A · L for a Lambertian emitter, per emitting face (L averaged over the triangle).
        double areaTimesL = double(e.area) * luminance(e.radiance);
        if (m.textures && m.textures->variesEmission()) {
            e.surface = textures ? textures->find(i) : TriangleSurface{};
            if (!e.surface.texCoords) continue;  // unreachable: a textured material's triangles have records
            areaTimesL = texturedEmitterPower(e.surface, e.radiance, e.area);
            if (!(areaTimesL > 0)) continue;
        }
        e.power = kPi * areaTimesL * (e.twoSided ? 2.0 : 1.0);
        byTriangle_[i] = static_cast<int>(all_.size());
        all_.push_back(e);
    }
    for (Emitter e : lights) {
        e.power = lightPower(e);
        all_.push_back(e);
    }
    if (environmentMap_ && environmentMap_->luminanceIntegral() > 0) {
        Emitter e;
        e.kind = Emitter::Kind::Environment;
        e.radiance = Spectrum(1.0f);
        e.power = lightPower(e);
        environment_ = static_cast<int>(all_.size());
        all_.push_back(e);
    }
    std::vector<double> power;
    for (const Emitter& e : all_) power.push_back(e.power);
    choice_ = Distribution1D(power);
    for (size_t i = 0; i < all_.size(); ++i) {
        const float pick = choice_.probability(i);
        pdfA_.push_back(all_[i].kind == Emitter::Kind::Triangle ? pick / all_[i].area : pick);
    }
}

double Emitters::lightPower(const Emitter& e) const {
    const double disc = kPi * double(bounds_.radius) * bounds_.radius;
    switch (e.kind) {
        case Emitter::Kind::Triangle: break;
        case Emitter::Kind::Point: return 4.0 * kPi * luminance(e.radiance);
        case Emitter::Kind::Spot: {
            // ∫ t² dω over the cone: the inner cone whole, and the falloff ring, where t is linear in
            // cos θ and dω = 2π d(cos θ), a third of its solid angle.
            const double inner = 2.0 * kPi * (1.0 - e.cosInner), ring = 2.0 * kPi * (e.cosInner - e.cosOuter);
            return luminance(e.radiance) * (inner + std::max(ring, 0.0) / 3.0);
        }
        case Emitter::Kind::Directional: return disc * luminance(e.radiance);
        case Emitter::Kind::Environment: return disc * environmentMap_->luminanceIntegral();
    }
    return 0;
}

EmitterSample Emitters::sample(float uc, Vec2 u, const std::vector<Triangle>& triangles) const {
    kEmitterSamples.add();
    const size_t i = choice_.sample(uc);
    const Emitter& e = all_[i];
    EmitterSample s;
    s.emitter = static_cast<uint32_t>(i);
    s.pdfA = pdfA_[i];
    switch (e.kind) {
        case Emitter::Kind::Triangle: {
            const Triangle& tri = triangles[e.triangle];
            const Vec2 b = sampleUniformTriangle(u);
            s.p = tri.p[0] * (1.0f - b.x - b.y) + tri.p[1] * b.x + tri.p[2] * b.y;
            s.bary = b;
            s.n = tri.geometricNormal();
            break;
        }
        case Emitter::Kind::Point:
        case Emitter::Kind::Spot: s.p = e.position; break;
        case Emitter::Kind::Directional: s.towardLight = e.axis; break;
        case Emitter::Kind::Environment:
            // The density of the direction as pdfA recomputes it from the direction, so that a
            // direction on a texel's edge has the one density every strategy gives it.
            s.towardLight = environmentMap_->sample(u).direction;
            s.pdfA = pdfA(static_cast<int>(i), s.towardLight);
            break;
    }
    return s;
}

Vec3 Emitters::sampleDirection(int e, Vec3 frontNormal, Vec2 u, float uc) const {
    const Emitter& em = all_[size_t(e)];
    if (em.kind == Emitter::Kind::Point) return sampleUniformSphere(u);
    if (em.kind == Emitter::Kind::Spot) return Frame(em.axis).toWorld(sampleUniformCone(u, em.cosOuter));
    const Vec3 local = sampleCosineHemisphere(u);
    const Vec3 n = em.twoSided && uc < 0.5f ? -frontNormal : frontNormal;
    return Frame(n).toWorld(local);
}

Vec3 Emitters::beamOrigin(Vec3 towardLight, Vec2 u) const {
    const Vec2 d = sampleUniformDisc(u);
    const Frame frame(towardLight);
    return bounds_.centre + (towardLight + frame.toWorld(Vec3(d.x, d.y, 0.0f))) * bounds_.radius;
}

float Emitters::directionPdf(int e, Vec3 frontNormal, Vec3 omega) const {
    const Emitter& em = all_[size_t(e)];
    switch (em.kind) {
        case Emitter::Kind::Point: return kUniformSpherePdf;
        case Emitter::Kind::Spot: return dot(omega, em.axis) >= em.cosOuter ? uniformConePdf(em.cosOuter) : 0.0f;
        case Emitter::Kind::Directional:
        case Emitter::Kind::Environment: return 1.0f / (kPi * bounds_.radius * bounds_.radius);
        case Emitter::Kind::Triangle: break;
    }
    const float c = dot(frontNormal, omega);
    if (em.twoSided) return 0.5f * std::abs(c) * kInvPi;
    return cosineHemispherePdf(c);
}

Spectrum Emitters::otherLe(const Emitter& em, Vec3 frontNormal, Vec3 omega, Vec2 bary) const {
    if (em.kind == Emitter::Kind::Triangle)  // textured
        return em.twoSided || dot(frontNormal, omega) > 0 ? emissionAt(em.surface, em.radiance, bary) : Spectrum(0.0f);
    if (em.kind == Emitter::Kind::Point || em.kind == Emitter::Kind::Directional) return em.radiance;
    if (em.kind == Emitter::Kind::Spot) return em.radiance * spotFalloff(em, dot(omega, em.axis));
    return environmentMap_->radiance(-omega);
}

}  // namespace tripath
