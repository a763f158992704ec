#include "geometry/emitters.h"

#include "geometry/surface_textures.h"
#include "geometry/triangle.h"
#include "core/stats.h"

namespace tripath {

namespace {
constexpr Counter kEmitterSamples{Event::EmitterSamples};
}  // namespace

Emitters::Emitters(const std::vector<Triangle>& triangles, const std::vector<Material>& materials,
                   const std::vector<Emitter>& pointLights, const SurfaceTextures* textures)
    : byTriangle_(triangles.size(), -1) {
    std::vector<double> power;
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
            e.textures = m.textures.get();
            e.texCoords = textures ? textures->find(i) : nullptr;
            if (!e.texCoords) continue;  // unreachable: a textured material's triangles have records
            areaTimesL = texturedEmitterPower(*e.textures, e.radiance, *e.texCoords, e.area);
            if (!(areaTimesL > 0)) continue;
        }
        e.power = kPi * areaTimesL * (e.twoSided ? 2.0 : 1.0);
        byTriangle_[i] = static_cast<int>(all_.size());
        all_.push_back(e);
        power.push_back(e.power);
    }
    for (Emitter e : pointLights) {
        e.kind = Emitter::Kind::Point;
        e.power = 4.0 * kPi * luminance(e.radiance);  // Φ = 4π · I
        all_.push_back(e);
        power.push_back(e.power);
    }
    choice_ = Distribution1D(power);
    for (size_t i = 0; i < all_.size(); ++i) {
        const float pick = choice_.probability(i);
        pdfA_.push_back(all_[i].kind == Emitter::Kind::Point ? pick : pick / all_[i].area);
    }
}

EmitterSample Emitters::sample(float uc, Vec2 u, const std::vector<Triangle>& triangles) const {
    kEmitterSamples.add();
    const size_t i = choice_.sample(uc);
    const Emitter& e = all_[i];
    EmitterSample s;
    s.emitter = static_cast<uint32_t>(i);
    if (e.kind == Emitter::Kind::Point) {
        s.p = e.position;
        s.pdfA = pdfA_[i];
        return s;
    }
    const Triangle& tri = triangles[e.triangle];
    const Vec2 b = sampleUniformTriangle(u);
    s.p = tri.p[0] * (1.0f - b.x - b.y) + tri.p[1] * b.x + tri.p[2] * b.y;
    s.bary = b;
    s.n = tri.geometricNormal();
    s.pdfA = pdfA_[i];
    return s;
}

Vec3 Emitters::sampleDirection(int e, Vec3 frontNormal, Vec2 u, float uc) const {
    const Emitter& em = all_[e];
    if (em.kind == Emitter::Kind::Point) return sampleUniformSphere(u);
    const Vec3 local = sampleCosineHemisphere(u);
    const Vec3 n = em.twoSided && uc < 0.5f ? -frontNormal : frontNormal;
    return Frame(n).toWorld(local);
}

float Emitters::directionPdf(int e, Vec3 frontNormal, Vec3 omega) const {
    const Emitter& em = all_[e];
    if (em.kind == Emitter::Kind::Point) return kUniformSpherePdf;
    const float c = dot(frontNormal, omega);
    if (em.twoSided) return 0.5f * std::abs(c) * kInvPi;
    return cosineHemispherePdf(c);
}

Spectrum Emitters::Le(int e, Vec3 frontNormal, Vec3 omega, Vec2 bary) const {
    const Emitter& em = all_[e];
    if (em.kind == Emitter::Kind::Point || em.twoSided || dot(frontNormal, omega) > 0)
        return em.textures ? em.textures->emissionAt(em.radiance, em.texCoords->at(bary)) : em.radiance;
    return Spectrum(0.0f);
}

}  // namespace tripath
