// The dielectric interface the glass materials share: the exact Fresnel reflectance of a smooth
// interface, and the rough dielectric lobe of Walter et al. 2007 ("Microfacet Models for
// Refraction through Rough Surfaces"): GGX microfacets that reflect with F(wo·h) and refract with
// 1 − F(wo·h), sampled through the normals visible from wo (Heitz 2018). A header of the geometry
// library's own, not part of its interface; material.cpp dispatches to it.
//
// Local shading frame (z = shading normal), directions pointing away from the surface, on either
// side: the exterior (+z) has index 1 and the interior the material's ior, so wo inside
// (wo.z < 0) sees the relative index 1/ior. The base colour tints transmission only, as
// KHR_materials_transmission says, and the smooth Dielectric does.
#pragma once
#include <optional>

#include "geometry/material.h"

namespace tripath {

// Unpolarised Fresnel reflectance of a smooth dielectric interface (Born & Wolf; pbrt 3e eq. 8.2).
// cosI ≥ 0 is the cosine on the incident side, eta = η_transmitted / η_incident. Returns 1 under
// total internal reflection; cosT receives the transmitted cosine (≥ 0).
float fresnelDielectric(float cosI, float eta, float& cosT);

// f(wo, wi) of the rough dielectric. Reflection: F D G2 / (4 |cos θo| |cos θi|), white.
// Refraction, for light arriving along wi and leaving along wo (Walter et al. eq. 21):
//     albedo · |wi·h| |wo·h| η_o² (1 − F) D G2 / (|cos θi| |cos θo| (η_i wi·h + η_o wo·h)²),
// with h the normal that refracts one into the other. That is the radiance BTDF; importance
// (light subpaths) carries its adjoint f(wi, wo), which has η_i² in place of η_o² (Veach 1997
// §5.2): f(wo, wi) / η_o² is symmetric, so pt and lt agree on paths through rough glass.
Spectrum evalRoughDielectric(const BsdfParams& m, Vec3 wo, Vec3 wi, TransportMode mode);
// Solid-angle pdf of sampleRoughDielectric drawing wi from wo: F D_wo(h) / (4 wo·h) for a
// reflection, (1 − F) D_wo(h) |∂ω_h / ∂ω_i| for a refraction (Walter et al. eq. 17).
float pdfRoughDielectric(const BsdfParams& m, Vec3 wo, Vec3 wi);
// Draws a visible normal h from u, then reflects about it with probability F(wo·h) (uc < F) and
// refracts otherwise; empty when the direction lands on the wrong side.
std::optional<Vec3> sampleRoughDielectric(const BsdfParams& m, Vec3 wo, Vec2 u, float uc);

}  // namespace tripath
