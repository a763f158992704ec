// glTF 2.0 materials → Material (gltf_materials.h; the user-facing table is in docs/gltf.md).
//
// Material mapping, from pbrMetallicRoughness factors (textures are ignored), tested in this order:
//   KHR_materials_transmission.transmissionFactor > 0   → Dielectric (smooth glass), albedo = baseColor,
//                                                          ior = KHR_materials_ior.ior (default 1.5)
//   metallicFactor ≥ 0.5 and roughnessFactor < 0.01     → Mirror, reflectance = baseColor
//   metallicFactor ≥ 0.5                                → Conductor (GGX), F0 = baseColor, roughness
//   metallicFactor < 0.5 and roughnessFactor ≥ 0.99     → Lambertian, albedo = baseColor
//   otherwise                                           → Plastic: diffuse baseColor under a GGX coat
//                                                          of roughnessFactor, ior 1.5 (or KHR_materials_ior)
//   emission         = emissiveFactor × KHR_materials_emissive_strength.emissiveStrength (default 1)
//   twoSidedEmission = doubleSided
//   no material      → Lambertian, albedo 0.8
//
// Its own file so that the mapping, its validation and the warnings about what it drops read in
// one place; gltf_writer.h writes materials so that this mapping gives them back.
#include "io/gltf_materials.h"

#include <cmath>

namespace tripath::gltf {

namespace {

MaterialType classifyMaterial(float metallic, float roughness, float transmission) {
    if (transmission > 0) return MaterialType::Dielectric;
    if (metallic >= 0.5f) return roughness < 0.01f ? MaterialType::Mirror : MaterialType::Conductor;
    return roughness >= 0.99f ? MaterialType::Lambertian : MaterialType::Plastic;
}

bool hasTexture(const tinygltf::Material& g) {
    return g.pbrMetallicRoughness.baseColorTexture.index >= 0 ||
           g.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0 ||
           g.normalTexture.index >= 0 || g.occlusionTexture.index >= 0 ||
           g.emissiveTexture.index >= 0;
}

// Converts one model's materials, failing and warning through the report.
class MaterialConverter {
public:
    explicit MaterialConverter(Report& report) : report_(report) {}
    Material convertMaterial(const tinygltf::Material& g, int index);

private:
    void warnIgnoredMaterialFeatures(const tinygltf::Material& g, float metallic, float roughness,
                                     float transmission);
    Spectrum emission(const tinygltf::Material& g, const std::string& context) const;
    double extensionNumber(const tinygltf::ExtensionMap& extensions, const std::string& extension,
                           const std::string& key, double fallback, const std::string& context) const;
    float unitFactor(double value, const std::string& what) const;

    Report& report_;
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
    m.type = classifyMaterial(metallic, roughness, transmission);
    m.roughness = (m.type == MaterialType::Mirror || m.type == MaterialType::Dielectric) ? 0.0f : roughness;
    m.emission = emission(g, context);
    m.twoSidedEmission = g.doubleSided;
    warnIgnoredMaterialFeatures(g, metallic, roughness, transmission);
    const std::string problem = validateMaterial(m);
    if (!problem.empty()) report_.fail(context + problem);
    return m;
}

void MaterialConverter::warnIgnoredMaterialFeatures(const tinygltf::Material& g, float metallic,
                                                    float roughness, float transmission) {
    if (hasTexture(g)) report_.warnOnce("textures are ignored (material factors are used)");
    if (g.alphaMode != "OPAQUE")
        report_.warnOnce("alphaMode " + excerpt(g.alphaMode) + " is ignored (surfaces are opaque)");
    if (metallic > 0 && metallic < 1)
        report_.warnOnce("metallicFactor between 0 and 1 is rounded to dielectric or metal at 0.5");
    if (transmission > 0 && transmission < 1) report_.warnOnce("transmissionFactor below 1 is treated as 1");
    if (transmission > 0 && roughness > 0) report_.warnOnce("rough transmission is rendered as smooth glass");
    for (const auto& [name, value] : g.extensions)
        if (!isHandledExtension(name)) report_.warnOnce("extension " + excerpt(name) + " is ignored");
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

std::vector<Material> convertMaterials(const tinygltf::Model& model, Report& report) {
    MaterialConverter converter(report);
    std::vector<Material> materials;
    for (size_t i = 0; i < model.materials.size(); ++i)
        materials.push_back(converter.convertMaterial(model.materials[i], int(i)));
    return materials;
}

Material defaultMaterial() {
    Material m;
    m.name = "default";
    m.type = MaterialType::Lambertian;
    m.albedo = Spectrum(0.8f);
    return m;
}

}  // namespace tripath::gltf
