// BSDFs of the scene model (docs/design.md §3): Lambertian, ideal mirror, smooth dielectric, rough
// GGX conductor and its smooth limit, a rough plastic (GGX coat over a diffuse base) and glTF's
// metallic-roughness mix of the conductor, the plastic and rough glass, and the dispatch over the
// material types behind evalBsdf, pdfBsdf and sampleBsdf. What the rough lobes share lives
// beside it: the GGX distribution in microfacet.cpp, the plastic coat's albedo table in
// coat_albedo.cpp, Fresnel and the rough dielectric in dielectric.cpp; this file holds the other
// lobes' own formulas and the switch over the types.
//
// Everything works in the local shading frame (z = shading normal), directions point away from
// the surface. The reflection lobes are two-sided: when wo is below the shading plane the frame is
// mirrored (z -> -z), which keeps f(wo,wi) = f(wi,wo) since both directions are flipped together.
// The rough dielectric tells its two sides apart (the index differs) and is the only non-delta
// lobe that joins them.
#include "geometry/material.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/coat_albedo.h"
#include "geometry/dielectric.h"
#include "geometry/microfacet.h"
#include "core/sampling.h"
#include "core/stats.h"

namespace tripath {

namespace {

constexpr Counter kBsdfSamples{Event::BsdfSamples};
constexpr Counter kBsdfEvaluations{Event::BsdfEvaluations};
constexpr Counter kBsdfPdfs{Event::BsdfPdfs};

// ---------------------------------------------------------------------------------------------
// Small geometric helpers

// Mirror w about the shading normal (z): the ideal specular direction.
Vec3 reflectAboutNormal(Vec3 w) { return {-w.x, -w.y, w.z}; }

// Two-sided shading: express w in the frame mirrored so that wo lies in the upper hemisphere
// (an involution, so the same call maps a sampled direction back).
Vec3 toSideOf(Vec3 wo, Vec3 w) { return wo.z < 0 ? Vec3(w.x, w.y, -w.z) : w; }

bool finitePositive(float x) { return std::isfinite(x) && x > 0; }

// ---------------------------------------------------------------------------------------------
// Fresnel (the dielectric's exact form is in dielectric.cpp)

Spectrum fresnelSchlick(Spectrum f0, float cosTheta) {
    return f0 + (Spectrum(1.0f) - f0) * schlickWeight(cosTheta);
}

// Normal-incidence reflectance of a dielectric of index ior in air: ((η − 1)/(η + 1))².
float dielectricF0(float ior) {
    const float r = (ior - 1.0f) / (ior + 1.0f);
    return r * r;
}

// ---------------------------------------------------------------------------------------------
// Lambertian: f = albedo / π, cosine-weighted sampling (pdf = cos θi / π). Upper side only.

Spectrum evalLambertian(const BsdfParams& m) { return m.albedo * kInvPi; }
float pdfLambertian(Vec3 wi) { return wi.z * kInvPi; }

// ---------------------------------------------------------------------------------------------
// Ideal specular reflection: f = R(θ) δ(wi − reflect(wo)) / |cos θi|, sampled with probability
// 1. The mirror's reflectance is its albedo at every angle; the smooth conductor's is Schlick's
// Fresnel of F0 = albedo at cos θ = |cos θo| (= |cos θi|), the limit of the rough conductor's
// F(wo·h) as its microfacet normals h gather at the shading normal.

// A delta sample whose 1/|cos θi| overflowed (wo denormal-close to the plane) carries no usable
// weight; dropping it keeps every returned value finite.
std::optional<BsdfSample> finiteDelta(BsdfSample s) {
    if (!isFinite(s.f) || !finitePositive(s.pdf)) return std::nullopt;
    return s;
}

std::optional<BsdfSample> sampleSpecularReflection(const BsdfParams& m, Vec3 wo) {
    if (wo.z == 0) return std::nullopt;
    const Vec3 wi = reflectAboutNormal(wo);
    const Spectrum reflectance =
        m.type == MaterialType::SmoothConductor ? fresnelSchlick(m.albedo, std::abs(wo.z)) : m.albedo;
    return finiteDelta({wi, reflectance / std::abs(wi.z), 1.0f, true});
}

// ---------------------------------------------------------------------------------------------
// Smooth dielectric. The lobe is chosen with probability F (reflect) or 1 − F (refract), so the
// sample weight f |cos θi| / pdf is 1 for reflection and, for refraction, 1/η² when radiance is
// carried (radiance changes by (η_wo/η_wi)² = 1/η² across the interface, Veach 1997 §5.2) and 1
// for importance, whose adjoint BTDF has no such factor. albedo tints transmission only: as in
// glTF's KHR_materials_transmission, colour comes from the bulk, while the surface reflection of
// a dielectric stays white.

// Refraction of wo through the interface whose normal is ±z; cosT from fresnelDielectric.
Vec3 refractThroughNormal(Vec3 wo, float eta, float cosT) {
    const float sign = wo.z > 0 ? 1.0f : -1.0f;
    Vec3 wi = -wo / eta;
    wi.z = -sign * cosT;
    return normalize(wi);
}

std::optional<BsdfSample> sampleDielectric(const BsdfParams& m, Vec3 wo, float uc, TransportMode mode) {
    if (wo.z == 0) return std::nullopt;
    // η = η(wi side) / η(wo side): entering the glass when wo is outside (z > 0).
    const float eta = wo.z > 0 ? m.ior : 1.0f / m.ior;
    float cosT = 0;
    const float fr = fresnelDielectric(std::abs(wo.z), eta, cosT);
    if (uc < fr || !(cosT > 0)) {
        const Vec3 wi = reflectAboutNormal(wo);
        const float p = cosT > 0 ? fr : 1.0f;
        return finiteDelta({wi, Spectrum(p / std::abs(wi.z)), p, true});
    }
    const Vec3 wi = refractThroughNormal(wo, eta, cosT);
    const float t = 1.0f - fr;
    const float scale = mode == TransportMode::Radiance ? 1.0f / (eta * eta) : 1.0f;
    return finiteDelta({wi, m.albedo * (t * scale / std::abs(wi.z)), t, true});
}

// ---------------------------------------------------------------------------------------------
// Rough conductor: Cook-Torrance f = F(wo·h) D(h) G2 / (4 cos θo cos θi) with Schlick Fresnel
// (F0 = albedo). Arguments are already on the upper side.

Spectrum evalConductor(const BsdfParams& m, Vec3 wo, Vec3 wi) {
    const float alpha = ggxAlpha(m.roughness);
    const float dv = ggxD(wo + wi, alpha) * ggxVisibility(wo, wi, alpha);
    return fresnelSchlick(m.albedo, halfVectorCos(wo, wi)) * dv;
}

// ---------------------------------------------------------------------------------------------
// Plastic: a GGX dielectric coat (Schlick Fresnel, F0 from ior) over a Lambertian base, coupled
// as in Kelemen & Szirmay-Kalos 2001:
//     f = F(wo·h) D G2 / (4 cos θo cos θi) + albedo/π · (1 − E(μo)) (1 − E(μi)) / (1 − Ē).
// E is the coat's directional albedo and Ē its cosine-weighted mean (coat_albedo.h). The diffuse
// term is symmetric in wo, wi (reciprocal) and integrates to albedo · (1 − E(μo)), so the
// directional albedo is E_true(μo) + albedo · (1 − E(μo)) ≤ 1: a white base reflects 1 minus the
// table's small conservative margin.

float plasticCoatF0(const BsdfParams& m) { return dielectricF0(m.ior); }

Spectrum evalPlasticDiffuse(const BsdfParams& m, Vec3 wo, Vec3 wi) {
    const float f0 = plasticCoatF0(m);
    const float norm = 1.0f - coatAlbedoAverage(m.roughness, f0);
    if (!(norm > 1e-6f)) return Spectrum(0.0f);
    const float to = 1.0f - coatAlbedo(wo.z, m.roughness, f0);
    const float ti = 1.0f - coatAlbedo(wi.z, m.roughness, f0);
    return m.albedo * (kInvPi * to * ti / norm);
}

Spectrum evalPlastic(const BsdfParams& m, Vec3 wo, Vec3 wi) {
    const float alpha = ggxAlpha(m.roughness);
    const float f0 = plasticCoatF0(m);
    const float fresnel = f0 + (1.0f - f0) * schlickWeight(halfVectorCos(wo, wi));
    const float specular = fresnel * ggxD(wo + wi, alpha) * ggxVisibility(wo, wi, alpha);
    return Spectrum(specular) + evalPlasticDiffuse(m, wo, wi);
}

// Probability of sampling the coat lobe: proportional to the lobes' albedos at wo, kept within
// [0.1, 0.9] so neither lobe is starved (depends on wo only, so the mixture pdf is exact).
float plasticSpecularProbability(const BsdfParams& m, Vec3 wo) {
    const float e = coatAlbedo(wo.z, m.roughness, plasticCoatF0(m));
    const float diffuse = std::max(average(m.albedo), 0.0f) * (1.0f - e);
    const float total = e + diffuse;
    return total > 0 ? std::clamp(e / total, 0.1f, 0.9f) : 0.5f;
}

// The sampler of a GGX reflection lobe of roughness m.roughness, chosen with probability
// `specular`, and a cosine lobe: its pdf, and a draw from it.
float pdfGgxOrCosine(const BsdfParams& m, float specular, Vec3 wo, Vec3 wi) {
    return specular * ggxReflectionPdf(wo, wi, ggxAlpha(m.roughness)) + (1.0f - specular) * wi.z * kInvPi;
}

std::optional<Vec3> sampleGgxOrCosine(const BsdfParams& m, float specular, Vec3 wo, Vec2 u, float uc) {
    if (uc < specular) return sampleGgxReflection(wo, ggxAlpha(m.roughness), u);
    return sampleCosineHemisphere(u);
}

float pdfPlastic(const BsdfParams& m, Vec3 wo, Vec3 wi) { return pdfGgxOrCosine(m, plasticSpecularProbability(m, wo), wo, wi); }

std::optional<Vec3> samplePlastic(const BsdfParams& m, Vec3 wo, Vec2 u, float uc) {
    return sampleGgxOrCosine(m, plasticSpecularProbability(m, wo), wo, u, uc);
}

// ---------------------------------------------------------------------------------------------
// glTF metallic-roughness (glTF 2.0 spec, Appendix B's mix of a metal and a dielectric): f = m ·
// conductor + (1 − m) · plastic, the conductor's F0 and the plastic's diffuse albedo both the base
// colour, one GGX roughness. The dielectric is the coupled plastic above rather than Appendix B's
// fresnel_mix (1 − F(v·h)) ρ/π + F(v·h) D V, whose albedo exceeds 1 at grazing angles. With
// KHR_materials_transmission's factor T the dielectric half is (1 − T) · plastic + T · rough
// dielectric (the extension's mix of the diffuse base and the BTDF under one Fresnel layer:
// linear in the base, so a mix of the two layered lobes). Each lobe scatters at most 1, so the
// mix does. Sampling picks the rough dielectric's sampler with its weight (1 − m) T
// (dielectricWeight), else the conductor's with probability m and the plastic's otherwise, in
// proportion; so the pdf is the mixture of theirs. The conductor and the plastic draw the same
// GGX reflection, so they read as one GGX lobe of probability (m + (1 − m)(1 − T) p_coat) / (1 −
// (1 − m) T) and the cosine lobe with the rest.

// The rough dielectric's weight in a material: all of a RoughDielectric, (1 − metallic) ×
// transmission of the metallic-roughness mix, none elsewhere.
float dielectricWeight(const BsdfParams& m) {
    if (m.type == MaterialType::RoughDielectric) return 1.0f;
    if (m.type == MaterialType::MetallicRoughness) return (1.0f - m.metallic) * m.transmission;
    return 0.0f;
}

Spectrum evalMetallicRoughness(const BsdfParams& m, Vec3 wo, Vec3 wi) {
    return evalConductor(m, wo, wi) * m.metallic +
           evalPlastic(m, wo, wi) * ((1.0f - m.metallic) * (1.0f - m.transmission));
}

float metallicSpecularProbability(const BsdfParams& m, Vec3 wo) {
    const float opaque = 1.0f - dielectricWeight(m);
    if (!(opaque > 0)) return 1.0f;  // never asked: the dielectric takes every sample
    return (m.metallic + (1.0f - m.metallic) * (1.0f - m.transmission) * plasticSpecularProbability(m, wo)) / opaque;
}

float pdfMetallicRoughness(const BsdfParams& m, Vec3 wo, Vec3 wi) {
    return pdfGgxOrCosine(m, metallicSpecularProbability(m, wo), wo, wi);
}

std::optional<Vec3> sampleMetallicRoughness(const BsdfParams& m, Vec3 wo, Vec2 u, float uc) {
    return sampleGgxOrCosine(m, metallicSpecularProbability(m, wo), wo, u, uc);
}

// ---------------------------------------------------------------------------------------------
// Dispatch for the two-sided non-delta materials, in the frame mirrored so that wo.z > 0.

Spectrum evalUpper(const BsdfParams& m, Vec3 wo, Vec3 wi) {
    switch (m.type) {
    case MaterialType::Lambertian: return evalLambertian(m);
    case MaterialType::Conductor: return evalConductor(m, wo, wi);
    case MaterialType::Plastic: return evalPlastic(m, wo, wi);
    case MaterialType::MetallicRoughness: return evalMetallicRoughness(m, wo, wi);
    default: return Spectrum(0.0f);
    }
}

float pdfUpper(const BsdfParams& m, Vec3 wo, Vec3 wi) {
    switch (m.type) {
    case MaterialType::Lambertian: return pdfLambertian(wi);
    case MaterialType::Conductor: return ggxReflectionPdf(wo, wi, ggxAlpha(m.roughness));
    case MaterialType::Plastic: return pdfPlastic(m, wo, wi);
    case MaterialType::MetallicRoughness: return pdfMetallicRoughness(m, wo, wi);
    default: return 0.0f;
    }
}

std::optional<Vec3> sampleUpper(const BsdfParams& m, Vec3 wo, Vec2 u, float uc) {
    switch (m.type) {
    case MaterialType::Lambertian: return sampleCosineHemisphere(u);
    case MaterialType::Conductor: return sampleGgxReflection(wo, ggxAlpha(m.roughness), u);
    case MaterialType::Plastic: return samplePlastic(m, wo, u, uc);
    case MaterialType::MetallicRoughness: return sampleMetallicRoughness(m, wo, u, uc);
    default: return std::nullopt;
    }
}

Spectrum finiteOrZero(Spectrum s) { return isFinite(s) ? max(s, Spectrum(0.0f)) : Spectrum(0.0f); }
float finiteOrZero(float x) { return std::isfinite(x) ? std::max(x, 0.0f) : 0.0f; }

// The reflection lobes' sampler in the frame mirrored to wo's side, with uc left for their choice.
std::optional<Vec3> sampleReflection(const BsdfParams& m, Vec3 wo, Vec2 u, float uc) {
    const std::optional<Vec3> wiUp = sampleUpper(m, toSideOf(wo, wo), u, uc);
    if (!wiUp) return std::nullopt;
    return toSideOf(wo, *wiUp);
}

// uc picks the rough dielectric with its weight w, and is rescaled to [0, 1) for the choice
// within the lobe picked.
std::optional<BsdfSample> sampleNonDelta(const BsdfParams& m, Vec3 wo, Vec2 u, float uc, TransportMode mode) {
    if (wo.z == 0) return std::nullopt;
    const float w = dielectricWeight(m);
    const std::optional<Vec3> sampled = uc < w ? sampleRoughDielectric(m, wo, u, uc / w)
                                               : sampleReflection(m, wo, u, w > 0 ? (uc - w) / (1.0f - w) : uc);
    if (!sampled) return std::nullopt;
    const Vec3 wi = *sampled;
    // Report exactly what evalBsdf / pdfBsdf say, so the estimator and MIS agree bit for bit.
    BsdfSample s{wi, evalBsdf(m, wo, wi, mode), pdfBsdf(m, wo, wi), false};
    if (!finitePositive(s.pdf)) return std::nullopt;
    return s;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Public interface

const char* materialTypeName(MaterialType t) {
    switch (t) {
    case MaterialType::Lambertian: return "lambertian";
    case MaterialType::Mirror: return "mirror";
    case MaterialType::Dielectric: return "dielectric";
    case MaterialType::RoughDielectric: return "rough-dielectric";
    case MaterialType::Conductor: return "conductor";
    case MaterialType::SmoothConductor: return "smooth-conductor";
    case MaterialType::Plastic: return "plastic";
    case MaterialType::MetallicRoughness: return "metallic-roughness";
    }
    return "unknown";
}

bool isDelta(const BsdfParams& m) {
    return m.type == MaterialType::Mirror || m.type == MaterialType::SmoothConductor ||
           m.type == MaterialType::Dielectric;
}

bool transmits(const BsdfParams& m) { return dielectricWeight(m) > 0; }

// The reflection lobes join directions strictly on the same side of the shading plane (so grazing
// z = 0 gives 0); the rough dielectric, weighted by dielectricWeight, adds its own, refraction
// included. TransportMode matters for refraction alone.
Spectrum evalBsdf(const BsdfParams& m, Vec3 wo, Vec3 wi, TransportMode mode) {
    kBsdfEvaluations.add();
    if (isDelta(m)) return Spectrum(0.0f);
    Spectrum f(0.0f);
    if (wo.z * wi.z > 0) f = evalUpper(m, toSideOf(wo, wo), toSideOf(wo, wi));
    if (const float w = dielectricWeight(m); w > 0) f += evalRoughDielectric(m, wo, wi, mode) * w;
    return finiteOrZero(f);
}

float pdfBsdf(const BsdfParams& m, Vec3 wo, Vec3 wi) {
    kBsdfPdfs.add();
    if (isDelta(m)) return 0.0f;
    float p = 0.0f;
    if (wo.z * wi.z > 0) p = pdfUpper(m, toSideOf(wo, wo), toSideOf(wo, wi));
    if (const float w = dielectricWeight(m); w > 0) p = p * (1.0f - w) + pdfRoughDielectric(m, wo, wi) * w;
    return finiteOrZero(p);
}

std::optional<BsdfSample> sampleBsdf(const BsdfParams& m, Vec3 wo, Vec2 u, float uc, TransportMode mode) {
    kBsdfSamples.add();
    switch (m.type) {
    case MaterialType::Mirror:
    case MaterialType::SmoothConductor: return sampleSpecularReflection(m, wo);
    case MaterialType::Dielectric: return sampleDielectric(m, wo, uc, mode);
    default: return sampleNonDelta(m, wo, u, uc, mode);
    }
}

namespace {

// First problem with a spectrum that must be finite and within [0, upper], or empty.
std::string checkSpectrum(const char* what, Spectrum s, float upper) {
    for (int c = 0; c < 3; ++c)
        if (!std::isfinite(s[c])) return std::string(what) + " has a non-finite component";
    for (int c = 0; c < 3; ++c)
        if (s[c] < 0) return std::string(what) + " has a negative component";
    for (int c = 0; c < 3; ++c)
        if (s[c] > upper) return std::string(what) + " exceeds 1 in some channel (would create energy)";
    return {};
}

}  // namespace

std::string validateMaterial(const Material& m) {
    // Albedo is a reflectance (diffuse albedo, mirror reflectance, glass tint, metal F0) for
    // every type, so [0,1] per channel is what energy conservation demands.
    if (auto e = checkSpectrum("albedo", m.albedo, 1.0f); !e.empty()) return e;
    if (auto e = checkSpectrum("emission", m.emission, std::numeric_limits<float>::infinity()); !e.empty())
        return e;
    if (!(m.roughness >= 0.0f && m.roughness <= 1.0f)) return "roughness must be a number in [0, 1]";
    if (!(m.metallic >= 0.0f && m.metallic <= 1.0f)) return "metallic must be a number in [0, 1]";
    if (!(m.transmission >= 0.0f && m.transmission <= 1.0f)) return "transmission must be a number in [0, 1]";
    if (!std::isfinite(m.ior)) return "ior is not finite";
    for (int c = 0; c < 3; ++c)
        if (!(m.absorption[c] >= 0)) return "absorption must be at least 0";
    const bool usesIor = m.type == MaterialType::Dielectric || m.type == MaterialType::RoughDielectric ||
                         m.type == MaterialType::Plastic || m.type == MaterialType::MetallicRoughness;
    if (usesIor && m.ior < 1.0f) return "ior must be at least 1";
    return {};
}

}  // namespace tripath
