// Materials: the small set of BSDFs the scene model maps glTF 2.0 onto (docs/design.md §3).
//
// Every BSDF is evaluated in its local shading frame, z = shading normal. Directions point AWAY
// from the surface: `wo` toward the vertex the walk came from, `wi` toward the next one.
// For light transport the BSDF is always f(wi -> wo) in the physical sense; reciprocal BSDFs make
// the distinction moot except for refraction, where `TransportMode` says whether radiance (camera
// subpaths) or importance (light subpaths) is carried (Veach's thesis §5.2: the 1/η² factor).
#pragma once
#include <memory>
#include <optional>
#include <string>

#include "core/vec.h"

namespace tripath {

enum class MaterialType {
    Lambertian,  // f = albedo / π
    Mirror,      // ideal specular reflection, reflectance = albedo at every angle (no Fresnel)
    Dielectric,  // ideal smooth glass: Fresnel-weighted reflection and refraction, ior
    // rough glass: GGX microfacet reflection and refraction (Walter et al. 2007), ior (refracting
    // with at least 1.001: dielectric.cpp), albedo tinting transmission
    RoughDielectric,
    Conductor,   // rough GGX microfacet metal (Cook-Torrance), F0 = albedo (Schlick Fresnel)
    // the Conductor's limit at roughness 0 (glTF's metallic 1, roughness 0): ideal specular
    // reflection of reflectance F_Schlick(albedo, cos θ)
    SmoothConductor,
    Plastic,     // diffuse albedo under a rough GGX dielectric coat of index ior
    // glTF 2.0's metallic-roughness mix (spec Appendix B): metallic × Conductor + (1 − metallic)
    // × Plastic, both with the base colour as albedo, one roughness, the coat of index ior. The
    // dielectric half is the energy-conserving Plastic, not Appendix B's fresnel_mix, which
    // reflects more than 1 at grazing angles (docs/gltf.md gives the difference). With
    // KHR_materials_transmission the dielectric half is (1 − transmission) × Plastic +
    // transmission × RoughDielectric
    MetallicRoughness,
};

const char* materialTypeName(MaterialType t);

// What the BSDF formulas read. A textured material's parameters at one point of a surface are one
// of these, made on the stack (MaterialTextures::at), with no copy of the material's name.
struct BsdfParams {
    MaterialType type = MaterialType::Lambertian;
    Spectrum albedo{0.8f};    // base colour: diffuse albedo, mirror reflectance or metal F0
    float roughness = 0.5f;   // perceptual roughness in [0,1]; GGX alpha = roughness²
    float metallic = 0.0f;    // MetallicRoughness: the conductor's weight in [0,1]
    float ior = 1.5f;         // dielectric / plastic coat index of refraction
    float transmission = 0.0f;  // MetallicRoughness: the RoughDielectric's share of its dielectric half
};

struct MaterialTextures;  // geometry/texture.h: what varies over a textured material's surfaces

struct Material : BsdfParams {
    std::string name;
    Spectrum emission{0.0f};  // emitted radiance Le (W / m² sr); zero for non-emitters
    bool twoSidedEmission = false;  // glTF doubleSided: emits from both faces
    // Absorption coefficient σ_a (1/m) of the volume a Dielectric closes (KHR_materials_volume):
    // light running inside it is attenuated by exp(−σ_a d) over a length d (kernels.h:
    // Segment::transmittance). Zero for none.
    Spectrum absorption{0.0f};
    // Null for a material uniform over its surfaces, whose BsdfParams are the ones evaluated.
    std::shared_ptr<const MaterialTextures> textures;
};

enum class TransportMode { Radiance, Importance };

struct BsdfSample {
    Vec3 wi;          // sampled direction (local frame)
    Spectrum f;       // BSDF value f(wo, wi); for a delta lobe, the lobe's weight divided by |cos θi|
    float pdf = 0;    // solid-angle pdf of wi; 1 for a delta lobe (by convention, as in pbrt)
    bool delta = false;
};

// True when the material has only delta lobes (mirror, glass): connections to it are impossible.
bool isDelta(const BsdfParams& m);

// Whether a non-delta material's lobes reach the other side of the surface (rough glass).
bool transmits(const BsdfParams& m);

// f(wo, wi) for the non-delta part; zero for delta materials.
Spectrum evalBsdf(const BsdfParams& m, Vec3 wo, Vec3 wi, TransportMode mode);
// Solid-angle pdf that sampleBsdf generates wi from wo with; zero for delta materials.
float pdfBsdf(const BsdfParams& m, Vec3 wo, Vec3 wi);
// Sample wi given wo with u in [0,1)² and uc in [0,1) (lobe choice). Empty when no direction.
std::optional<BsdfSample> sampleBsdf(const BsdfParams& m, Vec3 wo, Vec2 u, float uc, TransportMode mode);

// Checks a material's parameters; returns an error message naming the problem, or empty.
std::string validateMaterial(const Material& m);

}  // namespace tripath
