// glTF 2.0 → SceneDesc (see docs/gltf.md for the user-facing feature table): the entry point, the
// walk over the default scene's node hierarchy and what its nodes carry (meshes, the camera,
// point lights). The pieces it builds on have files of their own, one concept each: the scene
// file and the buffer files it names (gltf_file.cpp), accessors (gltf_accessors.cpp), node
// transforms (gltf_transforms.cpp), the material mapping (its table heads gltf_materials.cpp), the
// textures (gltf_textures.cpp) and the checks and messages they share (gltf_checks.h).
//
// Geometry: TRIANGLES primitives (other modes are skipped with a warning), POSITION and NORMAL as
// float VEC3, unsigned byte/short/int indices or none. Nodes of the default scene (else scene 0,
// else every root node) are composed parent × child; positions take the full matrix, normals its
// inverse transpose. Mirroring transforms (negative determinant) reverse the winding so the front
// face stays where the file put it. Triangles that are degenerate in world space are dropped.
// Instancing: a mesh placed more than once (by several nodes, or by a node's
// EXT_mesh_gpu_instancing, gltf_instancing.h), or whose POSITION accessor another placed mesh
// reads too, is kept once in its own space, its triangles degenerate there dropped, with a
// transform per copy (SceneDesc::instances).
// Primitives whose material has textures also keep TEXCOORD_0, TEXCOORD_1 and TANGENT (its xyz by
// the full matrix's linear part, its sign flipped by a mirroring one); the textures themselves are
// read with the materials (gltf_textures.cpp). Every primitive keeps its COLOR_0 (linear RGBA,
// float or normalized unsigned byte or short, in [0, 1]), which multiplies the base colour and
// its alpha (glTF 2.0 §3.9.2); COLOR_1… mean nothing to glTF's material and are not read.
// Lights: KHR_lights_punctual point, spot and directional lights; camera: the first perspective camera in depth-first order.
#include "io/gltf_loader.h"

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "io/gltf_accessors.h"
#include "io/gltf_checks.h"
#include "io/gltf_file.h"
#include "io/gltf_instancing.h"
#include "io/gltf_materials.h"
#include "io/gltf_textures.h"
#include "io/gltf_transforms.h"

namespace tripath::gltf {

namespace {

// A triangle is dropped when sin(angle between two edges) falls below this (zero-area slivers).
constexpr double kDegenerateSine = 1e-6;

// Extensions that only refine appearance: accepted even when required, with a warning.
const std::set<std::string> kIgnorableExtensions = {
    "KHR_materials_specular",   "KHR_materials_clearcoat", "KHR_materials_sheen",
    "KHR_materials_iridescence", "KHR_materials_anisotropy",
    "KHR_materials_dispersion", "KHR_materials_variants",
    "KHR_texture_basisu",       "EXT_texture_webp",        "EXT_texture_avif"};

// True when the float arithmetic the renderer does on a triangle stays finite: its edges, their
// squared lengths, their cross product (the normal, twice the area) and its squared length. A
// vertex at 1e30 passes for finite, but its triangles' areas are not.
bool hasFiniteProducts(Vec3 a, Vec3 b, Vec3 c) {
    const Vec3 e1 = b - a, e2 = c - a, n = cross(e1, e2);
    return isFinite(e1) && isFinite(e2) && isFinite(n) && std::isfinite(lengthSquared(e1)) &&
           std::isfinite(lengthSquared(e2)) && std::isfinite(lengthSquared(n));
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

// The POSITION accessors a mesh's primitives read.
std::set<int> positionAccessors(const tinygltf::Mesh& mesh) {
    std::set<int> out;
    for (const tinygltf::Primitive& prim : mesh.primitives)
        if (const auto it = prim.attributes.find("POSITION"); it != prim.attributes.end()) out.insert(it->second);
    return out;
}

class Loader {
public:
    Loader(std::string path, WarningSink warn, const GltfOptions& options)
        : report_(std::move(path), std::move(warn)), allowExternalFiles_(options.allowExternalFiles) {}
    SceneDesc load();

private:
    // Where a node places a mesh: at its world transform, or at each EXT_mesh_gpu_instancing instance.
    struct Placement {
        int mesh;
        int node;
        glm::dmat4 world;
        std::optional<std::vector<TrsDesc>> instances;
    };

    void checkExtensions();
    void warnIgnoredModelFeatures();
    int materialIndex(int gltfMaterial, const std::string& what);

    std::vector<int> rootNodes() const;
    void traverseScene();
    glm::dmat4 visitNode(int index, const glm::dmat4& parent);

    void addMeshes();
    void addInstances(const Placement& placement, std::pair<size_t, size_t> meshes);
    void addMesh(int meshIndex, const glm::dmat4& world, int nodeIndex);
    void addPrimitive(const tinygltf::Primitive& prim, const std::string& name, const glm::dmat4& world);
    std::vector<Vec3> worldNormals(const tinygltf::Primitive& prim, size_t vertexCount,
                                   const glm::dmat4& world, const std::string& what);
    MeshDesc textureAttributes(const tinygltf::Primitive& prim, size_t vertexCount, const glm::dmat4& world,
                               const std::string& what);
    std::vector<std::array<float, 4>> vertexColours(const tinygltf::Primitive& prim, size_t vertexCount,
                                                    const std::string& what);
    MeshDesc keepGoodTriangles(const std::vector<Vec3>& positions, const std::vector<Vec3>& normals,
                               const MeshDesc& attributes, const std::vector<uint32_t>& indices, bool flipWinding,
                               const std::string& what);

    void addCamera(int cameraIndex, const glm::dmat4& world, int nodeIndex);
    void addLight(const tinygltf::Node& node, const glm::dmat4& world, int nodeIndex);

    Report report_;
    bool allowExternalFiles_;
    std::vector<Placement> placements_;  // in depth-first order
    tinygltf::Model model_;
    Accessors accessors_{model_, report_};
    SceneDesc scene_;
    int defaultMaterial_ = -1;
    size_t droppedTriangles_ = 0;
};

SceneDesc Loader::load() {
    scene_.name = report_.path();
    model_ = readModel(allowExternalFiles_, report_, scene_.sources);
    checkExtensions();
    warnIgnoredModelFeatures();
    TextureReader textures(model_, sceneFolder(report_), allowExternalFiles_, report_, scene_.sources);
    scene_.materials = convertMaterials(model_, textures, report_);
    traverseScene();
    addMeshes();
    if (droppedTriangles_ > 0)
        report_.warnOnce("dropped " + std::to_string(droppedTriangles_) + " degenerate (zero-area) triangles");
    if (scene_.meshes.empty()) report_.fail("the scene contains no triangles");
    return std::move(scene_);
}

// ---------------------------------------------------------------------------------------------
// Extensions and materials

void Loader::checkExtensions() {
    for (const std::string& name : model_.extensionsRequired) {
        if (!isHandledExtension(name) && !kIgnorableExtensions.count(name))
            report_.fail("required extension " + excerpt(name) + " is not supported");
    }
    for (const auto* list : {&model_.extensionsRequired, &model_.extensionsUsed})
        for (const std::string& name : *list)
            if (!isHandledExtension(name)) report_.warnOnce("extension " + excerpt(name) + " is ignored");
}

void Loader::warnIgnoredModelFeatures() {
    if (!model_.animations.empty()) report_.warnOnce("animations are ignored (the static pose is used)");
    if (!model_.skins.empty()) report_.warnOnce("skins are ignored (meshes use their node transforms)");
}

int Loader::materialIndex(int gltfMaterial, const std::string& what) {
    if (gltfMaterial >= 0) {
        if (size_t(gltfMaterial) >= model_.materials.size())
            report_.fail(what + " references material " + std::to_string(gltfMaterial) + ", which does not exist");
        return gltfMaterial;
    }
    if (defaultMaterial_ < 0) {
        defaultMaterial_ = int(scene_.materials.size());
        scene_.materials.push_back(defaultMaterial());
    }
    return defaultMaterial_;
}

// ---------------------------------------------------------------------------------------------
// Node hierarchy

std::vector<int> Loader::rootNodes() const {
    if (model_.defaultScene >= 0) {
        if (size_t(model_.defaultScene) >= model_.scenes.size())
            report_.fail("default scene " + std::to_string(model_.defaultScene) + " does not exist");
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
void Loader::traverseScene() {
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
                report_.fail("node " + std::to_string(child) + " is its own ancestor (cycle in the node hierarchy)");
            onPath[size_t(child)] = 1;
            stack.push_back({child, world, 0});
        }
    }
}

// Adds what the node carries and returns its world transform.
glm::dmat4 Loader::visitNode(int index, const glm::dmat4& parent) {
    if (index < 0 || size_t(index) >= model_.nodes.size())
        report_.fail("node " + std::to_string(index) + " does not exist");
    const tinygltf::Node& node = model_.nodes[size_t(index)];
    const glm::dmat4 world = compose(parent, localTransform(node, index, report_));
    if (!allFinite(world)) report_.fail("node " + std::to_string(index) + " has a non-finite world transform");
    if (node.mesh >= 0) placements_.push_back({node.mesh, index, world, readInstances(node, index, accessors_, report_)});
    if (node.camera >= 0) addCamera(node.camera, world, index);
    addLight(node, world, index);
    return world;
}

// ---------------------------------------------------------------------------------------------
// Meshes

// In the order the nodes placed them: a mesh that is one copy of its vertices as world-space
// triangles; one placed more often, or whose POSITION accessor another placed mesh reads too (a
// sphere under a material per mesh, say), in its own space (where it is first placed) with its
// copies' transforms, so that what the file shares stays recognisable (an export writes it once).
void Loader::addMeshes() {
    std::vector<size_t> copies(model_.meshes.size(), 0);
    for (const Placement& p : placements_)
        if (size_t(p.mesh) < copies.size()) copies[size_t(p.mesh)] += p.instances ? p.instances->size() : 1;
    std::map<int, size_t> vertexCopies;  // per POSITION accessor, the copies of the meshes that read it
    for (size_t m = 0; m < copies.size(); ++m)
        for (int accessor : positionAccessors(model_.meshes[m])) vertexCopies[accessor] += copies[m];
    auto placedOnce = [&](const Placement& p) {
        if (size_t(p.mesh) >= copies.size()) return true;  // addMesh reports it
        const std::set<int> positions = positionAccessors(model_.meshes[size_t(p.mesh)]);
        return copies[size_t(p.mesh)] == 1 && !p.instances &&
               std::none_of(positions.begin(), positions.end(), [&](int a) { return vertexCopies[a] > 1; });
    };
    constexpr size_t kNone = std::numeric_limits<size_t>::max();
    std::vector<std::pair<size_t, size_t>> objectSpace(model_.meshes.size(), {kNone, kNone});  // MeshDesc range
    for (const Placement& p : placements_) {
        if (placedOnce(p)) {
            addMesh(p.mesh, p.world, p.node);
            continue;
        }
        auto& range = objectSpace[size_t(p.mesh)];
        if (range.first == kNone) {
            range.first = scene_.meshes.size();
            addMesh(p.mesh, glm::dmat4(1.0), p.node);
            range.second = scene_.meshes.size();
        }
        addInstances(p, range);
    }
}

// The placement's transforms, for each MeshDesc in [meshes.first, meshes.second). Instances
// compose with the node's world transform rounded to float, as the group keeps it (parent), so
// that an export, which writes that, loads back to the same transforms.
void Loader::addInstances(const Placement& placement, std::pair<size_t, size_t> meshes) {
    InstancesDesc group;
    auto add = [&](const glm::dmat4& world) {
        if (collapsesSpace(world))
            report_.fail("node " + std::to_string(placement.node) + " transform collapses mesh " +
                         std::to_string(placement.mesh) + " (zero scale or singular matrix)");
        group.toWorld.push_back(toAffine(world));
    };
    if (placement.instances) {
        group.parent = toAffine(placement.world);
        group.trs = *placement.instances;
        for (const TrsDesc& trs : group.trs) add(compose(toDmat4(group.parent), instanceMatrix(trs)));
    } else {
        add(placement.world);
    }
    for (size_t m = meshes.first; m < meshes.second; ++m) {
        group.mesh = int(m);
        scene_.instances.push_back(group);
    }
}

void Loader::addMesh(int meshIndex, const glm::dmat4& world, int nodeIndex) {
    const std::string node = "node " + std::to_string(nodeIndex);
    if (size_t(meshIndex) >= model_.meshes.size())
        report_.fail(node + " references mesh " + std::to_string(meshIndex) + ", which does not exist");
    if (collapsesSpace(world))
        report_.fail(node + " transform collapses mesh " + std::to_string(meshIndex) + " (zero scale or singular matrix)");
    const tinygltf::Mesh& mesh = model_.meshes[size_t(meshIndex)];
    for (size_t k = 0; k < mesh.primitives.size(); ++k) {
        const std::string name = (mesh.name.empty() ? "mesh " + std::to_string(meshIndex) : excerpt(mesh.name)) +
                                 " primitive " + std::to_string(k);
        addPrimitive(mesh.primitives[k], name, world);
    }
}

void Loader::addPrimitive(const tinygltf::Primitive& prim, const std::string& name, const glm::dmat4& world) {
    if (prim.mode != -1 && prim.mode != TINYGLTF_MODE_TRIANGLES) {
        report_.warnOnce(primitiveModeName(prim.mode) + " primitives are skipped (only TRIANGLES is supported)");
        return;
    }
    if (!prim.targets.empty()) report_.warnOnce("morph targets are ignored (the base geometry is used)");
    const auto position = prim.attributes.find("POSITION");
    if (position == prim.attributes.end()) report_.fail(name + " has no POSITION attribute");

    std::vector<Vec3> positions = accessors_.readVec3(position->second, name + " POSITION");
    for (Vec3& p : positions) p = transformPoint(world, p);
    for (const Vec3& p : positions)
        if (!isFinite(p)) report_.fail(name + " has non-finite vertex positions");
    const std::vector<Vec3> normals = worldNormals(prim, positions.size(), world, name);
    const int material = materialIndex(prim.material, name);
    MeshDesc attributes = scene_.materials[size_t(material)].textures
                              ? textureAttributes(prim, positions.size(), world, name) : MeshDesc{};
    attributes.colours = vertexColours(prim, positions.size(), name);

    std::vector<uint32_t> indices;
    if (prim.indices >= 0) {
        indices = accessors_.readIndices(prim.indices, name);
    } else {
        indices.resize(positions.size());
        for (size_t i = 0; i < indices.size(); ++i) indices[i] = uint32_t(i);
    }
    if (indices.size() % 3 != 0)
        report_.fail(name + " has " + std::to_string(indices.size()) + " indices, not a multiple of 3");
    for (uint32_t i : indices)
        if (i >= positions.size())
            report_.fail(name + " index " + std::to_string(i) + " is out of range (" +
                         std::to_string(positions.size()) + " vertices)");

    MeshDesc mesh = keepGoodTriangles(positions, normals, attributes, indices, mirrors(world), name);
    if (mesh.indices.empty()) return;
    mesh.name = name;
    mesh.material = material;
    scene_.meshes.push_back(std::move(mesh));
}

// World-space unit shading normals, or none when the primitive has no usable NORMAL attribute.
std::vector<Vec3> Loader::worldNormals(const tinygltf::Primitive& prim, size_t vertexCount,
                                       const glm::dmat4& world, const std::string& what) {
    const auto attribute = prim.attributes.find("NORMAL");
    if (attribute == prim.attributes.end()) return {};
    std::vector<Vec3> normals = accessors_.readVec3(attribute->second, what + " NORMAL");
    if (normals.size() != vertexCount)
        report_.fail(what + " has " + std::to_string(normals.size()) + " normals for " +
                     std::to_string(vertexCount) + " positions");
    const glm::dmat3 toWorld = normalMatrix(linearPart(world));
    for (Vec3& n : normals) {
        n = transformDirection(toWorld, n);
        if (isBlack(n)) {
            report_.warnOnce("primitives with zero-length or non-finite normals use geometric normals");
            return {};
        }
    }
    return normals;
}

// TEXCOORD_0, TEXCOORD_1 and TANGENT (world space; its sign flipped by a mirroring transform,
// which turns the bitangent's handedness) of a primitive whose material has textures, per vertex;
// an attribute the primitive lacks stays empty (TEXCOORD: read as (0, 0); TANGENT: derived from
// the texture coordinates, geometry/surface_textures.h).
MeshDesc Loader::textureAttributes(const tinygltf::Primitive& prim, size_t vertexCount, const glm::dmat4& world,
                                   const std::string& what) {
    MeshDesc m;
    auto read = [&](const char* attribute, int components) -> std::vector<float> {
        const auto it = prim.attributes.find(attribute);
        if (it == prim.attributes.end()) return {};
        const bool texCoord = components == 2;  // TEXCOORD_n may be normalized integers; TANGENT is float
        std::vector<float> values = accessors_.readFloats(it->second, components, what + " " + attribute, texCoord);
        if (values.size() != vertexCount * size_t(components))
            report_.fail(what + " has " + std::to_string(values.size() / size_t(components)) + " " + attribute +
                         " for " + std::to_string(vertexCount) + " positions");
        if (!allFinite(std::vector<double>(values.begin(), values.end())))
            report_.fail(what + " " + attribute + " is not finite");
        return values;
    };
    for (int set = 0; set < 2; ++set) {
        const std::vector<float> uv = read(set == 0 ? "TEXCOORD_0" : "TEXCOORD_1", 2);
        for (size_t i = 0; i < uv.size(); i += 2) m.texCoords[set].push_back({uv[i], uv[i + 1]});
    }
    const std::vector<float> tangents = read("TANGENT", 4);
    const glm::dmat3 linear = linearPart(world);
    const float handedness = mirrors(world) ? -1.0f : 1.0f;
    for (size_t i = 0; i < tangents.size(); i += 4) {
        m.tangents.push_back(transformDirection(linear, {tangents[i], tangents[i + 1], tangents[i + 2]}));
        m.tangentSigns.push_back(tangents[i + 3] < 0 ? -handedness : handedness);
    }
    return m;
}

// COLOR_0 of a primitive, per vertex, or none when it has no such attribute.
std::vector<std::array<float, 4>> Loader::vertexColours(const tinygltf::Primitive& prim, size_t vertexCount,
                                                        const std::string& what) {
    const auto it = prim.attributes.find("COLOR_0");
    if (it == prim.attributes.end()) return {};
    std::vector<std::array<float, 4>> colours = accessors_.readColours(it->second, what + " COLOR_0");
    if (colours.size() != vertexCount)
        report_.fail(what + " has " + std::to_string(colours.size()) + " COLOR_0 for " + std::to_string(vertexCount) +
                     " positions");
    for (const auto& c : colours)
        for (float x : c)
            if (!(x >= 0 && x <= 1)) report_.fail(what + " COLOR_0 has a value " + formatNumber(x) + " outside [0, 1]");
    return colours;
}

// Copies vertex v's texture attributes and colour (those `from` has) onto the end of `to`'s.
void copyVertexAttributes(const MeshDesc& from, uint32_t v, MeshDesc& to) {
    for (int set = 0; set < 2; ++set)
        if (!from.texCoords[set].empty()) to.texCoords[set].push_back(from.texCoords[set][v]);
    if (!from.colours.empty()) to.colours.push_back(from.colours[v]);
    if (from.tangents.empty()) return;
    to.tangents.push_back(from.tangents[v]);
    to.tangentSigns.push_back(from.tangentSigns[v]);
}

// Copies the non-degenerate triangles and the vertices they use, with their attributes (normals,
// and the texture attributes and colours `attributes` holds); counts the dropped ones. Fails on a
// triangle too large for float.
MeshDesc Loader::keepGoodTriangles(const std::vector<Vec3>& positions,
                                   const std::vector<Vec3>& normals, const MeshDesc& attributes,
                                   const std::vector<uint32_t>& indices, bool flipWinding, const std::string& what) {
    constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
    std::vector<uint32_t> remap(positions.size(), kUnused);
    MeshDesc mesh;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        uint32_t tri[3] = {indices[t], indices[t + 1], indices[t + 2]};
        if (flipWinding) std::swap(tri[1], tri[2]);
        const Vec3 a = positions[tri[0]], b = positions[tri[1]], c = positions[tri[2]];
        if (!hasFiniteProducts(a, b, c))
            report_.fail(what + " triangle " + std::to_string(t / 3) + " is not finite in float: its edges' " +
                         "lengths or cross product overflow (largest coordinate " +
                         formatNumber(maxComponent(max(abs(a), max(abs(b), abs(c))))) + ")");
        if (isDegenerate(a, b, c)) {
            ++droppedTriangles_;
            continue;
        }
        for (uint32_t v : tri) {
            if (remap[v] == kUnused) {
                remap[v] = uint32_t(mesh.positions.size());
                mesh.positions.push_back(positions[v]);
                if (!normals.empty()) mesh.normals.push_back(normals[v]);
                copyVertexAttributes(attributes, v, mesh);
            }
            mesh.indices.push_back(remap[v]);
        }
    }
    return mesh;
}

// ---------------------------------------------------------------------------------------------
// Camera and lights

void Loader::addCamera(int cameraIndex, const glm::dmat4& world, int nodeIndex) {
    const std::string node = "node " + std::to_string(nodeIndex);
    if (size_t(cameraIndex) >= model_.cameras.size())
        report_.fail(node + " references camera " + std::to_string(cameraIndex) + ", which does not exist");
    const tinygltf::Camera& camera = model_.cameras[size_t(cameraIndex)];
    if (camera.type != "perspective") {
        report_.warnOnce(excerpt(camera.type) + " cameras are ignored (only perspective cameras are supported)");
        return;
    }
    if (scene_.camera.present) return;  // the first perspective camera wins
    const double yfov = camera.perspective.yfov;
    if (!std::isfinite(yfov) || yfov <= 0 || yfov >= kPi)
        report_.fail("camera " + std::to_string(cameraIndex) + " yfov " + formatNumber(yfov) + " is not in (0, pi)");
    const Vec3 forward = transformDirection(linearPart(world), Vec3(0, 0, -1));
    const Vec3 upHint = transformDirection(linearPart(world), Vec3(0, 1, 0));
    const Vec3 upOrtho = upHint - forward * dot(upHint, forward);
    if (isBlack(forward) || !(length(upOrtho) > 1e-6f))
        report_.fail(node + " camera transform is degenerate");
    if (camera.perspective.aspectRatio > 0)
        report_.warnOnce("camera aspectRatio is ignored (the image size sets the aspect ratio)");
    scene_.camera.present = true;
    scene_.camera.position = transformPoint(world, Vec3(0.0f));
    scene_.camera.forward = forward;
    scene_.camera.up = normalize(upOrtho);
    scene_.camera.yfov = float(yfov);
}

// glTF gives point and spot intensities in candela (lm/sr) and a directional light's in lux
// (lm/m²). This renderer has no photometric units, so the numbers are taken as radiant intensity
// in W/sr and irradiance in W/m²: colour × intensity. Spot and directional lights shine along
// their node's −Z; `range` is a rasteriser's cut-off, not physics, and is ignored.
void Loader::addLight(const tinygltf::Node& node, const glm::dmat4& world, int nodeIndex) {
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end()) return;
    const std::string nodeName = "node " + std::to_string(nodeIndex);
    if (!ext->second.IsObject() || !ext->second.Get("light").IsInt())
        report_.fail(nodeName + " KHR_lights_punctual has no light index");
    const int index = ext->second.Get("light").GetNumberAsInt();
    if (index < 0 || size_t(index) >= model_.lights.size())
        report_.fail(nodeName + " references light " + std::to_string(index) + ", which does not exist");
    const tinygltf::Light& light = model_.lights[size_t(index)];
    const std::string what = "light " + std::to_string(index);
    LightDesc l;
    if (light.type == "point") {
        l.kind = LightDesc::Kind::Point;
    } else if (light.type == "spot") {
        l.kind = LightDesc::Kind::Spot;
        const double inner = light.spot.innerConeAngle, outer = light.spot.outerConeAngle;
        if (!std::isfinite(inner) || !std::isfinite(outer) || inner < 0 || inner >= outer || outer > 0.5 * kPi)
            report_.fail(what + " spot cone angles must satisfy 0 <= inner < outer <= pi/2");
        l.innerConeAngle = float(inner);
        l.outerConeAngle = float(outer);
    } else if (light.type == "directional") {
        l.kind = LightDesc::Kind::Directional;
    } else {
        report_.fail(what + " has type " + excerpt(light.type) + ", not point, spot or directional");
    }
    const Vec3 color = finiteVec3(light.color, Vec3(1.0f), what + " color", report_);
    if (!std::isfinite(float(light.intensity))) report_.fail(what + " intensity is not finite");
    if (light.intensity < 0 || color.x < 0 || color.y < 0 || color.z < 0)
        report_.fail(what + " has negative color or intensity");
    if (light.range > 0) report_.warnOnce("light range is ignored (lights fall off physically, as 1/r^2)");
    l.position = transformPoint(world, Vec3(0.0f));
    l.intensity = color * float(light.intensity);
    const Vec3 direction = transformDirection(linearPart(world), Vec3(0, 0, -1));
    if (isBlack(direction) || !isFinite(direction)) report_.fail(nodeName + " light transform is degenerate");
    l.direction = normalize(direction);
    scene_.lights.push_back(l);
}

}  // namespace

}  // namespace tripath::gltf

namespace tripath {

SceneDesc loadGltf(const std::string& path, WarningSink warn, const GltfOptions& options) {
    return gltf::Loader(path, std::move(warn), options).load();
}

}  // namespace tripath
