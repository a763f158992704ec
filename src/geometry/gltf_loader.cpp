// glTF 2.0 → SceneDesc (see docs/gltf.md for the user-facing feature table).
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
// Geometry: TRIANGLES primitives (other modes are skipped with a warning), POSITION and NORMAL as
// float VEC3, unsigned byte/short/int indices or none. Nodes of the default scene (else scene 0,
// else every root node) are composed parent × child; positions take the full matrix, normals its
// inverse transpose. Mirroring transforms (negative determinant) reverse the winding so the front
// face stays where the file put it. Triangles that are degenerate in world space are dropped.
// Lights: KHR_lights_punctual point lights; camera: the first perspective camera in depth-first order.
//
// Files: tinygltf opens only the buffer files that approveBufferFiles let through (external_files.h
// says which), through the file-system callbacks below; image files are never opened.
#include "geometry/gltf_loader.h"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_access.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>
#include <string_view>

#include "geometry/error.h"
#include "geometry/external_files.h"

namespace tripath {

namespace {

// A triangle is dropped when sin(angle between two edges) falls below this (zero-area slivers).
constexpr double kDegenerateSine = 1e-6;
// A mesh transform collapses when |det| / (product of its column lengths) falls below this.
constexpr double kCollapseRatio = 1e-6;

// Extensions whose content the loader reads.
const std::set<std::string> kHandledExtensions = {
    "KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
    "KHR_materials_emissive_strength"};
// Extensions that only refine appearance: accepted even when required, with a warning.
const std::set<std::string> kIgnorableExtensions = {
    "KHR_materials_specular",   "KHR_materials_clearcoat", "KHR_materials_sheen",
    "KHR_materials_volume",     "KHR_materials_iridescence", "KHR_materials_anisotropy",
    "KHR_materials_dispersion", "KHR_materials_variants",  "KHR_texture_transform",
    "KHR_texture_basisu",       "EXT_texture_webp",        "EXT_texture_avif"};

// Node transforms are glm::dmat4, column-major like glTF's node.matrix: (row r, column c) is m[c][r].

glm::dvec3 toGlm(Vec3 v) { return {v.x, v.y, v.z}; }
Vec3 toVec3(glm::dvec3 v) { return {float(v.x), float(v.y), float(v.z)}; }

bool allFinite(const glm::dmat4& a) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(a[c][r])) return false;
    return true;
}

bool isAffine(const glm::dmat4& a) { return glm::row(a, 3) == glm::dvec4(0, 0, 0, 1); }

// The upper 3×3: the linear part that directions, normals and the winding see.
glm::dmat3 linearPart(const glm::dmat4& a) { return glm::dmat3(a); }

// True when the upper 3×3 squashes space onto a plane, line or point (or is not finite).
bool collapsesSpace(const glm::dmat4& a) {
    const glm::dmat3 m = linearPart(a);
    const double scale = glm::length(m[0]) * glm::length(m[1]) * glm::length(m[2]);
    return !(std::abs(glm::determinant(m)) > kCollapseRatio * scale);
}

// The linear part, then the translation: ((a x + b y) + c z) + t, where glm's dmat4 × dvec4 would
// add in pairs, (a x + b y) + (c z + t), and round differently.
Vec3 transformPoint(const glm::dmat4& a, Vec3 p) {
    return toVec3(linearPart(a) * toGlm(p) + glm::dvec3(a[3]));
}

// Inverse transpose of the linear part, as cofactors over the determinant: row i of the cofactor
// matrix is the cross product of the rows after it (cyclically). glm::inverseTranspose would
// expand the determinant along the other axis and negate cofactors, which moves last bits and
// turns +0 entries into -0; the tangent frames built around normals (copysign in vec.h) see both.
glm::dmat3 normalMatrix(const glm::dmat3& m) {
    const glm::dmat3 rows = glm::transpose(m);
    const glm::dmat3 cofactorRows(glm::cross(rows[1], rows[2]), glm::cross(rows[2], rows[0]),
                                  glm::cross(rows[0], rows[1]));
    return glm::transpose(cofactorRows) / glm::determinant(m);
}

// parent × child, the world transform of the child. Zero entries come out as +0 whatever the
// signs of their products (x + 0 is x for any other x): a vertex coordinate at zero keeps one
// sign, and with it the tangent frames built from the triangle's normal (copysign in vec.h).
glm::dmat4 compose(const glm::dmat4& parent, const glm::dmat4& child) {
    return parent * child + glm::dmat4(0.0);
}

// Unit direction of m × v; zero vector when it vanishes or is not finite.
Vec3 transformDirection(const glm::dmat3& m, Vec3 v) {
    const glm::dvec3 d = m * toGlm(v);
    const double len = glm::length(d);
    if (!(len > 0) || !std::isfinite(len)) return Vec3(0.0f);
    return toVec3(d / len);
}

// T × R × S of a node without a matrix; inputs already checked for length and finiteness, the
// rotation normalised.
glm::dmat4 composeTrs(const glm::dvec3& t, const glm::dquat& r, const glm::dvec3& s) {
    glm::dmat4 m = glm::scale(glm::dmat4(glm::mat3_cast(r)), s);  // R × S: columns scaled
    m[3] = glm::dvec4(t, 1.0);                                      // T × (R × S)
    return m;
}

bool allFinite(const std::vector<double>& values) {
    for (double x : values)
        if (!std::isfinite(float(x))) return false;
    return true;
}

bool isDegenerate(Vec3 a, Vec3 b, Vec3 c) {
    const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
    const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
    const double cx = e1[1] * e2[2] - e1[2] * e2[1];
    const double cy = e1[2] * e2[0] - e1[0] * e2[2];
    const double cz = e1[0] * e2[1] - e1[1] * e2[0];
    const double l1 = e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2];
    const double l2 = e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2];
    return !(cx * cx + cy * cy + cz * cz > kDegenerateSine * kDegenerateSine * l1 * l2);
}

// Collapses tinygltf's multi-line messages into one line.
std::string oneLine(const std::string& text) {
    std::string out;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
        if (line.empty()) continue;
        if (!out.empty()) out += "; ";
        out += line;
    }
    return out;
}

// Shortest readable form of a number for messages ("4", "0.25", "1e+39").
std::string formatNumber(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
}

std::string primitiveModeName(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS: return "POINTS";
        case TINYGLTF_MODE_LINE: return "LINES";
        case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
        case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
        default: return "mode " + std::to_string(mode);
    }
}

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

// Quoted for a one-line message: quotes, backslashes and control characters are escaped.
std::string quoted(const std::string& text) {
    std::string out = "\"";
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (byte < 0x20 || byte == 0x7f) {
            static const char* const kHex = "0123456789abcdef";
            out += "\\x";
            out += kHex[byte >> 4];
            out += kHex[byte & 15];
        } else {
            out += c;
        }
    }
    return out + "\"";
}

// The JSON chunk of a GLB file; empty when the header is malformed (tinygltf then says how).
std::string_view glbJsonChunk(const std::vector<char>& bytes) {
    constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON", little-endian
    if (bytes.size() < 20) return {};
    uint32_t length = 0, type = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    std::memcpy(&type, bytes.data() + 16, 4);
    if (type != kJsonChunk || length > bytes.size() - 20) return {};
    return {bytes.data() + 20, length};
}

// The files tinygltf may open: the resolved paths of the buffer files approveBufferFiles let
// through. The callbacks get each URI decoded (the model is loaded with an empty base folder)
// and resolve it against the scene's folder again; everything else, image files included, is
// reported missing.
struct ApprovedFiles {
    std::filesystem::path folder;
    bool allowOutside = false;
    std::set<std::filesystem::path> files;

    // The file `decodedUri` names, or an empty path when it was not approved.
    std::filesystem::path find(const std::string& decodedUri) const {
        const ExternalFile file = resolveExternalFile(folder, decodedUri, allowOutside);
        return file.problem.empty() && files.count(file.path) ? file.path : std::filesystem::path();
    }
};

bool approvedFileExists(const std::string& decodedUri, void* approved) {
    return !static_cast<const ApprovedFiles*>(approved)->find(decodedUri).empty();
}

std::string keepPath(const std::string& path, void*) { return path; }

bool readApprovedFile(std::vector<unsigned char>* out, std::string* err, const std::string& decodedUri,
                      void* approved) {
    const std::filesystem::path path = static_cast<const ApprovedFiles*>(approved)->find(decodedUri);
    if (!path.empty()) {
        std::error_code ec;
        const uintmax_t size = std::filesystem::file_size(path, ec);
        std::ifstream in(path, std::ios::binary);
        if (!ec && in) {
            out->resize(size_t(size));
            if (in.read(reinterpret_cast<char*>(out->data()), std::streamsize(out->size()))) return true;
        }
    }
    *err += "cannot read " + quoted(decodedUri);
    return false;
}

// Textures are not supported: accept every image without decoding it.
bool skipImageDecoding(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                       const unsigned char*, int, void*) {
    return true;
}

// The bytes of an accessor's first element and the distance between elements.
struct AccessorBytes {
    const unsigned char* first = nullptr;
    size_t stride = 0;
    size_t count = 0;
};

class GltfLoader {
public:
    GltfLoader(std::string path, WarningSink warn, const GltfOptions& options)
        : path_(std::move(path)), warn_(std::move(warn)) {
        approved_.allowOutside = options.allowExternalFiles;
    }
    SceneDesc load();

private:
    [[noreturn]] void fail(const std::string& what) const { throw InputError(path_ + ": " + what); }
    void warnOnce(const std::string& what);

    void readModel();
    std::vector<char> readSceneFile() const;
    void approveBufferFiles(std::string_view json);
    void forwardLibraryWarnings(const std::string& text);
    void checkExtensions();
    void warnIgnoredModelFeatures();

    void convertMaterials();
    Material convertMaterial(const tinygltf::Material& g, int index);
    void warnIgnoredMaterialFeatures(const tinygltf::Material& g, float metallic, float roughness,
                                     float transmission);
    Spectrum emission(const tinygltf::Material& g, const std::string& context) const;
    double extensionNumber(const tinygltf::ExtensionMap& extensions, const std::string& extension,
                           const std::string& key, double fallback, const std::string& context) const;
    Vec3 finiteVec3(const std::vector<double>& values, Vec3 fallback, const std::string& what) const;
    float unitFactor(double value, const std::string& what) const;
    int materialIndex(int gltfMaterial, const std::string& what);

    std::vector<int> rootNodes() const;
    void traverseScene();
    glm::dmat4 visitNode(int index, const glm::dmat4& parent);
    glm::dmat4 localTransform(const tinygltf::Node& node, int index) const;

    void addMesh(int meshIndex, const glm::dmat4& world, int nodeIndex);
    void addPrimitive(const tinygltf::Primitive& prim, const std::string& name, const glm::dmat4& world);
    std::vector<Vec3> worldNormals(const tinygltf::Primitive& prim, size_t vertexCount,
                                   const glm::dmat4& world, const std::string& what);
    MeshDesc keepGoodTriangles(const std::vector<Vec3>& positions, const std::vector<Vec3>& normals,
                               const std::vector<uint32_t>& indices, bool flipWinding);

    const tinygltf::Accessor& accessor(int index, const std::string& what) const;
    AccessorBytes accessorBytes(int index, size_t elementSize) const;
    std::vector<Vec3> readVec3(int index, const std::string& what) const;
    std::vector<uint32_t> readIndices(int index, const std::string& what) const;

    void addCamera(int cameraIndex, const glm::dmat4& world, int nodeIndex);
    void addLight(const tinygltf::Node& node, const glm::dmat4& world, int nodeIndex);

    std::string path_;
    WarningSink warn_;
    ApprovedFiles approved_;
    tinygltf::Model model_;
    SceneDesc scene_;
    std::set<std::string> warned_;
    int defaultMaterial_ = -1;
    size_t droppedTriangles_ = 0;
};

SceneDesc GltfLoader::load() {
    scene_.name = path_;
    readModel();
    checkExtensions();
    warnIgnoredModelFeatures();
    convertMaterials();
    traverseScene();
    if (droppedTriangles_ > 0)
        warnOnce("dropped " + std::to_string(droppedTriangles_) + " degenerate (zero-area) triangles");
    if (scene_.meshes.empty()) fail("the scene contains no triangles");
    return std::move(scene_);
}

void GltfLoader::warnOnce(const std::string& what) {
    if (warned_.insert(what).second && warn_) warn_(path_ + ": " + what);
}

// ---------------------------------------------------------------------------------------------
// File and extensions

void GltfLoader::readModel() {
    const std::vector<char> bytes = readSceneFile();
    const bool binary = std::memcmp(bytes.data(), "glTF", 4) == 0 ||
                        std::filesystem::path(path_).extension() == ".glb";
    std::error_code ec;
    approved_.folder = std::filesystem::canonical(std::filesystem::absolute(path_).parent_path(), ec);
    if (ec) fail("cannot resolve the scene's folder (" + ec.message() + ")");
    approveBufferFiles(binary ? glbJsonChunk(bytes) : std::string_view(bytes.data(), bytes.size()));

    tinygltf::TinyGLTF parser;
    parser.SetImageLoader(&skipImageDecoding, nullptr);
    parser.SetFsCallbacks({&approvedFileExists, &keepPath, &readApprovedFile, nullptr, &approved_});
    std::string err, warnings;
    bool ok = false;
    try {
        const auto size = static_cast<unsigned int>(bytes.size());
        ok = binary ? parser.LoadBinaryFromMemory(&model_, &err, &warnings,
                                                  reinterpret_cast<const unsigned char*>(bytes.data()), size, "")
                    : parser.LoadASCIIFromString(&model_, &err, &warnings, bytes.data(), size, "");
    } catch (const std::exception& e) {
        fail(std::string("cannot parse glTF: ") + e.what());
    }
    forwardLibraryWarnings(warnings);
    if (!ok) fail(err.empty() ? std::string("cannot parse glTF") : oneLine(err));
}

std::vector<char> GltfLoader::readSceneFile() const {
    std::error_code ec;
    if (!std::filesystem::exists(path_, ec)) fail("file not found");
    if (!std::filesystem::is_regular_file(path_, ec)) fail("not a regular file");
    const uintmax_t size = std::filesystem::file_size(path_, ec);
    if (!ec && size > UINT_MAX) fail("file is larger than 4 GiB (not supported)");
    std::vector<char> bytes(ec ? 0 : size_t(size));
    std::ifstream in(path_, std::ios::binary);
    if (bytes.size() < 4 || !in || !in.read(bytes.data(), std::streamsize(bytes.size())))
        fail("cannot read file (empty or unreadable)");
    return bytes;
}

// Checks every external buffer URI before tinygltf opens any file, so that a refusal names the
// buffer; approves the files that pass. JSON that does not parse is left for tinygltf to report.
void GltfLoader::approveBufferFiles(std::string_view json) {
    const auto doc = nlohmann::json::parse(json.begin(), json.end(), nullptr, false);
    if (!doc.is_object() || !doc.contains("buffers") || !doc["buffers"].is_array()) return;
    const auto& buffers = doc["buffers"];
    for (size_t i = 0; i < buffers.size(); ++i) {
        const auto& buffer = buffers[i];
        if (!buffer.is_object() || !buffer.contains("uri") || !buffer["uri"].is_string()) continue;
        const std::string& uri = buffer["uri"].get_ref<const std::string&>();
        if (uri.empty() || tinygltf::IsDataURI(uri)) continue;
        const ExternalFile file = resolveExternalFile(approved_.folder, decodeUriPath(uri), approved_.allowOutside);
        if (!file.problem.empty()) {
            std::string name = "buffer " + std::to_string(i);
            if (buffer.contains("name") && buffer["name"].is_string())
                name += " " + quoted(buffer["name"].get_ref<const std::string&>());
            fail(name + ": uri " + quoted(uri) + " names " + quoted(file.path.string()) + ", " + file.problem);
        }
        approved_.files.insert(file.path);
    }
}

// tinygltf's own warnings, minus those about image files: textures are ignored anyway (and a
// missing file only warns for images; a missing buffer is an error).
void GltfLoader::forwardLibraryWarnings(const std::string& text) {
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        line = oneLine(line);
        const bool aboutImages = line.find("image") != std::string::npos ||
                                 line.find("Image") != std::string::npos ||
                                 line.rfind("File not found", 0) == 0;
        if (!line.empty() && !aboutImages) warnOnce(line);
    }
}

void GltfLoader::checkExtensions() {
    for (const std::string& name : model_.extensionsRequired) {
        if (!kHandledExtensions.count(name) && !kIgnorableExtensions.count(name))
            fail("required extension " + name + " is not supported");
    }
    for (const auto* list : {&model_.extensionsRequired, &model_.extensionsUsed})
        for (const std::string& name : *list)
            if (!kHandledExtensions.count(name)) warnOnce("extension " + name + " is ignored");
}

void GltfLoader::warnIgnoredModelFeatures() {
    if (!model_.textures.empty() || !model_.images.empty())
        warnOnce("textures are ignored (material factors are used)");
    if (!model_.animations.empty()) warnOnce("animations are ignored (the static pose is used)");
    if (!model_.skins.empty()) warnOnce("skins are ignored (meshes use their node transforms)");
}

// ---------------------------------------------------------------------------------------------
// Materials

void GltfLoader::convertMaterials() {
    for (size_t i = 0; i < model_.materials.size(); ++i)
        scene_.materials.push_back(convertMaterial(model_.materials[i], int(i)));
}

Material GltfLoader::convertMaterial(const tinygltf::Material& g, int index) {
    Material m;
    m.name = g.name.empty() ? "material " + std::to_string(index) : g.name;
    const std::string context = "material '" + m.name + "': ";
    const auto& pbr = g.pbrMetallicRoughness;
    m.albedo = finiteVec3(pbr.baseColorFactor, Vec3(1.0f), context + "baseColorFactor");
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
    if (!problem.empty()) fail(context + problem);
    return m;
}

void GltfLoader::warnIgnoredMaterialFeatures(const tinygltf::Material& g, float metallic,
                                             float roughness, float transmission) {
    if (hasTexture(g)) warnOnce("textures are ignored (material factors are used)");
    if (g.alphaMode != "OPAQUE") warnOnce("alphaMode " + g.alphaMode + " is ignored (surfaces are opaque)");
    if (metallic > 0 && metallic < 1)
        warnOnce("metallicFactor between 0 and 1 is rounded to dielectric or metal at 0.5");
    if (transmission > 0 && transmission < 1) warnOnce("transmissionFactor below 1 is treated as 1");
    if (transmission > 0 && roughness > 0) warnOnce("rough transmission is rendered as smooth glass");
    for (const auto& [name, value] : g.extensions)
        if (!kHandledExtensions.count(name)) warnOnce("extension " + name + " is ignored");
}

Spectrum GltfLoader::emission(const tinygltf::Material& g, const std::string& context) const {
    const Vec3 factor = finiteVec3(g.emissiveFactor, Vec3(0.0f), context + "emissiveFactor");
    const double strength = extensionNumber(g.extensions, "KHR_materials_emissive_strength",
                                            "emissiveStrength", 1.0, context);
    if (strength < 0) fail(context + "emissiveStrength is negative");
    const Spectrum e = factor * float(strength);
    if (!isFinite(e)) fail(context + "emission is not finite");
    if (e.x < 0 || e.y < 0 || e.z < 0) fail(context + "emission is negative");
    return e;
}

double GltfLoader::extensionNumber(const tinygltf::ExtensionMap& extensions,
                                   const std::string& extension, const std::string& key,
                                   double fallback, const std::string& context) const {
    const auto it = extensions.find(extension);
    if (it == extensions.end() || !it->second.IsObject() || !it->second.Has(key)) return fallback;
    const tinygltf::Value& value = it->second.Get(key);
    const std::string what = context + extension + "." + key;
    if (!value.IsNumber()) fail(what + " is not a number");
    if (!std::isfinite(float(value.GetNumberAsDouble()))) fail(what + " is not finite");
    return value.GetNumberAsDouble();
}

Vec3 GltfLoader::finiteVec3(const std::vector<double>& values, Vec3 fallback,
                            const std::string& what) const {
    if (values.empty()) return fallback;
    if (values.size() < 3) fail(what + " has " + std::to_string(values.size()) + " components");
    if (!allFinite(values)) fail(what + " is not finite");
    return {float(values[0]), float(values[1]), float(values[2])};
}

float GltfLoader::unitFactor(double value, const std::string& what) const {
    if (!std::isfinite(float(value))) fail(what + " is not finite");
    if (value < 0 || value > 1) fail(what + " " + formatNumber(value) + " is outside [0, 1]");
    return float(value);
}

int GltfLoader::materialIndex(int gltfMaterial, const std::string& what) {
    if (gltfMaterial >= 0) {
        if (size_t(gltfMaterial) >= model_.materials.size())
            fail(what + " references material " + std::to_string(gltfMaterial) + ", which does not exist");
        return gltfMaterial;
    }
    if (defaultMaterial_ < 0) {
        Material m;
        m.name = "default";
        m.type = MaterialType::Lambertian;
        m.albedo = Spectrum(0.8f);
        defaultMaterial_ = int(scene_.materials.size());
        scene_.materials.push_back(m);
    }
    return defaultMaterial_;
}

// ---------------------------------------------------------------------------------------------
// Node hierarchy

std::vector<int> GltfLoader::rootNodes() const {
    if (model_.defaultScene >= 0) {
        if (size_t(model_.defaultScene) >= model_.scenes.size())
            fail("default scene " + std::to_string(model_.defaultScene) + " does not exist");
        return model_.scenes[size_t(model_.defaultScene)].nodes;
    }
    if (!model_.scenes.empty()) return model_.scenes[0].nodes;
    std::vector<bool> isChild(model_.nodes.size(), false);
    for (const auto& node : model_.nodes)
        for (int child : node.children)
            if (child >= 0 && size_t(child) < isChild.size()) isChild[size_t(child)] = true;
    std::vector<int> roots;
    for (size_t i = 0; i < isChild.size(); ++i)
        if (!isChild[i]) roots.push_back(int(i));
    return roots;
}

// Depth-first, children in order, with an explicit stack (deep hierarchies cannot overflow it).
void GltfLoader::traverseScene() {
    struct Frame {
        int node;
        glm::dmat4 world;
        size_t nextChild;
    };
    std::vector<char> onPath(model_.nodes.size(), 0);
    for (int root : rootNodes()) {
        std::vector<Frame> stack;
        stack.push_back({root, visitNode(root, glm::dmat4(1.0)), 0});
        onPath[size_t(root)] = 1;
        while (!stack.empty()) {
            Frame& top = stack.back();
            const auto& children = model_.nodes[size_t(top.node)].children;
            if (top.nextChild == children.size()) {
                onPath[size_t(top.node)] = 0;
                stack.pop_back();
                continue;
            }
            const int child = children[top.nextChild++];
            const glm::dmat4 parentWorld = top.world;
            const glm::dmat4 world = visitNode(child, parentWorld);
            if (onPath[size_t(child)])
                fail("node " + std::to_string(child) + " is its own ancestor (cycle in the node hierarchy)");
            onPath[size_t(child)] = 1;
            stack.push_back({child, world, 0});
        }
    }
}

// Adds what the node carries and returns its world transform.
glm::dmat4 GltfLoader::visitNode(int index, const glm::dmat4& parent) {
    if (index < 0 || size_t(index) >= model_.nodes.size())
        fail("node " + std::to_string(index) + " does not exist");
    const tinygltf::Node& node = model_.nodes[size_t(index)];
    const glm::dmat4 world = compose(parent, localTransform(node, index));
    if (!allFinite(world)) fail("node " + std::to_string(index) + " has a non-finite world transform");
    if (node.mesh >= 0) addMesh(node.mesh, world, index);
    if (node.camera >= 0) addCamera(node.camera, world, index);
    addLight(node, world, index);
    return world;
}

glm::dmat4 GltfLoader::localTransform(const tinygltf::Node& node, int index) const {
    const std::string what = "node " + std::to_string(index);
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) fail(what + " matrix does not have 16 entries");
        if (!allFinite(node.matrix)) fail(what + " has a non-finite matrix");
        const glm::dmat4 m = glm::make_mat4(node.matrix.data());
        if (!isAffine(m)) fail(what + " matrix is not affine (last row must be 0 0 0 1)");
        return m;
    }
    const std::vector<double> t = node.translation.empty() ? std::vector<double>{0, 0, 0} : node.translation;
    const std::vector<double> q = node.rotation.empty() ? std::vector<double>{0, 0, 0, 1} : node.rotation;
    const std::vector<double> s = node.scale.empty() ? std::vector<double>{1, 1, 1} : node.scale;
    if (t.size() != 3 || q.size() != 4 || s.size() != 3) fail(what + " has a malformed translation, rotation or scale");
    if (!allFinite(t) || !allFinite(q) || !allFinite(s)) fail(what + " has a non-finite translation, rotation or scale");
    const glm::dquat rotation(q[3], q[0], q[1], q[2]);  // glTF stores (x, y, z, w); glm takes w first
    if (!(glm::length(rotation) > 0)) fail(what + " rotation quaternion has zero length");
    return composeTrs(glm::make_vec3(t.data()), glm::normalize(rotation), glm::make_vec3(s.data()));
}

// ---------------------------------------------------------------------------------------------
// Meshes

void GltfLoader::addMesh(int meshIndex, const glm::dmat4& world, int nodeIndex) {
    const std::string node = "node " + std::to_string(nodeIndex);
    if (size_t(meshIndex) >= model_.meshes.size())
        fail(node + " references mesh " + std::to_string(meshIndex) + ", which does not exist");
    if (collapsesSpace(world))
        fail(node + " transform collapses mesh " + std::to_string(meshIndex) + " (zero scale or singular matrix)");
    const tinygltf::Mesh& mesh = model_.meshes[size_t(meshIndex)];
    for (size_t k = 0; k < mesh.primitives.size(); ++k) {
        const std::string name = (mesh.name.empty() ? "mesh " + std::to_string(meshIndex) : mesh.name) +
                                 " primitive " + std::to_string(k);
        addPrimitive(mesh.primitives[k], name, world);
    }
}

void GltfLoader::addPrimitive(const tinygltf::Primitive& prim, const std::string& name, const glm::dmat4& world) {
    if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) {
        warnOnce(primitiveModeName(prim.mode) + " primitives are skipped (only TRIANGLES is supported)");
        return;
    }
    if (!prim.targets.empty()) warnOnce("morph targets are ignored (the base geometry is used)");
    const auto position = prim.attributes.find("POSITION");
    if (position == prim.attributes.end()) fail(name + " has no POSITION attribute");

    std::vector<Vec3> positions = readVec3(position->second, name + " POSITION");
    for (Vec3& p : positions) p = transformPoint(world, p);
    for (const Vec3& p : positions)
        if (!isFinite(p)) fail(name + " has non-finite vertex positions");
    const std::vector<Vec3> normals = worldNormals(prim, positions.size(), world, name);

    std::vector<uint32_t> indices;
    if (prim.indices >= 0) {
        indices = readIndices(prim.indices, name);
    } else {
        indices.resize(positions.size());
        for (size_t i = 0; i < indices.size(); ++i) indices[i] = uint32_t(i);
    }
    if (indices.size() % 3 != 0)
        fail(name + " has " + std::to_string(indices.size()) + " indices, not a multiple of 3");
    for (uint32_t i : indices)
        if (i >= positions.size())
            fail(name + " index " + std::to_string(i) + " is out of range (" +
                 std::to_string(positions.size()) + " vertices)");

    MeshDesc mesh = keepGoodTriangles(positions, normals, indices, glm::determinant(linearPart(world)) < 0);
    if (mesh.indices.empty()) return;
    mesh.name = name;
    mesh.material = materialIndex(prim.material, name);
    scene_.meshes.push_back(std::move(mesh));
}

// World-space unit shading normals, or none when the primitive has no usable NORMAL attribute.
std::vector<Vec3> GltfLoader::worldNormals(const tinygltf::Primitive& prim, size_t vertexCount,
                                           const glm::dmat4& world, const std::string& what) {
    const auto attribute = prim.attributes.find("NORMAL");
    if (attribute == prim.attributes.end()) return {};
    std::vector<Vec3> normals = readVec3(attribute->second, what + " NORMAL");
    if (normals.size() != vertexCount)
        fail(what + " has " + std::to_string(normals.size()) + " normals for " +
             std::to_string(vertexCount) + " positions");
    const glm::dmat3 toWorld = normalMatrix(linearPart(world));
    for (Vec3& n : normals) {
        n = transformDirection(toWorld, n);
        if (isBlack(n)) {
            warnOnce("primitives with zero-length or non-finite normals use geometric normals");
            return {};
        }
    }
    return normals;
}

// Copies the non-degenerate triangles and the vertices they use; counts the dropped ones.
MeshDesc GltfLoader::keepGoodTriangles(const std::vector<Vec3>& positions,
                                       const std::vector<Vec3>& normals,
                                       const std::vector<uint32_t>& indices, bool flipWinding) {
    constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
    std::vector<uint32_t> remap(positions.size(), kUnused);
    MeshDesc mesh;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        uint32_t tri[3] = {indices[t], indices[t + 1], indices[t + 2]};
        if (flipWinding) std::swap(tri[1], tri[2]);
        if (isDegenerate(positions[tri[0]], positions[tri[1]], positions[tri[2]])) {
            ++droppedTriangles_;
            continue;
        }
        for (uint32_t v : tri) {
            if (remap[v] == kUnused) {
                remap[v] = uint32_t(mesh.positions.size());
                mesh.positions.push_back(positions[v]);
                if (!normals.empty()) mesh.normals.push_back(normals[v]);
            }
            mesh.indices.push_back(remap[v]);
        }
    }
    return mesh;
}

// ---------------------------------------------------------------------------------------------
// Accessors

const tinygltf::Accessor& GltfLoader::accessor(int index, const std::string& what) const {
    if (index < 0 || size_t(index) >= model_.accessors.size())
        fail(what + " references accessor " + std::to_string(index) + ", which does not exist");
    const tinygltf::Accessor& a = model_.accessors[size_t(index)];
    if (a.sparse.isSparse) fail("accessor " + std::to_string(index) + " is sparse (not supported)");
    return a;
}

// Validates the bufferView and buffer indices and that every element lies inside both.
AccessorBytes GltfLoader::accessorBytes(int index, size_t elementSize) const {
    const tinygltf::Accessor& a = model_.accessors[size_t(index)];
    const std::string name = "accessor " + std::to_string(index);
    if (a.bufferView < 0) fail(name + " has no bufferView (not supported)");
    if (size_t(a.bufferView) >= model_.bufferViews.size())
        fail(name + " references bufferView " + std::to_string(a.bufferView) + ", which does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
    const std::string viewName = "bufferView " + std::to_string(a.bufferView);
    if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
        fail(viewName + " references buffer " + std::to_string(view.buffer) + ", which does not exist");
    const std::vector<unsigned char>& data = model_.buffers[size_t(view.buffer)].data;
    const std::string bufferName = "buffer " + std::to_string(view.buffer);
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
        fail(viewName + " reads past the end of " + bufferName);
    const size_t stride = view.byteStride != 0 ? view.byteStride : elementSize;
    if (stride < elementSize) fail(viewName + " byteStride is smaller than the elements of " + name);
    if (a.count > 0) {
        const size_t available = view.byteLength;
        if (a.byteOffset > available || elementSize > available - a.byteOffset ||
            (a.count - 1) > (available - a.byteOffset - elementSize) / stride)
            fail(name + " reads past the end of " + viewName + " in " + bufferName);
    }
    return {data.data() + view.byteOffset + a.byteOffset, stride, a.count};
}

std::vector<Vec3> GltfLoader::readVec3(int index, const std::string& what) const {
    const tinygltf::Accessor& a = accessor(index, what);
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || a.type != TINYGLTF_TYPE_VEC3)
        fail(what + " accessor " + std::to_string(index) + " is not float VEC3");
    const AccessorBytes bytes = accessorBytes(index, 3 * sizeof(float));
    std::vector<Vec3> out(bytes.count);
    for (size_t i = 0; i < bytes.count; ++i) {
        float v[3];
        std::memcpy(v, bytes.first + i * bytes.stride, sizeof v);
        out[i] = {v[0], v[1], v[2]};
    }
    return out;
}

std::vector<uint32_t> GltfLoader::readIndices(int index, const std::string& what) const {
    const tinygltf::Accessor& a = accessor(index, what + " indices");
    size_t size = 0;
    switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: size = 4; break;
        default: break;
    }
    if (size == 0 || a.type != TINYGLTF_TYPE_SCALAR)
        fail(what + " indices accessor " + std::to_string(index) +
             " is not unsigned byte, short or int scalars");
    const AccessorBytes bytes = accessorBytes(index, size);
    std::vector<uint32_t> out(bytes.count);
    for (size_t i = 0; i < bytes.count; ++i) {
        const unsigned char* p = bytes.first + i * bytes.stride;
        if (size == 1) {
            out[i] = p[0];
        } else if (size == 2) {
            uint16_t v;
            std::memcpy(&v, p, 2);
            out[i] = v;
        } else {
            std::memcpy(&out[i], p, 4);
        }
    }
    return out;
}

// ---------------------------------------------------------------------------------------------
// Camera and lights

void GltfLoader::addCamera(int cameraIndex, const glm::dmat4& world, int nodeIndex) {
    const std::string node = "node " + std::to_string(nodeIndex);
    if (size_t(cameraIndex) >= model_.cameras.size())
        fail(node + " references camera " + std::to_string(cameraIndex) + ", which does not exist");
    const tinygltf::Camera& camera = model_.cameras[size_t(cameraIndex)];
    if (camera.type != "perspective") {
        warnOnce(camera.type + " cameras are ignored (only perspective cameras are supported)");
        return;
    }
    if (scene_.camera.present) return;  // the first perspective camera wins
    const double yfov = camera.perspective.yfov;
    if (!std::isfinite(yfov) || yfov <= 0 || yfov >= kPi)
        fail("camera " + std::to_string(cameraIndex) + " yfov " + formatNumber(yfov) + " is not in (0, pi)");
    const Vec3 forward = transformDirection(linearPart(world), Vec3(0, 0, -1));
    const Vec3 upHint = transformDirection(linearPart(world), Vec3(0, 1, 0));
    const Vec3 upOrtho = upHint - forward * dot(upHint, forward);
    if (isBlack(forward) || !(length(upOrtho) > 1e-6f))
        fail(node + " camera transform is degenerate");
    if (camera.perspective.aspectRatio > 0)
        warnOnce("camera aspectRatio is ignored (the image size sets the aspect ratio)");
    scene_.camera.present = true;
    scene_.camera.position = transformPoint(world, Vec3(0.0f));
    scene_.camera.forward = forward;
    scene_.camera.up = normalize(upOrtho);
    scene_.camera.yfov = float(yfov);
}

// glTF gives a point light's intensity in candela (lm/sr). This renderer has no photometric
// units, so the number is taken as radiant intensity in W/sr: I = color × intensity.
void GltfLoader::addLight(const tinygltf::Node& node, const glm::dmat4& world, int nodeIndex) {
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) return;
    const std::string nodeName = "node " + std::to_string(nodeIndex);
    if (!ext->second.IsObject() || !ext->second.Get("light").IsInt())
        fail(nodeName + " KHR_lights_punctual has no light index");
    const int index = ext->second.Get("light").GetNumberAsInt();
    if (index < 0 || size_t(index) >= model_.lights.size())
        fail(nodeName + " references light " + std::to_string(index) + ", which does not exist");
    const tinygltf::Light& light = model_.lights[size_t(index)];
    if (light.type != "point") {
        warnOnce(light.type + " lights are ignored (only point lights are supported)");
        return;
    }
    const std::string what = "light " + std::to_string(index);
    const Vec3 color = finiteVec3(light.color, Vec3(1.0f), what + " color");
    if (!std::isfinite(float(light.intensity))) fail(what + " intensity is not finite");
    if (light.intensity < 0 || color.x < 0 || color.y < 0 || color.z < 0)
        fail(what + " has negative color or intensity");
    if (light.range > 0) warnOnce("light range is ignored (point lights fall off as 1/r^2)");
    scene_.pointLights.push_back({transformPoint(world, Vec3(0.0f)), color * float(light.intensity)});
}

}  // namespace

SceneDesc loadGltf(const std::string& path, WarningSink warn, const GltfOptions& options) {
    return GltfLoader(path, std::move(warn), options).load();
}

}  // namespace tripath
