// BSDFs of the scene model (DESIGN.md §3): Lambertian, ideal mirror, smooth dielectric, rough GGX
// conductor and a rough plastic (GGX coat over a diffuse base).
//
// Everything works in the local shading frame (z = shading normal), directions point away from
// the surface. Non-delta BSDFs are two-sided: when wo is below the shading plane the frame is
// mirrored (z -> -z), which keeps f(wo,wi) = f(wi,wo) since both directions are flipped together.
#include "geometry/material.h"

#include <array>
#include <cmath>
#include <limits>

#include "geometry/sampling.h"
#include "geometry/stats.h"

namespace tripath {

namespace {

// ---------------------------------------------------------------------------------------------
// Small geometric helpers

// Mirror w about the shading normal (z): the ideal specular direction.
Vec3 reflectAboutNormal(Vec3 w) { return {-w.x, -w.y, w.z}; }

// Mirror w about an arbitrary unit microfacet normal h: 2(w·h)h − w.
Vec3 reflectAbout(Vec3 w, Vec3 h) { return 2.0f * dot(w, h) * h - w; }

// Squared sine of the polar angle from the components, not 1 − z²: this stays accurate near the
// pole, where the GGX lobe of a smooth surface lives.
float sin2Theta(Vec3 w) { return w.x * w.x + w.y * w.y; }

// Two-sided shading: express w in the frame mirrored so that wo lies in the upper hemisphere
// (an involution, so the same call maps a sampled direction back).
Vec3 toSideOf(Vec3 wo, Vec3 w) { return wo.z < 0 ? Vec3(w.x, w.y, -w.z) : w; }

bool finitePositive(float x) { return std::isfinite(x) && x > 0; }

// ---------------------------------------------------------------------------------------------
// Fresnel

// Exact unpolarised Fresnel reflectance of a smooth dielectric interface (Born & Wolf; pbrt 3e
// eq. 8.2). cosI ≥ 0 is the cosine on the incident side, eta = η_transmitted / η_incident.
// Returns 1 under total internal reflection; cosT receives the transmitted cosine (≥ 0).
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

// The (1 − cos θ)^5 factor of Schlick's approximation (Schlick 1994, eq. 24).
float schlickWeight(float cosTheta) {
    const float m = std::clamp(1.0f - cosTheta, 0.0f, 1.0f);
    const float m2 = m * m;
    return m2 * m2 * m;
}

Spectrum fresnelSchlick(Spectrum f0, float cosTheta) {
    return f0 + (Spectrum(1.0f) - f0) * schlickWeight(cosTheta);
}

// Normal-incidence reflectance of a dielectric of index ior in air: ((η − 1)/(η + 1))².
float dielectricF0(float ior) {
    const float r = (ior - 1.0f) / (ior + 1.0f);
    return r * r;
}

// ---------------------------------------------------------------------------------------------
// GGX / Trowbridge-Reitz microfacet distribution (Walter et al. 2007), isotropic, with the
// height-correlated Smith masking-shadowing function (Heitz 2014, "Understanding the
// Masking-Shadowing Function", eq. 99). All directions here are in the upper hemisphere.

// Perceptual roughness -> GGX alpha; the floor keeps D finite (peak 1/(π α²)) for roughness 0.
float ggxAlpha(float roughness) { return std::max(roughness * roughness, 1e-3f); }

// D(h) for the un-normalised half vector h = wo + wi, written with |h|⁴ / (α² h_z² + h_xy²)²
// so no 1 − cos² cancellation occurs (Walter et al. 2007, eq. 33).
float ggxD(Vec3 h, float alpha) {
    const float a2 = alpha * alpha;
    const float len2 = lengthSquared(h);
    const float denom = a2 * h.z * h.z + sin2Theta(h);
    if (!(denom > 0)) return 0.0f;
    return a2 * len2 * len2 / (kPi * denom * denom);
}

// |z| · sqrt(1 + α² tan²θ) = sqrt(z² + α² sin²θ): the building block of Smith's Λ for GGX,
// Λ(w) = (ggxRoot(w) / z − 1) / 2 (Heitz 2014, eq. 72), kept in a form finite at grazing.
float ggxRoot(Vec3 w, float alpha) { return std::sqrt(w.z * w.z + alpha * alpha * sin2Theta(w)); }

// G1(w) / cos θ = 2 / (z + ggxRoot): the visible-normal normalisation (Heitz 2014, eq. 43).
float ggxG1OverCos(Vec3 w, float alpha) { return 2.0f / (w.z + ggxRoot(w, alpha)); }

// Height-correlated G2 / (4 cos θo cos θi) = 1 / (2 (zi·rootO + zo·rootI)): the whole
// geometric part of the Cook-Torrance BRDF, symmetric in wo and wi.
float ggxVisibility(Vec3 wo, Vec3 wi, float alpha) {
    const float denom = 2.0f * (wi.z * ggxRoot(wo, alpha) + wo.z * ggxRoot(wi, alpha));
    return denom > 0 ? 1.0f / denom : 0.0f;
}

// G2(wo,wi) / G1(wo): the weight f·cos θi / pdf of a VNDF-sampled reflection with F = 1.
float ggxMaskingRatio(Vec3 wo, Vec3 wi, float alpha) {
    const float rootO = ggxRoot(wo, alpha), rootI = ggxRoot(wi, alpha);
    const float denom = wi.z * rootO + wo.z * rootI;
    return denom > 0 ? wi.z * (wo.z + rootO) / denom : 0.0f;
}

// Sample a microfacet normal from the distribution of normals visible from wo,
// D_wo(h) = G1(wo) max(0, wo·h) D(h) / cos θo (Heitz 2018, "Sampling the GGX Distribution of
// Visible Normals", listing 1): stretch to the α = 1 configuration, sample the projected
// hemisphere, unstretch.
Vec3 sampleGgxVisibleNormal(Vec3 wo, float alpha, Vec2 u) {
    const Vec3 vh = normalize(Vec3(alpha * wo.x, alpha * wo.y, wo.z));
    const float lensq = vh.x * vh.x + vh.y * vh.y;
    const Vec3 t1 = lensq > 0 ? Vec3(-vh.y, vh.x, 0) / std::sqrt(lensq) : Vec3(1, 0, 0);
    const Vec3 t2 = cross(vh, t1);
    const float r = std::sqrt(u.x);
    const float phi = 2.0f * kPi * u.y;
    const float p1 = r * std::cos(phi);
    const float s = 0.5f * (1.0f + vh.z);
    const float p2 = (1.0f - s) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + s * r * std::sin(phi);
    const Vec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * vh;
    return normalize(Vec3(alpha * nh.x, alpha * nh.y, std::max(0.0f, nh.z)));
}

// Solid-angle density of wi = reflect(wo, h) with h ~ D_wo: D_wo(h) / (4 wo·h)
// = G1(wo) D(h) / (4 cos θo) (Heitz 2018, eq. 17). Both directions in the upper hemisphere.
float ggxReflectionPdf(Vec3 wo, Vec3 wi, float alpha) {
    return ggxD(wo + wi, alpha) * ggxG1OverCos(wo, alpha) * 0.25f;
}

// Cosine between wo (or wi) and their half vector: for unit vectors wo·(wo + wi) = |wo + wi|²/2, so
// cos θh = |wo + wi| / 2. Unlike dot(wo, ĥ) this is symmetric in wo, wi bit for bit (reciprocity)
// and free of the cancellation in 1 + wo·wi when wo ≈ −wi.
float halfVectorCos(Vec3 wo, Vec3 wi) { return std::clamp(0.5f * length(wo + wi), 0.0f, 1.0f); }

// Draw wi by reflecting wo about a visible normal; empty when it lands below the horizon.
std::optional<Vec3> sampleGgxReflection(Vec3 wo, float alpha, Vec2 u) {
    const Vec3 wi = reflectAbout(wo, sampleGgxVisibleNormal(wo, alpha, u));
    if (!(wi.z > 0) || !isFinite(wi)) return std::nullopt;
    return normalize(wi);
}

// ---------------------------------------------------------------------------------------------
// Directional albedo of the plastic's GGX coat, for the coupled diffuse term of Kelemen &
// Szirmay-Kalos 2001 ("A Microfacet Based Coupled Specular-Matte BRDF Model with Importance
// Sampling"). With Schlick Fresnel the coat albedo is linear in F0:
//     E(μ, r; F0) = F0 · A(μ, r) + (1 − F0) · B(μ, r),
//     A = E_vndf[G2/G1],  B = E_vndf[(1 − wo·h)^5 · G2/G1],
// so two tables in (cos θ, roughness) serve every index of refraction. They are built once, on
// first use, by a deterministic quadrature over the VNDF sample square.

class CoatAlbedoTable {
public:
    static constexpr int kMu = 96, kRough = 32, kQuad = 24;
    // Safety margin added to the tabulated E: for these sizes the worst underestimate of the true
    // albedo over μ ∈ (0,1], roughness ∈ [0,1], F0 ∈ [0,1] measured 1.1e-3 (vs. a 400² quadrature).
    static constexpr double kMargin = 2.5e-3;

    CoatAlbedoTable() {
        for (int j = 0; j < kRough; ++j) {
            for (int i = 0; i < kMu; ++i) integrateNode(i, j);
            aAvg_[j] = cosineAverageOf(a_[j]);
            bAvg_[j] = cosineAverageOf(b_[j]);
        }
    }

    // Coat albedo E(μ) for cos θ = mu, bilinear in (sqrt μ, log α).
    float albedo(float mu, float roughness, float f0) const {
        const Lerp m = lerpAt(std::sqrt(std::max(mu, 0.0f)), kMu);
        const Lerp r = lerpAt(roughnessCoordinate(roughness), kRough);
        auto at = [&](int j, int i) { return f0 * a_[j][i] + (1.0f - f0) * b_[j][i]; };
        const float lo = (1 - m.t) * at(r.i, m.i) + m.t * at(r.i, m.i + 1);
        const float hi = (1 - m.t) * at(r.i + 1, m.i) + m.t * at(r.i + 1, m.i + 1);
        return std::clamp((1 - r.t) * lo + r.t * hi, 0.0f, 1.0f);
    }

    // Ē = 2 ∫ E(μ) μ dμ of the *interpolated* table, so that the coupled diffuse lobe below
    // integrates exactly to albedo · (1 − E(μo)) whatever the table's own error.
    float cosineWeightedAverage(float roughness, float f0) const {
        const Lerp r = lerpAt(roughnessCoordinate(roughness), kRough);
        auto at = [&](int j) { return f0 * aAvg_[j] + (1.0f - f0) * bAvg_[j]; };
        return std::clamp((1 - r.t) * at(r.i) + r.t * at(r.i + 1), 0.0f, 1.0f);
    }

private:
    struct Lerp {
        int i;
        float t;
    };
    static Lerp lerpAt(float x, int n) {
        const float s = std::clamp(x, 0.0f, 1.0f) * static_cast<float>(n - 1);
        const int i = std::min(static_cast<int>(s), n - 2);
        return {i, s - static_cast<float>(i)};
    }
    static float nodeValue(int i, int n) { return static_cast<float>(i) / static_cast<float>(n - 1); }

    // The roughness axis is uniform in log α: near-specular coats change character with the
    // ratio of α values (the grazing masking scale μ ~ α), not with their difference.
    static constexpr float kLogAlphaMin = -6.907755279f;  // log(1e-3), the ggxAlpha floor
    static float roughnessCoordinate(float roughness) {
        return 1.0f - std::log(ggxAlpha(std::clamp(roughness, 0.0f, 1.0f))) / kLogAlphaMin;
    }
    static float alphaAtNode(int j) { return std::exp(kLogAlphaMin * (1.0f - nodeValue(j, kRough))); }

    // Nodes are uniform in t = sqrt(μ): for a smooth coat E changes on a scale μ ~ α near
    // grazing incidence (masking), which uniform μ nodes would miss.
    void integrateNode(int i, int j) {
        const float t = nodeValue(i, kMu);
        const float mu = std::max(t * t, 1e-5f);  // μ = 0 is the limit; evaluate just above it
        const Vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
        const float alpha = alphaAtNode(j);
        double sumA = 0, sumB = 0;
        for (int y = 0; y < kQuad; ++y)
            for (int x = 0; x < kQuad; ++x) {
                // Substitute u1 = 1 − (1 − v)²: the VNDF warp has a sqrt(1 − u1) edge at the rim
                // of the disk that a midpoint rule in u1 integrates poorly.
                const double v = (x + 0.5) / kQuad;
                const Vec2 u{static_cast<float>(1.0 - (1.0 - v) * (1.0 - v)), (y + 0.5f) / kQuad};
                const auto wi = sampleGgxReflection(wo, alpha, u);
                if (!wi) continue;
                const double g = 2.0 * (1.0 - v) * ggxMaskingRatio(wo, *wi, alpha);
                sumA += g;
                sumB += g * schlickWeight(halfVectorCos(wo, *wi));
            }
        // Bias upward by the margin (never past 1): the diffuse lobe then gets slightly less
        // than 1 − E_true and the total albedo stays ≤ 1 despite quadrature and interpolation.
        a_[j][i] = static_cast<float>(std::min(1.0, sumA / (kQuad * kQuad) + kMargin));
        b_[j][i] = static_cast<float>(std::min(1.0, sumB / (kQuad * kQuad) + kMargin));
    }

    // 2 ∫ E μ dμ = ∫ E(t) 4t³ dt with E linear in t on each interval: a quartic there, which
    // 3-point Gauss-Legendre integrates exactly.
    static float cosineAverageOf(const std::array<float, kMu>& e) {
        constexpr double kNode[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
        constexpr double kWeight[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
        const double h = 1.0 / (kMu - 1);
        double sum = 0;
        for (int i = 0; i + 1 < kMu; ++i)
            for (int q = 0; q < 3; ++q) {
                const double s = 0.5 * (1.0 + kNode[q]);  // position within the interval
                const double t = (i + s) * h;
                const double ev = (1.0 - s) * e[i] + s * e[i + 1];
                sum += 0.5 * h * kWeight[q] * ev * 4.0 * t * t * t;
            }
        return static_cast<float>(sum);
    }

    std::array<std::array<float, kMu>, kRough> a_{}, b_{};
    std::array<float, kRough> aAvg_{}, bAvg_{};
};

const CoatAlbedoTable& coatAlbedoTable() {
    static const CoatAlbedoTable table;  // thread-safe one-time construction (C++11 magic static)
    return table;
}

// ---------------------------------------------------------------------------------------------
// Lambertian: f = albedo / π, cosine-weighted sampling (pdf = cos θi / π). Upper side only.

Spectrum evalLambertian(const Material& m) { return m.albedo * kInvPi; }
float pdfLambertian(Vec3 wi) { return wi.z * kInvPi; }

// ---------------------------------------------------------------------------------------------
// Mirror: f = albedo δ(wi − R(wo)) / |cos θi|, sampled with probability 1.

// A delta sample whose 1/|cos θi| overflowed (wo denormal-close to the plane) carries no usable
// weight; dropping it keeps every returned value finite.
std::optional<BsdfSample> finiteDelta(BsdfSample s) {
    if (!isFinite(s.f) || !finitePositive(s.pdf)) return std::nullopt;
    return s;
}

std::optional<BsdfSample> sampleMirror(const Material& m, Vec3 wo) {
    if (wo.z == 0) return std::nullopt;
    const Vec3 wi = reflectAboutNormal(wo);
    return finiteDelta({wi, m.albedo / std::abs(wi.z), 1.0f, true});
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

std::optional<BsdfSample> sampleDielectric(const Material& m, Vec3 wo, float uc, TransportMode mode) {
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

Spectrum evalConductor(const Material& m, Vec3 wo, Vec3 wi) {
    const float alpha = ggxAlpha(m.roughness);
    const float dv = ggxD(wo + wi, alpha) * ggxVisibility(wo, wi, alpha);
    return fresnelSchlick(m.albedo, halfVectorCos(wo, wi)) * dv;
}

// ---------------------------------------------------------------------------------------------
// Plastic: a GGX dielectric coat (Schlick Fresnel, F0 from ior) over a Lambertian base, coupled
// as in Kelemen & Szirmay-Kalos 2001:
//     f = F(wo·h) D G2 / (4 cos θo cos θi) + albedo/π · (1 − E(μo)) (1 − E(μi)) / (1 − Ē).
// E is the coat's directional albedo and Ē its cosine-weighted mean (CoatAlbedoTable). The diffuse
// term is symmetric in wo, wi (reciprocal) and integrates to albedo · (1 − E(μo)), so the
// directional albedo is E_true(μo) + albedo · (1 − E(μo)) ≤ 1: a white base reflects 1 minus the
// table's small conservative margin.

float plasticCoatF0(const Material& m) { return dielectricF0(m.ior); }

Spectrum evalPlasticDiffuse(const Material& m, Vec3 wo, Vec3 wi) {
    const CoatAlbedoTable& table = coatAlbedoTable();
    const float f0 = plasticCoatF0(m);
    const float norm = 1.0f - table.cosineWeightedAverage(m.roughness, f0);
    if (!(norm > 1e-6f)) return Spectrum(0.0f);
    const float to = 1.0f - table.albedo(wo.z, m.roughness, f0);
    const float ti = 1.0f - table.albedo(wi.z, m.roughness, f0);
    return m.albedo * (kInvPi * to * ti / norm);
}

Spectrum evalPlastic(const Material& m, Vec3 wo, Vec3 wi) {
    const float alpha = ggxAlpha(m.roughness);
    const float f0 = plasticCoatF0(m);
    const float fresnel = f0 + (1.0f - f0) * schlickWeight(halfVectorCos(wo, wi));
    const float specular = fresnel * ggxD(wo + wi, alpha) * ggxVisibility(wo, wi, alpha);
    return Spectrum(specular) + evalPlasticDiffuse(m, wo, wi);
}

// Probability of sampling the coat lobe: proportional to the lobes' albedos at wo, kept within
// [0.1, 0.9] so neither lobe is starved (depends on wo only, so the mixture pdf is exact).
float plasticSpecularProbability(const Material& m, Vec3 wo) {
    const float e = coatAlbedoTable().albedo(wo.z, m.roughness, plasticCoatF0(m));
    const float diffuse = std::max(average(m.albedo), 0.0f) * (1.0f - e);
    const float total = e + diffuse;
    return total > 0 ? std::clamp(e / total, 0.1f, 0.9f) : 0.5f;
}

float pdfPlastic(const Material& m, Vec3 wo, Vec3 wi) {
    const float ps = plasticSpecularProbability(m, wo);
    return ps * ggxReflectionPdf(wo, wi, ggxAlpha(m.roughness)) + (1.0f - ps) * wi.z * kInvPi;
}

std::optional<Vec3> samplePlastic(const Material& m, Vec3 wo, Vec2 u, float uc) {
    if (uc < plasticSpecularProbability(m, wo)) return sampleGgxReflection(wo, ggxAlpha(m.roughness), u);
    return sampleCosineHemisphere(u);
}

// ---------------------------------------------------------------------------------------------
// Dispatch for the two-sided non-delta materials, in the frame mirrored so that wo.z > 0.

Spectrum evalUpper(const Material& m, Vec3 wo, Vec3 wi) {
    switch (m.type) {
    case MaterialType::Lambertian: return evalLambertian(m);
    case MaterialType::Conductor: return evalConductor(m, wo, wi);
    case MaterialType::Plastic: return evalPlastic(m, wo, wi);
    default: return Spectrum(0.0f);
    }
}

float pdfUpper(const Material& m, Vec3 wo, Vec3 wi) {
    switch (m.type) {
    case MaterialType::Lambertian: return pdfLambertian(wi);
    case MaterialType::Conductor: return ggxReflectionPdf(wo, wi, ggxAlpha(m.roughness));
    case MaterialType::Plastic: return pdfPlastic(m, wo, wi);
    default: return 0.0f;
    }
}

std::optional<Vec3> sampleUpper(const Material& m, Vec3 wo, Vec2 u, float uc) {
    switch (m.type) {
    case MaterialType::Lambertian: return sampleCosineHemisphere(u);
    case MaterialType::Conductor: return sampleGgxReflection(wo, ggxAlpha(m.roughness), u);
    case MaterialType::Plastic: return samplePlastic(m, wo, u, uc);
    default: return std::nullopt;
    }
}

Spectrum finiteOrZero(Spectrum s) { return isFinite(s) ? max(s, Spectrum(0.0f)) : Spectrum(0.0f); }
float finiteOrZero(float x) { return std::isfinite(x) ? std::max(x, 0.0f) : 0.0f; }

std::optional<BsdfSample> sampleNonDelta(const Material& m, Vec3 wo, Vec2 u, float uc, TransportMode mode) {
    if (wo.z == 0) return std::nullopt;
    const std::optional<Vec3> wiUp = sampleUpper(m, toSideOf(wo, wo), u, uc);
    if (!wiUp) return std::nullopt;
    const Vec3 wi = toSideOf(wo, *wiUp);
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
    case MaterialType::Conductor: return "conductor";
    case MaterialType::Plastic: return "plastic";
    }
    return "unknown";
}

bool isDelta(const Material& m) {
    return m.type == MaterialType::Mirror || m.type == MaterialType::Dielectric;
}

// Non-delta lobes are reflection only: both directions strictly on the same side of the shading
// plane (so grazing z = 0 gives 0); TransportMode only matters for refraction.
Spectrum evalBsdf(const Material& m, Vec3 wo, Vec3 wi, TransportMode /*mode*/) {
    count(Event::BsdfEvaluations);
    if (isDelta(m) || !(wo.z * wi.z > 0)) return Spectrum(0.0f);
    return finiteOrZero(evalUpper(m, toSideOf(wo, wo), toSideOf(wo, wi)));
}

float pdfBsdf(const Material& m, Vec3 wo, Vec3 wi) {
    count(Event::BsdfPdfs);
    if (isDelta(m) || !(wo.z * wi.z > 0)) return 0.0f;
    return finiteOrZero(pdfUpper(m, toSideOf(wo, wo), toSideOf(wo, wi)));
}

std::optional<BsdfSample> sampleBsdf(const Material& m, Vec3 wo, Vec2 u, float uc, TransportMode mode) {
    count(Event::BsdfSamples);
    const PhaseScope scope(Phase::Scattering);
    switch (m.type) {
    case MaterialType::Mirror: return sampleMirror(m, wo);
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
    if (!std::isfinite(m.ior)) return "ior is not finite";
    const bool usesIor = m.type == MaterialType::Dielectric || m.type == MaterialType::Plastic;
    if (usesIor && m.ior < 1.0f) return "ior must be at least 1";
    return {};
}

}  // namespace tripath
