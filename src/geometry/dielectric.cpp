// The dielectric interface: Fresnel, and the rough dielectric lobe (dielectric.h says what each
// function computes).
//
// The lobe is evaluated in the frame mirrored so that wo lies above (z > 0), with the index
// across the interface relative to wo's side: ior entering from outside, 1/ior leaving. There the
// refraction's microfacet normal is h ∝ −(wo + η wi) (Snell's law in vector form, Walter et al.
// eq. 16), turned to wo's side; a pair is a refraction only through a facet that faces wo and
// turns its back to wi, and the Jacobian of the half-vector map is
//     |∂ω_h / ∂ω_i| = η² |wi·h| / (wo·h + η wi·h)²,
// the same expressions with both indices divided by η_o.
#include "geometry/dielectric.h"

#include <algorithm>
#include <cmath>

#include "geometry/microfacet.h"

namespace tripath {

namespace {

// The least index the lobe refracts with. At index 1 an interface neither reflects nor bends
// light whatever its facets (Walter's refraction normal −(wo + wi) vanishes: the lobe is a delta
// straight through), which a non-delta lobe cannot be; a glTF mix reaches it where a texture
// lowers the metallic of a material of ior 1. At 1.001 a facet met at θ' turns light by
// (1 − 1/η) tan θ' off straight on (a fifth of a degree at 70°) and reflects 2.5e-7, while the
// half vectors keep a float's accuracy to 1e-4 (|wo + η wi| ≥ 0.001 cos θ'). What the facets
// still do is mask: at roughness 1 the lobe passes 85 % at 45° and 67 % at 70°.
constexpr float kLeastIndex = 1.001f;

// η across the interface over η on wo's side: the exterior (+z) has index 1, the interior ior.
float relativeEta(const BsdfParams& m, Vec3 wo) {
    const float ior = std::max(m.ior, kLeastIndex);
    return wo.z > 0 ? ior : 1.0f / ior;
}

// w in the frame mirrored so that wo lies above (an involution: maps a sampled direction back).
Vec3 mirroredUp(Vec3 wo, Vec3 w) { return wo.z < 0 ? Vec3(w.x, w.y, -w.z) : w; }

// The microfacet normal that refracts wo (above) into wi (below) for the relative index eta, with
// the cosines wo·h > 0 and wi·h < 0; empty where no facet does.
struct Refraction {
    Vec3 h;
    float cosO, cosI;
};
std::optional<Refraction> refractingNormal(Vec3 wo, Vec3 wi, float eta) {
    Vec3 h = -(wo + wi * eta);
    if (h.z < 0) h = -h;
    const float len2 = lengthSquared(h);
    if (!(len2 > 0)) return std::nullopt;
    h = h / std::sqrt(len2);
    const float cosO = dot(wo, h), cosI = dot(wi, h);
    if (!(cosO > 0 && cosI < 0)) return std::nullopt;
    return Refraction{h, cosO, cosI};
}

float square(float x) { return x * x; }

// 1 − F of the refraction a facet makes between the cosines cosO (incident side, index ratio eta
// across) and cosT (transmitted side), from the two parallel and perpendicular transmittances
//     1 − r_∥² = 4 η cosO cosT / (η cosO + cosT)²,   1 − r_⊥² = 4 η cosO cosT / (cosO + η cosT)².
// The same value as 1 − fresnelDielectric, but free of its cancellation near total internal
// reflection (F → 1), and the same expression with the sides swapped (cosT, 1/η): the refraction
// lobe stays reciprocal where its value is smallest.
float fresnelTransmittance(float cosO, float cosT, float eta) {
    const float product = 2.0f * eta * cosO * cosT;
    return product * (1.0f / square(eta * cosO + cosT) + 1.0f / square(cosO + eta * cosT));
}

}  // namespace

float fresnelDielectric(float cosI, float eta, float& cosT) {
    cosT = 0;
    if (cosI <= 0) return 1.0f;
    const float sin2T = (1.0f - cosI * cosI) / (eta * eta);
    if (sin2T >= 1.0f) return 1.0f;
    cosT = std::sqrt(1.0f - sin2T);
    const float rPar = (eta * cosI - cosT) / (eta * cosI + cosT);
    const float rPerp = (cosI - eta * cosT) / (cosI + eta * cosT);
    return 0.5f * (rPar * rPar + rPerp * rPerp);
}

Spectrum evalRoughDielectric(const BsdfParams& m, Vec3 wo, Vec3 wi, TransportMode mode) {
    if (wo.z == 0 || wi.z == 0) return Spectrum(0.0f);
    const float eta = relativeEta(m, wo), alpha = ggxAlpha(m.roughness);
    const Vec3 o = mirroredUp(wo, wo), i = mirroredUp(wo, wi);
    float cosT = 0;
    if (i.z > 0)
        return Spectrum(fresnelDielectric(halfVectorCos(o, i), eta, cosT) * ggxD(o + i, alpha) * ggxVisibility(o, i, alpha));
    const std::optional<Refraction> r = refractingNormal(o, i, eta);
    if (!r) return Spectrum(0.0f);
    const float transmitted = fresnelTransmittance(r->cosO, -r->cosI, eta);
    const float g2 = ggxG2(o, Vec3(i.x, i.y, -i.z), alpha);
    const float radiance = r->cosO * -r->cosI * transmitted * ggxD(r->h, alpha) * g2 /
                           (o.z * -i.z * square(r->cosO + eta * r->cosI));
    return m.albedo * (mode == TransportMode::Importance ? radiance * eta * eta : radiance);
}

float pdfRoughDielectric(const BsdfParams& m, Vec3 wo, Vec3 wi) {
    if (wo.z == 0 || wi.z == 0) return 0.0f;
    const float eta = relativeEta(m, wo), alpha = ggxAlpha(m.roughness);
    const Vec3 o = mirroredUp(wo, wo), i = mirroredUp(wo, wi);
    float cosT = 0;
    if (i.z > 0) return fresnelDielectric(halfVectorCos(o, i), eta, cosT) * ggxReflectionPdf(o, i, alpha);
    const std::optional<Refraction> r = refractingNormal(o, i, eta);
    if (!r) return 0.0f;
    const float transmitted = fresnelTransmittance(r->cosO, -r->cosI, eta);
    const float jacobian = eta * eta * -r->cosI / square(r->cosO + eta * r->cosI);
    return transmitted * ggxVisibleNormalPdf(o, r->h, alpha) * jacobian;
}

std::optional<Vec3> sampleRoughDielectric(const BsdfParams& m, Vec3 wo, Vec2 u, float uc) {
    if (wo.z == 0) return std::nullopt;
    const float eta = relativeEta(m, wo);
    const Vec3 o = mirroredUp(wo, wo);
    const Vec3 h = sampleGgxVisibleNormal(o, ggxAlpha(m.roughness), u);
    const float cosO = dot(o, h);
    float cosT = 0;
    const float reflectance = fresnelDielectric(cosO, eta, cosT);
    const bool reflects = uc < reflectance;
    const Vec3 i = reflects ? h * (2.0f * cosO) - o : h * (cosO / eta - cosT) - o / eta;
    if (reflects ? !(i.z > 0) : !(i.z < 0)) return std::nullopt;
    if (!isFinite(i)) return std::nullopt;
    return mirroredUp(wo, normalize(i));
}

}  // namespace tripath
