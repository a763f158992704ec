// GGX microfacet distribution, masking-shadowing and visible-normal sampling (microfacet.h says
// what each function computes; Walter et al. 2007, Heitz 2014 and 2018). Kept apart from the
// materials so that the lobes that use it and the coat albedo table that integrates it share
// one definition.
#include "geometry/microfacet.h"

#include <algorithm>
#include <cmath>

namespace tripath {

namespace {

// Squared sine of the polar angle from the components, not 1 − z²: this stays accurate near the
// pole, where the GGX lobe of a smooth surface lives.
float sin2Theta(Vec3 w) { return w.x * w.x + w.y * w.y; }

// Mirror w about an arbitrary unit microfacet normal h: 2(w·h)h − w.
Vec3 reflectAbout(Vec3 w, Vec3 h) { return 2.0f * dot(w, h) * h - w; }

// |z| · sqrt(1 + α² tan²θ) = sqrt(z² + α² sin²θ): the building block of Smith's Λ for GGX,
// Λ(w) = (ggxRoot(w) / z − 1) / 2 (Heitz 2014, eq. 72), kept in a form finite at grazing.
float ggxRoot(Vec3 w, float alpha) { return std::sqrt(w.z * w.z + alpha * alpha * sin2Theta(w)); }

// G1(w) / cos θ = 2 / (z + ggxRoot): the visible-normal normalisation (Heitz 2014, eq. 43).
float ggxG1OverCos(Vec3 w, float alpha) { return 2.0f / (w.z + ggxRoot(w, alpha)); }

}  // namespace

float schlickWeight(float cosTheta) {
    const float m = std::clamp(1.0f - cosTheta, 0.0f, 1.0f);
    const float m2 = m * m;
    return m2 * m2 * m;
}

float ggxAlpha(float roughness) { return std::max(roughness * roughness, 1e-3f); }

float ggxD(Vec3 h, float alpha) {
    const float a2 = alpha * alpha;
    const float len2 = lengthSquared(h);
    const float denom = a2 * h.z * h.z + sin2Theta(h);
    if (!(denom > 0)) return 0.0f;
    return a2 * len2 * len2 / (kPi * denom * denom);
}

float ggxVisibility(Vec3 wo, Vec3 wi, float alpha) {
    const float denom = 2.0f * (wi.z * ggxRoot(wo, alpha) + wo.z * ggxRoot(wi, alpha));
    return denom > 0 ? 1.0f / denom : 0.0f;
}

float ggxMaskingRatio(Vec3 wo, Vec3 wi, float alpha) {
    const float rootO = ggxRoot(wo, alpha), rootI = ggxRoot(wi, alpha);
    const float denom = wi.z * rootO + wo.z * rootI;
    return denom > 0 ? wi.z * (wo.z + rootO) / denom : 0.0f;
}

float ggxReflectionPdf(Vec3 wo, Vec3 wi, float alpha) {
    return ggxD(wo + wi, alpha) * ggxG1OverCos(wo, alpha) * 0.25f;
}

float ggxG2(Vec3 wo, Vec3 wi, float alpha) {
    const float denom = wi.z * ggxRoot(wo, alpha) + wo.z * ggxRoot(wi, alpha);
    return denom > 0 ? 2.0f * wo.z * wi.z / denom : 0.0f;
}

float ggxVisibleNormalPdf(Vec3 wo, Vec3 h, float alpha) {
    const float cosOh = dot(wo, h);
    if (!(cosOh > 0) || !(wo.z > 0)) return 0.0f;
    return ggxG1OverCos(wo, alpha) * cosOh * ggxD(h, alpha);
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

float halfVectorCos(Vec3 wo, Vec3 wi) { return std::clamp(0.5f * length(wo + wi), 0.0f, 1.0f); }

std::optional<Vec3> sampleGgxReflection(Vec3 wo, float alpha, Vec2 u) {
    const Vec3 wi = reflectAbout(wo, sampleGgxVisibleNormal(wo, alpha, u));
    if (!(wi.z > 0) || !isFinite(wi)) return std::nullopt;
    return normalize(wi);
}

}  // namespace tripath
