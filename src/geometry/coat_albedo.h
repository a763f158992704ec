// Directional albedo of the plastic's GGX coat, for the coupled diffuse term of Kelemen &
// Szirmay-Kalos 2001 (material.cpp's plastic): E(μ) and its cosine-weighted mean Ē, looked up in
// a table built once, on first use, from microfacet.h's GGX. A header of the geometry library's
// own, not part of its interface.
#pragma once

namespace tripath {

// E(μ) of a coat of this perceptual roughness and Schlick F0 at cos θ = mu, slightly above the
// true albedo (never below it) so that the coupled diffuse lobe keeps the total albedo ≤ 1.
float coatAlbedo(float mu, float roughness, float f0);

// Ē = 2 ∫ E(μ) μ dμ of the table as coatAlbedo interpolates it, so the coupled diffuse lobe
// (1 − E(μo)) (1 − E(μi)) / (1 − Ē) integrates exactly to 1 − E(μo).
float coatAlbedoAverage(float roughness, float f0);

}  // namespace tripath
