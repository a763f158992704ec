#include "io/gltf_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <optional>
#include <set>
#include <span>
#include <string_view>
#include <unordered_map>

#include "core/error.h"
#include "io/gltf_materials.h"
#include "io/gltf_model.h"

namespace tripath {

namespace {

// ---- numbers ----------------------------------------------------------------------------------

// The double nearest the shortest decimal that reads back as x (fmt's default for float): the
// file says 0.8, not 0.800000011920929, and the loader, reading it as a float, gets x back. JSON
// has no NaN or infinity, so a non-finite value is an error here rather than a broken file later.
double number(float x) {
    if (!std::isfinite(x)) throw InputError("cannot export a non-finite number to glTF");
    const std::string text = fmt::format("{}", x);
    double d = 0;
    std::from_chars(text.data(), text.data() + text.size(), d);
    return d;
}

std::vector<double> numbers(Vec3 v) { return {number(v.x), number(v.y), number(v.z)}; }

// KHR_materials_volume of absorption σ: attenuationColor exp(−σ) at attenuationDistance 1 (the
// loader's −ln(colour) gives σ back to float rounding).
void setVolume(tinygltf::ExtensionMap& extensions, Spectrum sigma) {
    tinygltf::Value::Array colour;
    for (double c : numbers(exp(sigma * -1.0f))) colour.emplace_back(c);
    extensions["KHR_materials_volume"] = tinygltf::Value(tinygltf::Value::Object{
        {"attenuationColor", tinygltf::Value(std::move(colour))}, {"attenuationDistance", tinygltf::Value(1.0)}});
}

// Smooth or rough glass: KHR_materials_transmission at factor 1, its ior written always.
bool isGlass(const Material& m) { return m.type == MaterialType::Dielectric || m.type == MaterialType::RoughDielectric; }

// A node matrix, column-major: the affine map's columns, then its translation.
std::vector<double> matrix(const Affine& a) {
    std::vector<double> m;
    for (const Vec3 column : {a.x, a.y, a.z, a.t}) {
        const std::vector<double> xyz = numbers(column);
        m.insert(m.end(), xyz.begin(), xyz.end());
        m.push_back(m.size() == 15 ? 1.0 : 0.0);
    }
    return m;
}

// Two groups place their meshes alike.
bool samePlacement(const InstancesDesc& a, const InstancesDesc& b) {
    return a.toWorld == b.toWorld && a.trs == b.trs && a.parent == b.parent;
}

bool samePlacements(const std::vector<const InstancesDesc*>& a, const std::vector<const InstancesDesc*>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                      [](const InstancesDesc* x, const InstancesDesc* y) { return samePlacement(*x, *y); });
}

// ---- splitting a radiance or intensity into a factor in [0, 1] and a scale --------------------

struct Scaled {
    Vec3 factor;
    float scale = 1;
};

// tinygltf leaves out an emissiveFactor within 1e-12 of black, so a faint one is scaled up too.
constexpr float kFaint = 1e-6f;

// scale = the smallest power of two ≥ the largest component (1 when that is in [kFaint, 1]):
// dividing by a power of two only changes the exponent, so factor × scale is exactly v again.
Scaled splitScale(Vec3 v) {
    const float m = maxComponent(v);
    if (!(m > 1.0f) && !(m > 0.0f && m < kFaint)) return {v, 1.0f};
    const float scale = std::exp2(std::ceil(std::log2(m)));
    return {v / scale, scale};
}

// ---- the document -----------------------------------------------------------------------------

// glTF cameras have no "infinitely far": tinygltf always writes zfar (0 when unset, which glTF
// forbids), so the camera gets a far plane beyond any scene. The loader ignores it.
constexpr float kFar = 1e30f;

class ModelBuilder {
public:
    ModelBuilder(const SceneDesc& scene, const WarningSink& warn) : scene_(scene), warn_(warn) {}
    tinygltf::Model build();

private:
    void warn(const std::string& what) {
        if (warn_) warn_(scene_.name + ": " + what);
    }
    int addArray(const void* data, size_t bytes, int componentType, size_t count, int type);
    int addIndices(const std::vector<uint32_t>& indices);
    tinygltf::Material material(const Material& m);
    void addMeshes();
    std::optional<tinygltf::Primitive> primitive(const MeshDesc& m);
    int addMesh(std::span<const MeshDesc> meshes);
    void addPlacement(int mesh, const InstancesDesc& group);
    int addNode(tinygltf::Node node);
    void addCamera();
    void addLights();

    const SceneDesc& scene_;
    const WarningSink& warn_;
    tinygltf::Model model_;
    std::set<std::string> extensions_;
    std::unordered_multimap<size_t, int> written_;  // accessors by the hash of their bytes
};

// An array with the type, count and bytes of one already written is that accessor again, so
// what the scene repeats (the vertices of meshes kept apart for their materials, say) is written
// once.
int ModelBuilder::addArray(const void* data, size_t bytes, int componentType, size_t count, int type) {
    const std::string_view content(static_cast<const char*>(data), bytes);
    const size_t hash = std::hash<std::string_view>{}(content);
    const auto [first, last] = written_.equal_range(hash);
    for (auto it = first; it != last; ++it) {
        const tinygltf::Accessor& a = model_.accessors[size_t(it->second)];
        const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
        const auto* stored = reinterpret_cast<const char*>(model_.buffers[0].data.data()) + view.byteOffset;
        if (a.componentType == componentType && a.type == type && a.count == count &&
            std::string_view(stored, view.byteLength) == content)
            return it->second;
    }
    const int accessor = appendAccessor(model_, appendBufferView(model_, data, bytes), componentType, count, type);
    written_.emplace(hash, accessor);
    return accessor;
}

// Unsigned shorts when every index is below 65535 (glTF reserves each type's largest value), as
// exporters commonly write them; unsigned ints otherwise.
int ModelBuilder::addIndices(const std::vector<uint32_t>& indices) {
    if (*std::max_element(indices.begin(), indices.end()) < 65535) {
        const std::vector<uint16_t> shorts(indices.begin(), indices.end());
        return addArray(shorts.data(), shorts.size() * sizeof(uint16_t), TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                        shorts.size(), TINYGLTF_TYPE_SCALAR);
    }
    return addArray(indices.data(), indices.size() * sizeof(uint32_t), TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                    indices.size(), TINYGLTF_TYPE_SCALAR);
}

tinygltf::Material ModelBuilder::material(const Material& m) {
    float metallic = 0, roughness = 1;
    tinygltf::Material g;
    switch (m.type) {
        case MaterialType::Lambertian: break;
        case MaterialType::Plastic:
            roughness = m.roughness;
            if (roughness >= 0.99f)
                warn(fmt::format("material '{}': a plastic of roughness {} loads back as Lambertian", m.name, roughness));
            break;
        case MaterialType::Mirror:
            metallic = 1, roughness = 0;
            g.extras = gltf::mirrorMarker();
            break;
        case MaterialType::SmoothConductor: metallic = 1, roughness = 0; break;
        case MaterialType::Conductor:
            metallic = 1, roughness = m.roughness;
            if (roughness == 0)
                warn(fmt::format("material '{}': a metal of roughness 0 loads back as a smooth conductor", m.name));
            break;
        case MaterialType::Dielectric:
        case MaterialType::RoughDielectric: roughness = m.type == MaterialType::Dielectric ? 0 : m.roughness; break;
        case MaterialType::MetallicRoughness: metallic = m.metallic, roughness = m.roughness; break;
    }
    if (transmits(m) || isGlass(m)) {
        const float transmission = m.type == MaterialType::MetallicRoughness ? m.transmission : 1.0f;
        setExtension(g.extensions, "KHR_materials_transmission", "transmissionFactor", tinygltf::Value(number(transmission)));
        if (!isBlack(m.absorption)) setVolume(g.extensions, m.absorption);
    }
    const bool usesIor = isGlass(m) || m.type == MaterialType::Plastic || m.type == MaterialType::MetallicRoughness;
    if (usesIor && (isGlass(m) || m.ior != 1.5f))
        setExtension(g.extensions, "KHR_materials_ior", "ior", tinygltf::Value(number(m.ior)));
    const Scaled e = splitScale(m.emission);
    if (e.scale != 1.0f)
        setExtension(g.extensions, "KHR_materials_emissive_strength", "emissiveStrength",
                     tinygltf::Value(number(e.scale)));
    for (const auto& [name, value] : g.extensions) extensions_.insert(name);
    g.name = m.name;
    g.pbrMetallicRoughness.baseColorFactor = numbers(m.albedo);
    g.pbrMetallicRoughness.baseColorFactor.push_back(1.0);
    g.pbrMetallicRoughness.metallicFactor = number(metallic);
    g.pbrMetallicRoughness.roughnessFactor = number(roughness);
    g.emissiveFactor = numbers(e.factor);
    g.doubleSided = m.twoSidedEmission;
    if (m.textures) warn(fmt::format("material '{}': its textures are left out (its factors are written)", m.name));
    return g;
}

// The buffer holds the scene's arrays as they lie in memory: glTF wants packed little-endian floats.
static_assert(sizeof(Vec3) == 3 * sizeof(float), "Vec3 must be three packed floats");
static_assert(sizeof(MeshDesc::colours[0]) == 4 * sizeof(float), "a vertex colour must be four packed floats");
static_assert(std::endian::native == std::endian::little, "glTF buffers are little-endian");

std::optional<tinygltf::Primitive> ModelBuilder::primitive(const MeshDesc& m) {
    // glTF forbids empty accessors; a mesh without triangles has nothing to say anyway.
    if (m.indices.empty() || m.positions.empty()) {
        warn(fmt::format("mesh '{}' has no triangles and is left out", m.name));
        return std::nullopt;
    }
    Vec3 lo(3e38f), hi(-3e38f);
    for (const Vec3& p : m.positions) {
        if (!isFinite(p)) throw InputError(fmt::format("{}: mesh '{}' has a non-finite position", scene_.name, m.name));
        lo = min(lo, p);
        hi = max(hi, p);
    }
    tinygltf::Primitive primitive;
    const int position = addArray(m.positions.data(), m.positions.size() * sizeof(Vec3),
                                  TINYGLTF_COMPONENT_TYPE_FLOAT, m.positions.size(), TINYGLTF_TYPE_VEC3);
    model_.accessors[size_t(position)].minValues = numbers(lo);
    model_.accessors[size_t(position)].maxValues = numbers(hi);
    primitive.attributes["POSITION"] = position;
    if (!m.normals.empty())
        primitive.attributes["NORMAL"] = addArray(m.normals.data(), m.normals.size() * sizeof(Vec3),
                                                  TINYGLTF_COMPONENT_TYPE_FLOAT, m.normals.size(), TINYGLTF_TYPE_VEC3);
    if (!m.colours.empty())
        primitive.attributes["COLOR_0"] = addArray(m.colours.data(), m.colours.size() * sizeof(m.colours[0]),
                                                   TINYGLTF_COMPONENT_TYPE_FLOAT, m.colours.size(), TINYGLTF_TYPE_VEC4);
    primitive.indices = addIndices(m.indices);
    primitive.material = m.material;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    return primitive;
}

// One glTF mesh with a primitive per MeshDesc, named after the first; -1 when none has triangles.
int ModelBuilder::addMesh(std::span<const MeshDesc> meshes) {
    tinygltf::Mesh mesh;
    mesh.name = meshes.front().name;
    for (const MeshDesc& m : meshes)
        if (auto p = primitive(m)) mesh.primitives.push_back(std::move(*p));
    if (mesh.primitives.empty()) return -1;
    model_.meshes.push_back(mesh);
    return static_cast<int>(model_.meshes.size()) - 1;
}

// A mesh used once gets a node with no transform. Consecutive meshes placed alike (the
// primitives of one instanced glTF mesh) become one glTF mesh, written once, with a node per
// placement: a matrix each, or one node with EXT_mesh_gpu_instancing where the group came so.
void ModelBuilder::addMeshes() {
    std::vector<std::vector<const InstancesDesc*>> placements(scene_.meshes.size());
    for (const InstancesDesc& group : scene_.instances) {
        if (group.mesh < 0 || size_t(group.mesh) >= placements.size())
            throw InputError(fmt::format("{}: instances name mesh {}, which does not exist", scene_.name, group.mesh));
        placements[size_t(group.mesh)].push_back(&group);
    }
    const std::span<const MeshDesc> meshes(scene_.meshes);
    for (size_t i = 0; i < meshes.size();) {
        size_t end = i + 1;
        while (!placements[i].empty() && end < meshes.size() && samePlacements(placements[end], placements[i])) ++end;
        const int mesh = addMesh(meshes.subspan(i, end - i));
        if (mesh >= 0) {
            if (placements[i].empty()) {
                tinygltf::Node node;
                node.name = meshes[i].name;
                node.mesh = mesh;
                addNode(node);
            }
            for (const InstancesDesc* group : placements[i]) addPlacement(mesh, *group);
        }
        i = end;
    }
}

void ModelBuilder::addPlacement(int mesh, const InstancesDesc& group) {
    tinygltf::Node node;
    node.name = model_.meshes[size_t(mesh)].name;
    node.mesh = mesh;
    if (group.trs.empty()) {
        for (const Affine& a : group.toWorld) {
            node.matrix = matrix(a);
            addNode(node);
        }
        return;
    }
    std::vector<float> t, r, s;
    for (const TrsDesc& d : group.trs) {
        t.insert(t.end(), {d.translation.x, d.translation.y, d.translation.z});
        r.insert(r.end(), d.rotation, d.rotation + 4);
        s.insert(s.end(), {d.scale.x, d.scale.y, d.scale.z});
    }
    const size_t n = group.trs.size();
    const auto array = [&](const std::vector<float>& v, int type) {
        return tinygltf::Value(addArray(v.data(), v.size() * sizeof(float), TINYGLTF_COMPONENT_TYPE_FLOAT, n, type));
    };
    node.matrix = matrix(group.parent);
    tinygltf::Value::Object attributes{{"TRANSLATION", array(t, TINYGLTF_TYPE_VEC3)},
                                       {"ROTATION", array(r, TINYGLTF_TYPE_VEC4)},
                                       {"SCALE", array(s, TINYGLTF_TYPE_VEC3)}};
    setExtension(node.extensions, "EXT_mesh_gpu_instancing", "attributes", tinygltf::Value(std::move(attributes)));
    extensions_.insert("EXT_mesh_gpu_instancing");
    addNode(node);
}

// Every node is a root of the one scene.
int ModelBuilder::addNode(tinygltf::Node node) {
    model_.nodes.push_back(std::move(node));
    const int index = static_cast<int>(model_.nodes.size()) - 1;
    model_.scenes[0].nodes.push_back(index);
    return index;
}

// The frame of a node looking down `forward` (its −z) from `position`, +y as near `up` as forward
// allows: its columns are the right, up and −forward directions, and the position.
Affine lookingAlong(Vec3 position, Vec3 forward, Vec3 up) {
    const Vec3 f = normalize(forward);
    Vec3 r = cross(f, up);
    if (!(lengthSquared(r) > 1e-12f)) r = cross(f, Vec3(1, 0, 0));
    r = normalize(r);
    return Affine{r, cross(r, f), -f, position};
}

void ModelBuilder::addCamera() {
    const CameraDesc& c = scene_.camera;
    if (!c.present) return;
    tinygltf::Camera camera;
    camera.type = "perspective";
    camera.perspective.yfov = number(c.yfov);
    camera.perspective.znear = number(0.001f);
    camera.perspective.zfar = number(kFar);
    model_.cameras.push_back(camera);
    tinygltf::Node node;
    node.name = "camera";
    node.camera = 0;
    node.matrix = matrix(lookingAlong(c.position, c.forward, c.up));
    addNode(node);
}

void ModelBuilder::addLights() {
    for (const LightDesc& l : scene_.lights) {
        const Scaled i = splitScale(l.intensity);
        const int index = static_cast<int>(model_.lights.size());
        tinygltf::Light light;
        light.type = l.kind == LightDesc::Kind::Point ? "point" : l.kind == LightDesc::Kind::Spot ? "spot" : "directional";
        light.color = numbers(isBlack(i.factor) ? Vec3(1.0f) : i.factor);
        light.intensity = number(isBlack(i.factor) ? 0.0f : i.scale);
        if (l.kind == LightDesc::Kind::Spot) {
            light.spot.innerConeAngle = number(l.innerConeAngle);
            light.spot.outerConeAngle = number(l.outerConeAngle);
        }
        model_.lights.push_back(light);
        tinygltf::Node node;
        node.name = fmt::format("{} light {}", light.type, index);
        node.matrix = matrix(lookingAlong(l.position, l.direction, Vec3(0, 1, 0)));
        setExtension(node.extensions, "KHR_lights_punctual", "light", tinygltf::Value(index));
        addNode(node);
    }
    if (!model_.lights.empty()) extensions_.insert("KHR_lights_punctual");
}

tinygltf::Model ModelBuilder::build() {
    model_.asset.generator = "tripath export";
    model_.scenes.emplace_back();
    model_.scenes[0].name = scene_.name;
    model_.defaultScene = 0;
    for (const Material& m : scene_.materials) model_.materials.push_back(material(m));
    addMeshes();
    addCamera();
    addLights();
    if (scene_.environment.present())
        warn("its environment is left out (glTF has none): render the file with --environment to light it");
    model_.extensionsUsed.assign(extensions_.begin(), extensions_.end());
    return std::move(model_);
}

}  // namespace

void writeGltf(const SceneDesc& scene, const std::string& path, const WarningSink& warn, GltfBuffer buffer) {
    writeGltfModel(ModelBuilder(scene, warn).build(), path, buffer);
}

}  // namespace tripath
