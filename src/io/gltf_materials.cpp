// glTF 2.0 materials → Material (gltf_materials.h; the user-facing table is in docs/gltf.md).
//
// Material mapping, from pbrMetallicRoughness, tested in this order:
//   KHR_materials_transmission.transmissionFactor 1,     → Dielectric (smooth glass) at roughness 0 or
//   metallic 0, no metallicRoughnessTexture               ior 1, else RoughDielectric (Walter et al.);
//                                                          albedo = baseColor, ior = KHR_materials_ior.ior
//                                                          (default 1.5)
//   transmissionFactor > 0 otherwise, unless metallic   → MetallicRoughness with that transmission: the
//   is 1 without a texture (transmission weighs the       dielectric half (1 − T) Plastic + T RoughDielectric
//   dielectric half alone)
//   a metallicRoughnessTexture                          → MetallicRoughness (glTF's metal/dielectric mix;
//                                                          its dielectric the energy-conserving Plastic,
//                                                          not Appendix B's fresnel_mix: docs/gltf.md)
//   metallicFactor 1 and roughnessFactor 0              → SmoothConductor, F0 = baseColor (the BRDF's limit:
//                                                          Schlick's Fresnel); Mirror, reflectance =
//                                                          baseColor, when marked so (mirrorMarker)
//   metallicFactor 1                                    → Conductor (GGX), F0 = baseColor, roughness
//   metallicFactor 0 and roughnessFactor ≥ 0.99         → Lambertian, albedo = baseColor (an approximation:
//                                                          the BRDF keeps a rough coat; scene files
//                                                          write Lambertian surfaces so)
//   metallicFactor 0                                    → Plastic: diffuse baseColor under a GGX coat
//                                                          of roughnessFactor, ior 1.5 (or KHR_materials_ior)
//   otherwise                                           → MetallicRoughness: metallic × Conductor +
//                                                          (1 − metallic) × Plastic
//   emission         = emissiveFactor × KHR_materials_emissive_strength.emissiveStrength (default 1)
//   absorption       = −ln(attenuationColor) / attenuationDistance of KHR_materials_volume, for a
//                      transmissive material (Beer–Lambert inside its closed mesh)
//   twoSidedEmission = doubleSided
//   no material      → Lambertian, albedo 0.8
// Textures (gltf_textures.h) multiply the factors where they are read: baseColorTexture (sRGB) the
// base colour and, with alphaMode MASK, its alpha; metallicRoughnessTexture (linear: B metallic,
// G roughness); emissiveTexture (sRGB) the emission; normalTexture bends the shading normal.
// alphaMode BLEND is read as MASK with cutoff 0.5; occlusionTexture is ignored (ambient occlusion
// is a rasteriser's stand-in for what a path tracer computes).
//
// Its own file so that the mapping, its validation and the warnings about what it drops read in
// one place; gltf_writer.h writes materials so that this mapping gives them back.
#include "io/gltf_materials.h"

#include <cmath>
#include <limits>
#include <map>
#include <memory>

namespace tripath::gltf {

namespace {

bool markedMirror(const tinygltf::Value& extras) {
    if (!extras.IsObject() || !extras.Has("tripath")) return false;
    const tinygltf::Value& ours = extras.Get("tripath");
    return ours.IsObject() && ours.Has("bsdf") && ours.Get("bsdf").IsString() &&
           ours.Get("bsdf").Get<std::string>() == "mirror";
}

// Whether KHR_materials_transmission's factor reaches the BSDF: it weighs the dielectric half
// alone, which a metallic factor of 1 leaves out unless a texture lowers it.
bool transmissive(float metallic, float transmission, bool metallicRoughnessTexture) {
    return transmission > 0 && (metallic < 1 || metallicRoughnessTexture);
}

MaterialType classifyMaterial(float metallic, float roughness, float transmission, float ior,
                              bool metallicRoughnessTexture, bool mirror) {
    if (transmission == 1 && metallic == 0 && !metallicRoughnessTexture)
        return roughness == 0 || ior == 1 ? MaterialType::Dielectric : MaterialType::RoughDielectric;
    if (transmissive(metallic, transmission, metallicRoughnessTexture)) return MaterialType::MetallicRoughness;
    if (metallicRoughnessTexture) return MaterialType::MetallicRoughness;
    if (metallic == 1 && roughness == 0) return mirror ? MaterialType::Mirror : MaterialType::SmoothConductor;
    if (metallic == 1) return MaterialType::Conductor;
    if (metallic == 0) return roughness >= 0.99f ? MaterialType::Lambertian : MaterialType::Plastic;
    return MaterialType::MetallicRoughness;
}

// Converts one model's materials, failing and warning through the report.
class MaterialConverter {
public:
    MaterialConverter(TextureReader& textures, Report& report) : textures_(textures), report_(report) {}
    Material convertMaterial(const tinygltf::Material& g, int index);
    // One warning per kind of feature some materials lose, naming them.
    void warnIgnored();

private:
    void noteIgnoredMaterialFeatures(const tinygltf::Material& g, const std::string& name);
    std::shared_ptr<const MaterialTextures> readTextures(const tinygltf::Material& g, const std::string& context);
    Spectrum emission(const tinygltf::Material& g, const std::string& context) const;
    Spectrum volumeAbsorption(const tinygltf::Material& g, bool transmissive, const std::string& name,
                              const std::string& context);
    double extensionNumber(const tinygltf::ExtensionMap& extensions, const std::string& extension,
                           const std::string& key, double fallback, const std::string& context) const;
    float unitFactor(double value, const std::string& what) const;

    TextureReader& textures_;
    Report& report_;
    std::map<std::string, std::vector<std::string>> ignored_;  // what is lost → the materials losing it
};

Material MaterialConverter::convertMaterial(const tinygltf::Material& g, int index) {
    Material m;
    m.name = g.name.empty() ? "material " + std::to_string(index) : g.name;
    const std::string context = "material '" + excerpt(m.name) + "': ";
    const auto& pbr = g.pbrMetallicRoughness;
    m.albedo = finiteVec3(pbr.baseColorFactor, Vec3(1.0f), context + "baseColorFactor", report_);
    const float metallic = unitFactor(pbr.metallicFactor, context + "metallicFactor");
    const float roughness = unitFactor(pbr.roughnessFactor, context + "roughnessFactor");
    const float transmission = unitFactor(
        extensionNumber(g.extensions, "KHR_materials_transmission", "transmissionFactor", 0.0, context),
        context + "transmissionFactor");
    m.ior = float(extensionNumber(g.extensions, "KHR_materials_ior", "ior", 1.5, context));
    m.type = classifyMaterial(metallic, roughness, transmission, m.ior, pbr.metallicRoughnessTexture.index >= 0,
                              markedMirror(g.extras));
    m.roughness = isDelta(m) ? 0.0f : roughness;
    m.metallic = m.type == MaterialType::MetallicRoughness ? metallic : 0.0f;
    m.transmission = m.type == MaterialType::MetallicRoughness ? transmission : 0.0f;
    m.emission = emission(g, context);
    m.absorption =
        volumeAbsorption(g, transmissive(metallic, transmission, pbr.metallicRoughnessTexture.index >= 0), m.name, context);
    m.twoSidedEmission = g.doubleSided;
    m.textures = readTextures(g, context);
    noteIgnoredMaterialFeatures(g, m.name);
    const std::string problem = validateMaterial(m);
    if (!problem.empty()) report_.fail(context + problem);
    return m;
}

// The textures of a material, or null when it has none that is read (an occlusionTexture alone).
std::shared_ptr<const MaterialTextures> MaterialConverter::readTextures(const tinygltf::Material& g,
                                                                        const std::string& context) {
    const auto& pbr = g.pbrMetallicRoughness;
    MaterialTextures t;
    auto read = [&](const auto& info, ColourSpace space) {
        if (info.index < 0) return TextureSlot{};
        return textures_.slot(info.index, info.texCoord, info.extensions, space, context);
    };
    t.baseColor = read(pbr.baseColorTexture, ColourSpace::Srgb);
    t.metallicRoughness = read(pbr.metallicRoughnessTexture, ColourSpace::Linear);
    t.normal = read(g.normalTexture, ColourSpace::Linear);
    t.emissive = read(g.emissiveTexture, ColourSpace::Srgb);
    t.normalScale = float(g.normalTexture.scale);
    if (!std::isfinite(t.normalScale)) report_.fail(context + "normalTexture.scale is not finite");
    t.baseAlpha = pbr.baseColorFactor.size() == 4 ? float(pbr.baseColorFactor[3]) : 1.0f;
    if (!(t.baseAlpha >= 0 && t.baseAlpha <= 1)) report_.fail(context + "baseColorFactor's alpha is outside [0, 1]");
    if (g.alphaMode == "MASK" || g.alphaMode == "BLEND") {
        t.alphaCutoff = g.alphaMode == "MASK" ? float(g.alphaCutoff) : 0.5f;
        if (!(t.alphaCutoff >= 0)) report_.fail(context + "alphaCutoff must be a number ≥ 0");
    }
    if (!t.baseColor && !t.metallicRoughness && !t.normal && !t.emissive && !t.masks()) return nullptr;
    return std::make_shared<const MaterialTextures>(std::move(t));
}

void MaterialConverter::noteIgnoredMaterialFeatures(const tinygltf::Material& g, const std::string& name) {
    auto note = [&](const std::string& what) { ignored_[what].push_back(name); };
    if (g.occlusionTexture.index >= 0)
        note("occlusionTexture is ignored (path tracing computes what it stands in for)");
    if (g.alphaMode == "BLEND") note("alphaMode BLEND is rendered as MASK with alphaCutoff 0.5");
    const auto transmission = g.extensions.find("KHR_materials_transmission");
    if (transmission != g.extensions.end() && transmission->second.IsObject() &&
        transmission->second.Has("transmissionTexture"))
        note("transmissionTexture is ignored (transmissionFactor is used)");
    for (const auto& [extension, value] : g.extensions)  // as the file's extensionsUsed say it (gltf_loader.cpp)
        if (!isHandledExtension(extension)) report_.warnOnce("extension " + excerpt(extension) + " is ignored");
}

void MaterialConverter::warnIgnored() {
    for (const auto& [what, names] : ignored_) {
        std::string list;
        for (size_t i = 0; i < names.size() && i < 3; ++i) list += (i ? ", '" : "'") + excerpt(names[i], 24) + "'";
        if (names.size() > 3) list += " and " + std::to_string(names.size() - 3) + " more";
        report_.warnOnce(what + ": material" + (names.size() > 1 ? "s " : " ") + list);
    }
}

Spectrum MaterialConverter::emission(const tinygltf::Material& g, const std::string& context) const {
    const Vec3 factor = finiteVec3(g.emissiveFactor, Vec3(0.0f), context + "emissiveFactor", report_);
    const double strength = extensionNumber(g.extensions, "KHR_materials_emissive_strength",
                                            "emissiveStrength", 1.0, context);
    if (strength < 0) report_.fail(context + "emissiveStrength is negative");
    const Spectrum e = factor * float(strength);
    if (!isFinite(e)) report_.fail(context + "emission is not finite");
    if (e.x < 0 || e.y < 0 || e.z < 0) report_.fail(context + "emission is negative");
    return e;
}

// σ_a = −ln(attenuationColor) / attenuationDistance per channel, from KHR_materials_volume (0
// without it, or at its default infinite distance). Only a transmissive material closes a volume
// (the extension requires KHR_materials_transmission); on any other it is ignored with a warning.
// thicknessFactor serves rasterisers, which see no back faces: a path tracer measures the path
// through the mesh itself.
Spectrum MaterialConverter::volumeAbsorption(const tinygltf::Material& g, bool transmissive, const std::string& name,
                                             const std::string& context) {
    const auto it = g.extensions.find("KHR_materials_volume");
    if (it == g.extensions.end() || !it->second.IsObject()) return Spectrum(0.0f);
    if (!transmissive) {
        ignored_["KHR_materials_volume without transmission is ignored"].push_back(name);
        return Spectrum(0.0f);
    }
    const double distance = extensionNumber(g.extensions, "KHR_materials_volume", "attenuationDistance",
                                            std::numeric_limits<double>::infinity(), context);
    if (!(distance > 0)) report_.fail(context + "KHR_materials_volume.attenuationDistance must be above 0");
    Spectrum colour(1.0f);
    if (it->second.Has("attenuationColor")) {
        const tinygltf::Value& c = it->second.Get("attenuationColor");
        const std::string what = context + "KHR_materials_volume.attenuationColor";
        if (!c.IsArray() || c.ArrayLen() != 3) report_.fail(what + " is not three numbers");
        for (int i = 0; i < 3; ++i) {
            if (!c.Get(i).IsNumber()) report_.fail(what + " is not three numbers");
            colour[i] = unitFactor(c.Get(i).GetNumberAsDouble(), what);
        }
    }
    Spectrum sigma;
    for (int i = 0; i < 3; ++i) sigma[i] = float(-std::log(double(colour[i])) / distance);
    return sigma;
}

double MaterialConverter::extensionNumber(const tinygltf::ExtensionMap& extensions,
                                          const std::string& extension, const std::string& key,
                                          double fallback, const std::string& context) const {
    const auto it = extensions.find(extension);
    if (it == extensions.end() || !it->second.IsObject() || !it->second.Has(key)) return fallback;
    const tinygltf::Value& value = it->second.Get(key);
    const std::string what = context + extension + "." + key;
    if (!value.IsNumber()) report_.fail(what + " is not a number");
    if (!std::isfinite(float(value.GetNumberAsDouble()))) report_.fail(what + " is not finite");
    return value.GetNumberAsDouble();
}

float MaterialConverter::unitFactor(double value, const std::string& what) const {
    if (!std::isfinite(float(value))) report_.fail(what + " is not finite");
    if (value < 0 || value > 1) report_.fail(what + " " + formatNumber(value) + " is outside [0, 1]");
    return float(value);
}

}  // namespace

std::vector<Material> convertMaterials(const tinygltf::Model& model, TextureReader& textures, Report& report) {
    MaterialConverter converter(textures, report);
    std::vector<Material> materials;
    for (size_t i = 0; i < model.materials.size(); ++i)
        materials.push_back(converter.convertMaterial(model.materials[i], int(i)));
    converter.warnIgnored();
    return materials;
}

tinygltf::Value mirrorMarker() {
    tinygltf::Value::Object bsdf{{"bsdf", tinygltf::Value(std::string("mirror"))}};
    return tinygltf::Value(tinygltf::Value::Object{{"tripath", tinygltf::Value(std::move(bsdf))}});
}

Material defaultMaterial() {
    Material m;
    m.name = "default";
    m.type = MaterialType::Lambertian;
    m.albedo = Spectrum(0.8f);
    return m;
}

}  // namespace tripath::gltf
