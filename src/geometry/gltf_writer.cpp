#include "geometry/gltf_writer.h"

#include <fmt/format.h>
#include <unistd.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "geometry/error.h"

namespace tripath {

namespace {

// ---- JSON text --------------------------------------------------------------------------------

std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (const char ch : s) {
        const auto c = static_cast<unsigned char>(ch);
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\t': out += "\\t"; break;
            case '\r': out += "\\r"; break;
            default:
                if (c < 0x20) out += fmt::format("\\u{:04x}", c);
                else out += ch;  // UTF-8 passes through: JSON text is UTF-8
        }
    }
    return out + "\"";
}

// The shortest decimal that reads back as the same float (fmt's default for float). JSON has no
// NaN or infinity, so a non-finite value is an error here rather than a broken file later.
std::string num(float x) {
    if (!std::isfinite(x)) throw InputError("cannot export a non-finite number to glTF");
    return fmt::format("{}", x);
}

std::string vec3(Vec3 v) { return fmt::format("[{},{},{}]", num(v.x), num(v.y), num(v.z)); }

std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& item : items) out += (out.empty() ? "" : ",") + item;
    return out;
}


// ---- splitting a radiance or intensity into a factor in [0, 1] and a scale --------------------

struct Scaled {
    Vec3 factor;
    float scale = 1;
};

// scale = the smallest power of two ≥ the largest component (1 when it is ≤ 1): dividing by a
// power of two only changes the exponent, so factor × scale is exactly v again after loading.
Scaled splitScale(Vec3 v) {
    const float m = maxComponent(v);
    if (!(m > 1.0f)) return {v, 1.0f};
    const float scale = std::exp2(std::ceil(std::log2(m)));
    return {v / scale, scale};
}

// ---- the document -----------------------------------------------------------------------------

class Writer {
public:
    Writer(const SceneDesc& scene, const WarningSink& warn) : scene_(scene), warn_(warn) {}
    std::string json();

private:
    void warn(const std::string& what) {
        if (warn_) warn_(scene_.name + ": " + what);
    }
    int addView(const void* data, size_t bytes);
    int addAccessor(int view, int componentType, size_t count, const std::string& type, const std::string& extra = "");
    std::string material(const Material& m);
    void addMesh(const MeshDesc& m);
    void addCamera();
    void addLights();

    const SceneDesc& scene_;
    const WarningSink& warn_;
    std::vector<unsigned char> bin_;
    std::vector<std::string> views_, accessors_, meshes_, nodes_, lights_;
    std::string camera_;
    std::set<std::string> extensions_;
};

int Writer::addView(const void* data, size_t bytes) {
    const size_t offset = bin_.size();
    const auto* p = static_cast<const unsigned char*>(data);
    bin_.insert(bin_.end(), p, p + bytes);  // every element is 4 bytes: offsets stay aligned
    views_.push_back(fmt::format(R"({{"buffer":0,"byteOffset":{},"byteLength":{}}})", offset, bytes));
    return static_cast<int>(views_.size()) - 1;
}

int Writer::addAccessor(int view, int componentType, size_t count, const std::string& type, const std::string& extra) {
    accessors_.push_back(fmt::format(R"({{"bufferView":{},"componentType":{},"count":{},"type":"{}"{}}})", view,
                                     componentType, count, type, extra));
    return static_cast<int>(accessors_.size()) - 1;
}

std::string Writer::material(const Material& m) {
    float metallic = 0, roughness = 1;
    std::vector<std::string> ext;
    switch (m.type) {
        case MaterialType::Lambertian: break;
        case MaterialType::Plastic:
            roughness = m.roughness;
            if (roughness >= 0.99f)
                warn(fmt::format("material '{}': a plastic of roughness {} loads back as Lambertian", m.name, roughness));
            break;
        case MaterialType::Mirror: metallic = 1, roughness = 0; break;
        case MaterialType::Conductor:
            metallic = 1, roughness = m.roughness;
            if (roughness < 0.01f)
                warn(fmt::format("material '{}': a metal of roughness {} loads back as a mirror", m.name, roughness));
            break;
        case MaterialType::Dielectric:
            roughness = 0;
            ext.push_back(R"("KHR_materials_transmission":{"transmissionFactor":1})");
            extensions_.insert("KHR_materials_transmission");
            break;
    }
    const bool usesIor = m.type == MaterialType::Dielectric || m.type == MaterialType::Plastic;
    if (usesIor && (m.type == MaterialType::Dielectric || m.ior != 1.5f)) {
        ext.push_back(R"("KHR_materials_ior":{"ior":)" + num(m.ior) + "}");
        extensions_.insert("KHR_materials_ior");
    }
    const Scaled e = splitScale(m.emission);
    if (e.scale != 1.0f) {
        ext.push_back(R"("KHR_materials_emissive_strength":{"emissiveStrength":)" + num(e.scale) + "}");
        extensions_.insert("KHR_materials_emissive_strength");
    }
    std::string out = "{\"name\":" + quoted(m.name) + ",\"pbrMetallicRoughness\":{\"baseColorFactor\":[" +
                      num(m.albedo.x) + "," + num(m.albedo.y) + "," + num(m.albedo.z) + ",1],\"metallicFactor\":" +
                      num(metallic) + ",\"roughnessFactor\":" + num(roughness) + "}";
    if (!isBlack(m.emission)) out += ",\"emissiveFactor\":" + vec3(e.factor);
    if (m.twoSidedEmission) out += ",\"doubleSided\":true";
    if (!ext.empty()) out += ",\"extensions\":{" + join(ext) + "}";
    return out + "}";
}

// The buffer holds the scene's arrays as they lie in memory: glTF wants packed little-endian floats.
static_assert(sizeof(Vec3) == 3 * sizeof(float), "Vec3 must be three packed floats");
static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");

void Writer::addMesh(const MeshDesc& m) {
    // glTF forbids empty accessors; a mesh without triangles has nothing to say anyway.
    if (m.indices.empty() || m.positions.empty()) {
        warn(fmt::format("mesh '{}' has no triangles and is left out", m.name));
        return;
    }
    Vec3 lo(3e38f), hi(-3e38f);
    for (const Vec3& p : m.positions) {
        if (!isFinite(p)) throw InputError(fmt::format("{}: mesh '{}' has a non-finite position", scene_.name, m.name));
        lo = min(lo, p);
        hi = max(hi, p);
    }
    constexpr int kFloat = 5126, kUnsignedInt = 5125;
    const int position = addAccessor(addView(m.positions.data(), m.positions.size() * sizeof(Vec3)), kFloat,
                                     m.positions.size(), "VEC3", ",\"min\":" + vec3(lo) + ",\"max\":" + vec3(hi));
    std::string attributes = "\"POSITION\":" + std::to_string(position);
    if (!m.normals.empty()) {
        const int normal = addAccessor(addView(m.normals.data(), m.normals.size() * sizeof(Vec3)), kFloat,
                                       m.normals.size(), "VEC3");
        attributes += ",\"NORMAL\":" + std::to_string(normal);
    }
    const int indices = addAccessor(addView(m.indices.data(), m.indices.size() * sizeof(uint32_t)), kUnsignedInt,
                                    m.indices.size(), "SCALAR");
    meshes_.push_back(fmt::format(R"({{"name":{},"primitives":[{{"attributes":{{{}}},"indices":{},"material":{},"mode":4}}]}})",
                                  quoted(m.name), attributes, indices, m.material));
    nodes_.push_back(fmt::format(R"({{"name":{},"mesh":{}}})", quoted(m.name), meshes_.size() - 1));
}

// glTF cameras look down their node's −z with +y up: the node matrix's columns are the scene's
// right, up and −forward, and the position.
void Writer::addCamera() {
    const CameraDesc& c = scene_.camera;
    if (!c.present) return;
    const Vec3 f = normalize(c.forward), r = normalize(cross(f, c.up)), u = cross(r, f);
    const std::vector<std::string> matrix = {num(r.x),  num(r.y),  num(r.z),  "0", num(u.x),          num(u.y),
                                             num(u.z),  "0",       num(-f.x), num(-f.y), num(-f.z), "0",
                                             num(c.position.x), num(c.position.y), num(c.position.z), "1"};
    camera_ = R"({"type":"perspective","perspective":{"yfov":)" + num(c.yfov) + R"(,"znear":0.001}})";
    nodes_.push_back(R"({"name":"camera","camera":0,"matrix":[)" + join(matrix) + "]}");
}

void Writer::addLights() {
    for (const PointLightDesc& l : scene_.pointLights) {
        const Scaled i = splitScale(l.intensity);
        const int index = static_cast<int>(lights_.size());
        lights_.push_back(R"({"type":"point","color":)" + vec3(isBlack(i.factor) ? Vec3(1.0f) : i.factor) +
                          ",\"intensity\":" + num(isBlack(i.factor) ? 0.0f : i.scale) + "}");
        nodes_.push_back(fmt::format(R"({{"name":"point light {}","translation":{},"extensions":{{"KHR_lights_punctual":{{"light":{}}}}}}})",
                                     index, vec3(l.position), index));
    }
    if (!lights_.empty()) extensions_.insert("KHR_lights_punctual");
}

std::string Writer::json() {
    std::vector<std::string> materials;
    for (const Material& m : scene_.materials) materials.push_back(material(m));
    for (const MeshDesc& m : scene_.meshes) addMesh(m);
    addCamera();
    addLights();

    std::vector<std::string> roots, used;
    for (size_t i = 0; i < nodes_.size(); ++i) roots.push_back(std::to_string(i));
    for (const std::string& e : extensions_) used.push_back(quoted(e));

    std::vector<std::string> members = {R"("asset":{"version":"2.0","generator":"tripath export"})"};
    if (!used.empty()) members.push_back("\"extensionsUsed\":[" + join(used) + "]");
    members.push_back("\"scene\":0");
    members.push_back("\"scenes\":[{\"name\":" + quoted(scene_.name) + ",\"nodes\":[" + join(roots) + "]}]");
    if (!nodes_.empty()) members.push_back("\"nodes\":[\n" + join(nodes_) + "\n]");
    if (!meshes_.empty()) members.push_back("\"meshes\":[\n" + join(meshes_) + "\n]");
    if (!materials.empty()) members.push_back("\"materials\":[\n" + join(materials) + "\n]");
    if (!camera_.empty()) members.push_back("\"cameras\":[" + camera_ + "]");
    if (!lights_.empty()) members.push_back("\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[" + join(lights_) + "]}}");
    if (!bin_.empty()) {
        members.push_back("\"accessors\":[\n" + join(accessors_) + "\n]");
        members.push_back("\"bufferViews\":[\n" + join(views_) + "\n]");
        members.push_back(fmt::format(R"("buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}])",
                                      bin_.size(), base64(bin_)));
    }
    std::string out = "{\n";
    for (size_t i = 0; i < members.size(); ++i) out += members[i] + (i + 1 < members.size() ? ",\n" : "\n");
    return out + "}\n";
}

}  // namespace

std::string base64(const std::vector<unsigned char>& data) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((data.size() + 2) / 3 * 4);
    for (size_t i = 0; i < data.size(); i += 3) {
        const uint32_t b0 = data[i];
        const uint32_t b1 = i + 1 < data.size() ? data[i + 1] : 0;
        const uint32_t b2 = i + 2 < data.size() ? data[i + 2] : 0;
        const uint32_t triple = (b0 << 16) | (b1 << 8) | b2;
        out += table[(triple >> 18) & 63];
        out += table[(triple >> 12) & 63];
        out += i + 1 < data.size() ? table[(triple >> 6) & 63] : '=';
        out += i + 2 < data.size() ? table[triple & 63] : '=';
    }
    return out;
}

std::string gltfJson(const SceneDesc& scene, const WarningSink& warn) { return Writer(scene, warn).json(); }

void writeGltf(const SceneDesc& scene, const std::string& path, const WarningSink& warn) {
    const std::string text = gltfJson(scene, warn);
    namespace fs = std::filesystem;
    const fs::path target(path);
    const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
    const fs::path temp = dir / fmt::format(".{}.tmp{}", target.filename().string(), static_cast<long>(getpid()));
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) throw InputError(path + ": cannot write (missing or read-only folder?)");
        out.write(text.data(), static_cast<std::streamsize>(text.size()));
        out.close();
        if (!out) {
            std::error_code ec;
            fs::remove(temp, ec);
            throw InputError(path + ": write failed (disk full?)");
        }
    }
    std::error_code ec;
    fs::rename(temp, target, ec);
    if (ec) {
        fs::remove(temp, ec);
        throw InputError(path + ": cannot replace the file: " + ec.message());
    }
}

}  // namespace tripath
