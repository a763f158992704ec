// The GGX (Trowbridge-Reitz) microfacet distribution that the rough materials share: the
// conductor's and the plastic coat's lobes in material.cpp and the coat albedo table
// (coat_albedo.cpp). Isotropic, with the height-correlated Smith masking-shadowing function
// (Heitz 2014, "Understanding the Masking-Shadowing Function", eq. 99) and sampling of the
// visible normals (Heitz 2018); plus Schlick's Fresnel weight, the F(wo·h) of those lobes.
// A header of the geometry library's own, not part of its interface.
//
// Local shading frame (z = shading normal), directions pointing away from the surface; all
// directions here are in the upper hemisphere (a transmitted one is mirrored up by its caller).
#pragma once
#include <optional>

#include "core/vec.h"

namespace tripath {

// The (1 − cos θ)^5 factor of Schlick's approximation (Schlick 1994, eq. 24).
float schlickWeight(float cosTheta);

// Perceptual roughness -> GGX alpha; the floor keeps D finite (peak 1/(π α²)) for roughness 0.
float ggxAlpha(float roughness);

// D(h) for the un-normalised half vector h = wo + wi, written with |h|⁴ / (α² h_z² + h_xy²)²
// so no 1 − cos² cancellation occurs (Walter et al. 2007, eq. 33).
float ggxD(Vec3 h, float alpha);

// Height-correlated G2 / (4 cos θo cos θi) = 1 / (2 (zi·rootO + zo·rootI)): the whole
// geometric part of the Cook-Torrance BRDF, symmetric in wo and wi.
float ggxVisibility(Vec3 wo, Vec3 wi, float alpha);

// Height-correlated G2(wo, wi) = 1 / (1 + Λ(wo) + Λ(wi)) itself, for two directions given on the
// upper side (a transmitted one mirrored up): the rough dielectric's refraction lobe reads it.
float ggxG2(Vec3 wo, Vec3 wi, float alpha);

// G2(wo,wi) / G1(wo): the weight f·cos θi / pdf of a VNDF-sampled reflection with F = 1.
float ggxMaskingRatio(Vec3 wo, Vec3 wi, float alpha);

// Solid-angle density of wi = reflect(wo, h) with h ~ D_wo: D_wo(h) / (4 wo·h)
// = G1(wo) D(h) / (4 cos θo) (Heitz 2018, eq. 17). Both directions in the upper hemisphere.
float ggxReflectionPdf(Vec3 wo, Vec3 wi, float alpha);

// Cosine between wo (or wi) and their half vector: for unit vectors wo·(wo + wi) = |wo + wi|²/2, so
// cos θh = |wo + wi| / 2. Unlike dot(wo, ĥ) this is symmetric in wo, wi bit for bit (reciprocity)
// and free of the cancellation in 1 + wo·wi when wo ≈ −wi.
float halfVectorCos(Vec3 wo, Vec3 wi);

// Density of the microfacet normals visible from wo at the unit normal h,
// D_wo(h) = G1(wo) max(0, wo·h) D(h) / cos θo (Heitz 2018, eq. 3), per solid angle of h.
float ggxVisibleNormalPdf(Vec3 wo, Vec3 h, float alpha);

// Draw a microfacet normal from D_wo (Heitz 2018, listing 1).
Vec3 sampleGgxVisibleNormal(Vec3 wo, float alpha, Vec2 u);

// Draw wi by reflecting wo about a visible normal; empty when it lands below the horizon.
std::optional<Vec3> sampleGgxReflection(Vec3 wo, float alpha, Vec2 u);

}  // namespace tripath
