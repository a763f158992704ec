// glTF loader tests: each writes its own small .gltf / .glb into a fresh temporary directory,
// filled as a tinygltf::Model and written by the project's glTF writer (io/gltf_model.h);
// only JSON that no model can hold (a syntax error, a buffer naming a file) is written by hand.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "io/gltf_checks.h"
#include "io/gltf_document.h"
#include "io/gltf_loader.h"
#include "io/gltf_materials.h"
#include "io/gltf_model.h"

namespace tripath {
namespace {

namespace fs = std::filesystem;

constexpr int kUnsignedByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
constexpr int kUnsignedShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
constexpr int kUnsignedInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT;
const double kSin45 = std::sqrt(0.5);

// A node's fields, to be written as designated initialisers: {.mesh = 0, .translation = {1, 2, 3}}.
struct NodeSpec {
    int mesh = -1;
    int camera = -1;
    int light = -1;  // KHR_lights_punctual
    std::vector<double> translation{}, rotation{}, scale{}, matrix{};
    std::vector<int> children{};
};

tinygltf::Node node(const NodeSpec& spec) {
    tinygltf::Node n;
    n.mesh = spec.mesh;
    n.camera = spec.camera;
    if (spec.light >= 0) setExtension(n.extensions, "KHR_lights_punctual", "light", tinygltf::Value(spec.light));
    n.translation = spec.translation;
    n.rotation = spec.rotation;
    n.scale = spec.scale;
    n.matrix = spec.matrix;
    n.children = spec.children;
    return n;
}

tinygltf::Primitive primitive(int positions, int indices = -1, int material = -1, int normals = -1,
                              int mode = TINYGLTF_MODE_TRIANGLES) {
    tinygltf::Primitive p;
    p.attributes["POSITION"] = positions;
    if (normals >= 0) p.attributes["NORMAL"] = normals;
    p.indices = indices;
    p.material = material;
    p.mode = mode;
    return p;
}

tinygltf::Material pbrMaterial(const std::string& name, std::vector<double> baseColor, double metallic,
                               double roughness) {
    tinygltf::Material m;
    m.name = name;
    m.pbrMetallicRoughness.baseColorFactor = std::move(baseColor);
    m.pbrMetallicRoughness.metallicFactor = metallic;
    m.pbrMetallicRoughness.roughnessFactor = roughness;
    return m;
}

// Image 0 with `uri`, texture 0 on it, and a material whose base colour is that texture.
void addTexturedMaterial(tinygltf::Model& model, const std::string& uri) {
    model.images.emplace_back().uri = uri;
    model.textures.emplace_back().source = 0;
    model.materials.emplace_back().pbrMetallicRoughness.baseColorTexture.index = 0;
}

template <class T>
int append(std::vector<T>& items, T item) {
    items.push_back(std::move(item));
    return int(items.size()) - 1;
}

std::string writeText(const fs::path& file, const std::string& text) {
    std::ofstream(file) << text;
    return file.string();
}

// A test's document: binary data goes into buffer 0, anything else straight into `model`.
// Without scenes, write() adds scene 0 holding `roots`.
class GltfBuilder {
public:
    int addView(const void* data, size_t size, size_t byteStride = 0) {
        return appendBufferView(model, data, size, byteStride);
    }
    int addAccessor(int view, int componentType, size_t count, int type, size_t byteOffset = 0) {
        return appendAccessor(model, view, componentType, count, type, byteOffset);
    }
    int addVec3(const std::vector<Vec3>& values) {
        std::vector<float> flat;
        for (Vec3 v : values) flat.insert(flat.end(), {v.x, v.y, v.z});
        return addAccessor(addView(flat.data(), flat.size() * sizeof(float)), kFloat, values.size(), TINYGLTF_TYPE_VEC3);
    }
    int addIndices(const std::vector<uint32_t>& indices, int componentType) {
        std::vector<unsigned char> bytes;
        for (uint32_t i : indices) {
            const size_t size = componentType == kUnsignedByte ? 1 : componentType == kUnsignedShort ? 2 : 4;
            for (size_t b = 0; b < size; ++b) bytes.push_back((i >> (8 * b)) & 0xff);
        }
        return addAccessor(addView(bytes.data(), bytes.size()), componentType, indices.size(), TINYGLTF_TYPE_SCALAR);
    }
    int addMesh(const std::vector<tinygltf::Primitive>& primitives) {
        tinygltf::Mesh mesh;
        mesh.primitives = primitives;
        return append(model.meshes, mesh);
    }
    // One-primitive mesh from already added accessors; material < 0 leaves it out.
    int addTriangleMesh(int positions, int indices = -1, int material = -1, int normals = -1) {
        return addMesh({primitive(positions, indices, material, normals)});
    }
    int addNode(const NodeSpec& spec) { return append(model.nodes, node(spec)); }
    int addRoot(const NodeSpec& spec) { return append(roots, addNode(spec)); }

    // A .gltf with the buffer embedded, or a .glb with it in the BIN chunk.
    std::string write(const fs::path& file) const {
        tinygltf::Model out = model;
        if (out.scenes.empty()) {
            out.scenes.emplace_back().nodes = roots;
            out.defaultScene = 0;
        }
        writeGltfModel(out, file.string(), GltfBuffer::Embedded);
        return file.string();
    }
    // The binary data in `binFile` (folders created) and a .gltf whose buffer has the given uri:
    // tinygltf embeds every buffer it writes, so the uri is set in the written JSON afterwards.
    std::string writeWithUri(const fs::path& file, const std::string& uri, const fs::path& binFile) const {
        const std::vector<unsigned char>& bytes = model.buffers.at(0).data;
        fs::create_directories(binFile.parent_path());
        std::ofstream(binFile, std::ios::binary)
            .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        nlohmann::json json = nlohmann::json::parse(std::ifstream(write(file)));
        json["buffers"][0]["uri"] = uri;
        return writeText(file, json.dump());
    }
    std::string writeWithBin(const fs::path& file) const {
        const std::string bin = file.stem().string() + ".bin";
        return writeWithUri(file, bin, file.parent_path() / bin);
    }

    tinygltf::Model model;
    std::vector<int> roots;
};

using Triangle = std::array<Vec3, 3>;

// The scene's triangles in world space: meshes as they are, then each instance's copy.
std::vector<Triangle> triangles(const SceneDesc& scene) {
    std::vector<Triangle> out;
    auto add = [&](const MeshDesc& mesh, const Affine& toWorld) {
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
            out.push_back({transformPoint(toWorld, mesh.positions[mesh.indices[t]]),
                           transformPoint(toWorld, mesh.positions[mesh.indices[t + 1]]),
                           transformPoint(toWorld, mesh.positions[mesh.indices[t + 2]])});
    };
    std::vector<bool> instanced(scene.meshes.size(), false);
    for (const InstancesDesc& group : scene.instances) instanced.at(size_t(group.mesh)) = true;
    for (size_t i = 0; i < scene.meshes.size(); ++i)
        if (!instanced[i]) add(scene.meshes[i], Affine{});
    for (const InstancesDesc& group : scene.instances)
        for (const Affine& a : group.toWorld) add(scene.meshes[size_t(group.mesh)], a);
    return out;
}

void expectNear(Vec3 actual, Vec3 expected, float tolerance = 1e-5f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

const std::vector<Vec3> kTriangle = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const std::vector<Vec3> kQuad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::vector<uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

class GltfTest : public ::testing::Test {
protected:
    void SetUp() override {
        const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
        dir_ = fs::temp_directory_path() / ("tripath_gltf_" + test + "_" + std::to_string(std::random_device{}()));
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }

    fs::path file(const std::string& name) const { return dir_ / name; }
    const fs::path& testDir() const { return dir_; }
    SceneDesc load(const std::string& path) {
        return loadGltf(path, [this](const std::string& w) { warnings.push_back(w); });
    }
    // Loads a single-triangle scene whose one node is `spec` with mesh 0.
    SceneDesc loadTriangleUnder(NodeSpec spec) {
        GltfBuilder b;
        b.addTriangleMesh(b.addVec3(kTriangle));
        spec.mesh = 0;
        b.addRoot(spec);
        return load(b.write(file("node.gltf")));
    }
    size_t warningsContaining(const std::string& fragment) const {
        size_t n = 0;
        for (const std::string& w : warnings) n += w.find(fragment) != std::string::npos;
        return n;
    }
    void expectInputError(const std::string& path, const std::string& fragment) {
        try {
            load(path);
            ADD_FAILURE() << "no InputError (expected one containing '" << fragment << "')";
        } catch (const InputError& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(path), std::string::npos) << message;
            EXPECT_NE(message.find(fragment), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << message;
            // The file's path (and its folder, in a buffer file's path) and a sentence, quoting
            // excerpts of the file at most.
            EXPECT_LT(message.size(), 2 * path.size() + 240) << message;
        }
    }
    // A single triangle whose material is `material` (the file's only one): loading it must fail
    // with a message containing `fragment`.
    void expectMaterialRefused(const tinygltf::Material& material, const std::string& fragment) {
        GltfBuilder b;
        b.model.materials = {material};
        b.addTriangleMesh(b.addVec3(kTriangle), -1, 0);
        b.addRoot({.mesh = 0});
        expectInputError(b.write(file("material.gltf")), fragment);
    }

    std::vector<std::string> warnings;

private:
    fs::path dir_;
};

// --- transforms -----------------------------------------------------------------------------

// Scale (2,3,4), then 90° about z, then translation (1,2,3).
const std::vector<Vec3> kTransformedTriangle = {{1, 4, 3}, {-2, 2, 3}, {1, 2, 7}};

TEST_F(GltfTest, TrsTransformPlacesVertices) {
    const SceneDesc scene =
        loadTriangleUnder({.translation = {1, 2, 3}, .rotation = {0, 0, kSin45, kSin45}, .scale = {2, 3, 4}});
    const auto tris = triangles(scene);
    ASSERT_EQ(tris.size(), 1u);
    for (int i = 0; i < 3; ++i) expectNear(tris[0][i], kTransformedTriangle[i], 1e-4f);
}

TEST_F(GltfTest, MatrixTransformPlacesVertices) {
    // The same transform as a column-major matrix.
    const SceneDesc scene = loadTriangleUnder({.matrix = {0, 2, 0, 0, -3, 0, 0, 0, 0, 0, 4, 0, 1, 2, 3, 1}});
    const auto tris = triangles(scene);
    ASSERT_EQ(tris.size(), 1u);
    for (int i = 0; i < 3; ++i) expectNear(tris[0][i], kTransformedTriangle[i]);
}

TEST_F(GltfTest, NestedNodesComposeParentTimesChild) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.addRoot({.translation = {10, 0, 0}, .scale = {2, 2, 2}, .children = {1}});
    b.addNode({.translation = {1, 0, 0}, .children = {2}});
    b.addNode({.mesh = 0, .translation = {0, 0, 1}});
    const auto tris = triangles(load(b.write(file("nested.gltf"))));
    ASSERT_EQ(tris.size(), 1u);
    // parent(scale 2, +10x) × child(+1x) × grandchild(+1z): (1,0,0) → (1+1, 0, 1)·2 + (10,0,0)
    expectNear(tris[0][0], {14, 0, 2});
    expectNear(tris[0][1], {12, 2, 2});
    expectNear(tris[0][2], {12, 0, 4});
}

TEST_F(GltfTest, LoadsOnlyTheDefaultScene) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.addNode({.mesh = 0});
    b.addNode({.mesh = 0, .translation = {0, 0, 5}});
    b.model.scenes.resize(2);
    b.model.scenes[0].nodes = {0};
    b.model.scenes[1].nodes = {1};
    b.model.defaultScene = 1;
    const auto tris = triangles(load(b.write(file("scenes.gltf"))));
    ASSERT_EQ(tris.size(), 1u);
    expectNear(tris[0][2], {0, 0, 6});
}

TEST_F(GltfTest, MeshPlacedByTwoNodesIsKeptOnceWithTwoTransforms) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.addRoot({.mesh = 0});
    b.addRoot({.mesh = 0, .translation = {0, 3, 0}});
    const SceneDesc scene = load(b.write(file("instanced.gltf")));
    ASSERT_EQ(scene.meshes.size(), 1u);
    ASSERT_EQ(scene.instances.size(), 2u);
    const auto tris = triangles(scene);
    ASSERT_EQ(tris.size(), 2u);
    expectNear(tris[0][1], {0, 1, 0});
    expectNear(tris[1][1], {0, 4, 0});
}

// --- indices and accessors ------------------------------------------------------------------

TEST_F(GltfTest, IndexTypesAndNonIndexedGiveTheSameTriangles) {
    GltfBuilder b;
    const int positions = b.addVec3(kQuad);
    b.addTriangleMesh(positions, b.addIndices(kQuadIndices, kUnsignedByte));
    b.addTriangleMesh(positions, b.addIndices(kQuadIndices, kUnsignedShort));
    b.addTriangleMesh(positions, b.addIndices(kQuadIndices, kUnsignedInt));
    std::vector<Vec3> unrolled;
    for (uint32_t i : kQuadIndices) unrolled.push_back(kQuad[i]);
    b.addTriangleMesh(b.addVec3(unrolled));
    for (int m = 0; m < 4; ++m) b.addRoot({.mesh = m});
    const SceneDesc scene = load(b.write(file("indices.gltf")));
    ASSERT_EQ(scene.meshes.size(), 4u);
    std::vector<Triangle> expected;
    for (size_t t = 0; t < kQuadIndices.size(); t += 3)
        expected.push_back({kQuad[kQuadIndices[t]], kQuad[kQuadIndices[t + 1]], kQuad[kQuadIndices[t + 2]]});
    for (int m = 0; m < 4; ++m) {
        SceneDesc one;
        one.meshes = {scene.meshes[m]};
        const auto tris = triangles(one);
        ASSERT_EQ(tris.size(), expected.size()) << "mesh " << m;
        EXPECT_EQ(scene.meshes[m].positions.size(), m < 3 ? 4u : 6u) << "shared vertices stay shared";
        for (size_t t = 0; t < tris.size(); ++t)
            for (int v = 0; v < 3; ++v) EXPECT_TRUE(tris[t][v] == expected[t][v]) << "mesh " << m;
    }
}

TEST_F(GltfTest, InterleavedAttributesWithByteStrideAndOffsets) {
    // position xyz, normal xyz per vertex (stride 24), preceded by 8 bytes of padding.
    std::vector<float> interleaved = {-1, -1};
    for (Vec3 p : kQuad) interleaved.insert(interleaved.end(), {p.x, p.y, p.z, 0, 0, 1});
    GltfBuilder b;
    const int view = b.addView(interleaved.data(), interleaved.size() * sizeof(float), 24);
    const int positions = b.addAccessor(view, kFloat, 4, TINYGLTF_TYPE_VEC3, 8);
    const int normals = b.addAccessor(view, kFloat, 4, TINYGLTF_TYPE_VEC3, 20);
    const std::vector<uint16_t> indices = {99, 0, 1, 2, 0, 2, 3};  // skip the first by byteOffset
    const int indexView = b.addView(indices.data(), indices.size() * 2);
    const int indexAccessor = b.addAccessor(indexView, kUnsignedShort, 6, TINYGLTF_TYPE_SCALAR, 2);
    b.addTriangleMesh(positions, indexAccessor, -1, normals);
    b.addRoot({.mesh = 0});
    const SceneDesc scene = load(b.write(file("interleaved.gltf")));
    const auto tris = triangles(scene);
    ASSERT_EQ(tris.size(), 2u);
    EXPECT_TRUE(tris[0][2] == kQuad[2]);
    EXPECT_TRUE(tris[1][2] == kQuad[3]);
    ASSERT_EQ(scene.meshes[0].normals.size(), scene.meshes[0].positions.size());
    for (Vec3 n : scene.meshes[0].normals) expectNear(n, {0, 0, 1});
}

// --- normals --------------------------------------------------------------------------------

TEST_F(GltfTest, NormalsUseTheInverseTransposeAndAreUnit) {
    const std::vector<Vec3> positions = {{0, 0, 0}, {1, -1, 0}, {0, 0, 1}};  // plane normal ∝ (1,1,0)
    const Vec3 n = normalize(Vec3(1, 1, 0));
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(positions), -1, -1, b.addVec3({n, n, n}));
    b.addRoot({.translation = {5, 5, 5}, .scale = {2, 1, 1}, .children = {1}});
    b.addNode({.mesh = 0});
    const SceneDesc scene = load(b.write(file("normals.gltf")));
    ASSERT_EQ(scene.meshes.size(), 1u);
    ASSERT_EQ(scene.meshes[0].normals.size(), 3u);
    const Vec3 expected = normalize(Vec3(1, 2, 0));  // diag(1/2,1,1)·(1,1,0), normalised
    for (Vec3 m : scene.meshes[0].normals) expectNear(m, expected);
}

TEST_F(GltfTest, MirroringTransformKeepsWindingConsistentWithNormals) {
    GltfBuilder b;
    const std::vector<Vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};  // counter-clockwise, +z
    const Vec3 up(0, 0, 1);
    b.addTriangleMesh(b.addVec3(positions), -1, -1, b.addVec3({up, up, up}));
    b.addRoot({.mesh = 0, .scale = {-1, 1, 1}});
    const SceneDesc scene = load(b.write(file("mirror.gltf")));
    const auto tris = triangles(scene);
    ASSERT_EQ(tris.size(), 1u);
    const Vec3 geometric = cross(tris[0][1] - tris[0][0], tris[0][2] - tris[0][0]);
    expectNear(scene.meshes[0].normals[0], {0, 0, 1});
    EXPECT_GT(dot(geometric, scene.meshes[0].normals[0]), 0.0f);
}

// --- materials ------------------------------------------------------------------------------

TEST_F(GltfTest, MaterialsMapToTypesAndParameters) {
    GltfBuilder b;
    b.model.extensionsUsed = {"KHR_materials_transmission", "KHR_materials_ior"};
    auto transmitting = [](const char* name, double metallic, double roughness, double transmission) {
        tinygltf::Material m = pbrMaterial(name, {0.9, 0.95, 1, 1}, metallic, roughness);
        setExtension(m.extensions, "KHR_materials_transmission", "transmissionFactor", tinygltf::Value(transmission));
        return m;
    };
    tinygltf::Material glass = transmitting("glass", 0, 0, 1);
    setExtension(glass.extensions, "KHR_materials_ior", "ior", tinygltf::Value(1.33));
    tinygltf::Material thinGlass = pbrMaterial("thin glass", {1, 1, 1, 1}, 0, 0);
    setExtension(thinGlass.extensions, "KHR_materials_transmission", "transmissionFactor", tinygltf::Value(1));
    tinygltf::Material mirror = pbrMaterial("mirror", {0.9, 0.9, 0.9, 1}, 1, 0);
    mirror.extras = gltf::mirrorMarker();
    b.model.materials = {glass,
                         pbrMaterial("smooth metal", {0.9, 0.9, 0.9, 1}, 1, 0),
                         pbrMaterial("metal", {1, 0.8, 0.5, 1}, 1, 0.3),
                         pbrMaterial("diffuse", {0.2, 0.4, 0.6, 1}, 0, 1),
                         pbrMaterial("plastic", {0.5, 0.1, 0.1, 1}, 0, 0.4),
                         thinGlass,
                         mirror,
                         transmitting("transmitting metal", 1, 0, 1),  // metallicFactor 1 leaves no dielectric half
                         transmitting("frosted glass", 0, 0.4, 1),
                         transmitting("partly transmissive", 0.2, 0.3, 0.5)};
    const int kFileMaterials = 10;
    const int positions = b.addVec3(kTriangle);
    for (int m = 0; m < kFileMaterials; ++m) b.addTriangleMesh(positions, -1, m);
    b.addTriangleMesh(positions);  // no material
    for (int m = 0; m <= kFileMaterials; ++m) b.addRoot({.mesh = m});
    const SceneDesc scene = load(b.write(file("materials.gltf")));

    ASSERT_EQ(scene.meshes.size(), size_t(kFileMaterials + 1));
    ASSERT_EQ(scene.materials.size(), size_t(kFileMaterials + 1));
    for (int m = 0; m < kFileMaterials; ++m) EXPECT_EQ(scene.meshes[m].material, m);
    const auto& mats = scene.materials;
    EXPECT_EQ(mats[0].type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(mats[0].ior, 1.33f);
    expectNear(mats[0].albedo, {0.9f, 0.95f, 1});
    EXPECT_EQ(mats[1].type, MaterialType::SmoothConductor);  // the BRDF's limit: Schlick's Fresnel
    expectNear(mats[1].albedo, Vec3(0.9f));
    EXPECT_EQ(mats[6].type, MaterialType::Mirror);  // marked as the renderer's Fresnel-free mirror
    expectNear(mats[6].albedo, Vec3(0.9f));
    EXPECT_EQ(mats[2].type, MaterialType::Conductor);
    EXPECT_FLOAT_EQ(mats[2].roughness, 0.3f);
    expectNear(mats[2].albedo, {1, 0.8f, 0.5f});
    EXPECT_EQ(mats[3].type, MaterialType::Lambertian);
    expectNear(mats[3].albedo, {0.2f, 0.4f, 0.6f});
    EXPECT_EQ(mats[4].type, MaterialType::Plastic);
    EXPECT_FLOAT_EQ(mats[4].roughness, 0.4f);
    EXPECT_FLOAT_EQ(mats[4].ior, 1.5f);
    expectNear(mats[4].albedo, {0.5f, 0.1f, 0.1f});
    EXPECT_EQ(mats[5].type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(mats[5].ior, 1.5f);
    EXPECT_EQ(mats[7].type, MaterialType::SmoothConductor);
    EXPECT_EQ(mats[8].type, MaterialType::RoughDielectric);
    EXPECT_FLOAT_EQ(mats[8].roughness, 0.4f);
    expectNear(mats[8].albedo, {0.9f, 0.95f, 1});
    EXPECT_EQ(mats[9].type, MaterialType::MetallicRoughness);
    EXPECT_FLOAT_EQ(mats[9].metallic, 0.2f);
    EXPECT_FLOAT_EQ(mats[9].transmission, 0.5f);
    EXPECT_FLOAT_EQ(mats[9].roughness, 0.3f);
    EXPECT_EQ(mats[10].type, MaterialType::Lambertian);  // the default for no material
    expectNear(mats[10].albedo, Vec3(0.8f));
    EXPECT_EQ(scene.meshes[10].material, 10);
    for (const Material& m : mats) EXPECT_TRUE(isBlack(m.emission)) << m.name;
}

TEST_F(GltfTest, EmissionIsFactorTimesStrengthAndDoubleSidedIsTwoSided) {
    GltfBuilder b;
    tinygltf::Material strong, plain;
    strong.emissiveFactor = {1, 0.5, 0.25};
    strong.doubleSided = true;
    setExtension(strong.extensions, "KHR_materials_emissive_strength", "emissiveStrength", tinygltf::Value(10));
    plain.emissiveFactor = {0.5, 0.5, 0.5};
    b.model.materials = {strong, plain};
    const int positions = b.addVec3(kTriangle);
    b.addTriangleMesh(positions, -1, 0);
    b.addTriangleMesh(positions, -1, 1);
    b.addRoot({.mesh = 0});
    b.addRoot({.mesh = 1});
    const SceneDesc scene = load(b.write(file("emission.gltf")));
    ASSERT_EQ(scene.materials.size(), 2u);
    expectNear(scene.materials[0].emission, {10, 5, 2.5f});
    EXPECT_TRUE(scene.materials[0].twoSidedEmission);
    expectNear(scene.materials[1].emission, Vec3(0.5f));
    EXPECT_FALSE(scene.materials[1].twoSidedEmission);
}

// --- camera and lights ----------------------------------------------------------------------

TEST_F(GltfTest, FirstPerspectiveCameraInTheHierarchy) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.model.cameras.resize(3);
    tinygltf::Camera& orthographic = b.model.cameras[0];
    orthographic.type = "orthographic";
    orthographic.orthographic.xmag = orthographic.orthographic.ymag = 1;
    orthographic.orthographic.znear = 0.1;
    orthographic.orthographic.zfar = 10;
    for (int c : {1, 2}) {
        b.model.cameras[c].type = "perspective";
        b.model.cameras[c].perspective.yfov = c == 1 ? 0.8 : 0.3;
        b.model.cameras[c].perspective.znear = 0.1;
    }
    b.addRoot({.mesh = 0});
    b.addRoot({.camera = 0});
    b.addRoot({.translation = {0, 10, 0}, .children = {3}});
    b.addNode({.camera = 1, .translation = {1, 2, 3}, .rotation = {0, kSin45, 0, kSin45}});
    b.addRoot({.camera = 2});
    const SceneDesc scene = load(b.write(file("camera.gltf")));
    ASSERT_TRUE(scene.camera.present);
    expectNear(scene.camera.position, {1, 12, 3});
    expectNear(scene.camera.forward, {-1, 0, 0}, 1e-4f);  // -z turned 90° about +y
    expectNear(scene.camera.up, {0, 1, 0}, 1e-4f);
    EXPECT_FLOAT_EQ(scene.camera.yfov, 0.8f);
    EXPECT_EQ(warningsContaining("orthographic cameras are ignored"), 1u);
}

TEST_F(GltfTest, NoCameraLeavesCameraAbsent) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.addRoot({.mesh = 0});
    EXPECT_FALSE(load(b.write(file("nocamera.gltf"))).camera.present);
}

TEST_F(GltfTest, PunctualLightsFromKhrLightsPunctual) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.model.lights.resize(3);  // tinygltf lists KHR_lights_punctual in extensionsUsed
    b.model.lights[0].type = "point";
    b.model.lights[0].color = {1, 0.5, 0.25};
    b.model.lights[0].intensity = 100;
    b.model.lights[1].type = "spot";
    b.model.lights[1].intensity = 5;
    b.model.lights[1].spot.innerConeAngle = 0.25;
    b.model.lights[1].spot.outerConeAngle = 0.5;
    b.model.lights[2].type = "directional";
    b.model.lights[2].intensity = 3;
    b.model.lights[2].range = 10;
    b.addRoot({.mesh = 0});
    b.addRoot({.translation = {0, 5, 0}, .children = {2}});
    b.addNode({.light = 0, .translation = {1, 0, 0}});
    b.addRoot({.light = 1, .translation = {0, 0, 2}});
    // A quarter turn about −x takes the node's −Z to −Y: a light shining straight down.
    b.addRoot({.light = 2, .rotation = {-std::sqrt(0.5), 0, 0, std::sqrt(0.5)}});
    const SceneDesc scene = load(b.write(file("lights.gltf")));
    ASSERT_EQ(scene.lights.size(), 3u);
    EXPECT_EQ(scene.lights[0].kind, LightDesc::Kind::Point);
    expectNear(scene.lights[0].position, {1, 5, 0});
    expectNear(scene.lights[0].intensity, {100, 50, 25});
    EXPECT_EQ(scene.lights[1].kind, LightDesc::Kind::Spot);
    expectNear(scene.lights[1].position, {0, 0, 2});
    expectNear(scene.lights[1].direction, {0, 0, -1});
    EXPECT_FLOAT_EQ(scene.lights[1].innerConeAngle, 0.25f);
    EXPECT_FLOAT_EQ(scene.lights[1].outerConeAngle, 0.5f);
    EXPECT_EQ(scene.lights[2].kind, LightDesc::Kind::Directional);
    expectNear(scene.lights[2].direction, {0, -1, 0});
    expectNear(scene.lights[2].intensity, {3, 3, 3});
    EXPECT_EQ(warningsContaining("range is ignored"), 1u);
}

// --- containers -----------------------------------------------------------------------------

GltfBuilder quadScene() {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kQuad), b.addIndices(kQuadIndices, kUnsignedShort));
    b.addRoot({.mesh = 0, .translation = {0, 0, -2}});
    return b;
}

void expectSameTriangles(const SceneDesc& a, const SceneDesc& b) {
    const auto ta = triangles(a), tb = triangles(b);
    ASSERT_EQ(ta.size(), tb.size());
    for (size_t t = 0; t < ta.size(); ++t)
        for (int v = 0; v < 3; ++v) EXPECT_TRUE(ta[t][v] == tb[t][v]);
}

TEST_F(GltfTest, GlbWithEmbeddedBinChunk) {
    const GltfBuilder b = quadScene();
    const SceneDesc glb = load(b.write(file("quad.glb")));
    EXPECT_EQ(triangles(glb).size(), 2u);
    expectNear(triangles(glb)[0][1], {1, 0, -2});
    expectSameTriangles(glb, load(b.write(file("quad.gltf"))));
    EXPECT_EQ(glb.name, file("quad.glb").string());
}

TEST_F(GltfTest, GltfWithBinFileBesideIt) {
    const GltfBuilder b = quadScene();
    const SceneDesc separate = load(b.writeWithBin(file("quad.gltf")));
    EXPECT_EQ(triangles(separate).size(), 2u);
    expectSameTriangles(separate, load(b.write(file("quad.glb"))));
}

// --- which files a buffer URI may name --------------------------------------------------------

// Expects the load to be refused with one line naming the scene, buffer 0 (with its name when
// the builder gave one), the resolved path and the reason.
void expectBufferRefused(const std::string& scene, const std::string& buffer, const fs::path& resolved,
                         const std::string& reason, const GltfOptions& options = {}) {
    try {
        loadGltf(scene, [](const std::string&) {}, options);
        ADD_FAILURE() << scene << " loaded (expected the buffer to be refused: " << reason << ")";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_EQ(message.rfind(scene + ": " + buffer + ": uri ", 0), 0u) << message;
        EXPECT_NE(message.find(" names \"" + resolved.string() + "\", " + reason), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

// The scene folder for these tests: a subfolder of the test's folder, so that there is an
// outside to escape to. Resolved, as the messages give paths.
fs::path sceneFolder(const fs::path& testFolder) {
    fs::create_directories(testFolder / "scene");
    return fs::canonical(testFolder / "scene");
}

// The fuzzer's find: "%2E" decodes to ".", the scene's own folder, which tinygltf read as a file
// of 2^63 bytes (std::bad_alloc). The saved input is refused naming the buffer and the folder.
TEST_F(GltfTest, BufferUriNamingTheScenesFolderIsRefused) {
    const fs::path fuzzInput =
        fs::path(TRIPATH_SOURCE_DIR) / "tests" / "data" / "fuzz" / "buffer-uri-names-its-folder.gltf";
    expectBufferRefused(fuzzInput.string(), "buffer 0", fs::canonical(fuzzInput.parent_path()),
                        "which is a directory, not a file");

    GltfBuilder b = quadScene();
    b.model.buffers[0].name = "geometry";
    const fs::path folder = sceneFolder(testDir());
    for (const std::string uri : {"%2E", "%2e/", ".", "%2E%2Fsub%2F%2E%2E"}) {
        fs::create_directories(folder / "sub");
        expectBufferRefused(b.writeWithUri(folder / "quad.gltf", uri, testDir() / "unused.bin"),
                            "buffer 0 \"geometry\"", folder, "which is a directory, not a file");
    }
}

TEST_F(GltfTest, AbsoluteBufferUriIsRefused) {
    const GltfBuilder b = quadScene();
    const fs::path folder = sceneFolder(testDir());
    for (const std::string& path :
         std::vector<std::string>{"/etc/passwd", "/proc/self/environ", (testDir() / "quad.bin").string()}) {
        expectBufferRefused(b.writeWithUri(folder / "quad.gltf", path, testDir() / "quad.bin"), "buffer 0", path,
                            "an absolute path");
    }
}

TEST_F(GltfTest, BufferUriEscapingTheFolderWithDotDotIsRefused) {
    const GltfBuilder b = quadScene();
    const fs::path folder = sceneFolder(testDir());
    for (const std::string uri : {"../quad.bin", "%2E%2E%2Fquad.bin", "sub/../../quad.bin"}) {
        expectBufferRefused(b.writeWithUri(folder / "quad.gltf", uri, testDir() / "quad.bin"), "buffer 0",
                            fs::canonical(testDir()) / "quad.bin", "outside the scene's folder " + folder.string());
    }
}

TEST_F(GltfTest, SymlinkLeavingTheFolderIsRefused) {
    const GltfBuilder b = quadScene();
    const fs::path folder = sceneFolder(testDir());
    const std::string scene = b.writeWithUri(folder / "quad.gltf", "link.bin", testDir() / "quad.bin");
    fs::create_symlink(testDir() / "quad.bin", folder / "link.bin");
    expectBufferRefused(scene, "buffer 0", fs::canonical(testDir()) / "quad.bin",
                        "outside the scene's folder " + folder.string());
}

TEST_F(GltfTest, BufferInASubfolderLoads) {
    const GltfBuilder b = quadScene();
    const fs::path folder = sceneFolder(testDir());
    const SceneDesc embedded = load(b.write(file("quad.gltf")));
    expectSameTriangles(load(b.writeWithUri(folder / "quad.gltf", "data/quad%20file.bin", folder / "data" / "quad file.bin")),
                        embedded);
    expectSameTriangles(load(b.writeWithUri(folder / "quad.gltf", "data/../data/quad+file.bin", folder / "data" / "quad file.bin")),
                        embedded);
    // A symlink that stays inside the folder is fine too.
    fs::create_symlink(folder / "data" / "quad file.bin", folder / "link.bin");
    expectSameTriangles(load(b.writeWithUri(folder / "quad.gltf", "link.bin", folder / "data" / "quad file.bin")),
                        embedded);
}

TEST_F(GltfTest, OutsideFilesLoadWhenAllowed) {
    const GltfBuilder b = quadScene();
    const fs::path folder = sceneFolder(testDir());
    const SceneDesc embedded = load(b.write(file("quad.gltf")));
    const GltfOptions allow{.allowExternalFiles = true};
    const auto silent = [](const std::string&) {};
    const fs::path outside = fs::canonical(testDir()) / "quad.bin";
    expectSameTriangles(loadGltf(b.writeWithUri(folder / "quad.gltf", "../quad.bin", outside), silent, allow), embedded);
    expectSameTriangles(loadGltf(b.writeWithUri(folder / "quad.gltf", outside.string(), outside), silent, allow), embedded);
    fs::create_symlink(outside, folder / "link.bin");
    expectSameTriangles(loadGltf(b.writeWithUri(folder / "quad.gltf", "link.bin", outside), silent, allow), embedded);
    // Still only regular files: not a directory, not a device.
    expectBufferRefused(b.writeWithUri(folder / "quad.gltf", "..", outside), "buffer 0", fs::canonical(testDir()),
                        "which is a directory, not a file", allow);
    expectBufferRefused(b.writeWithUri(folder / "quad.gltf", "/dev/zero", outside), "buffer 0", "/dev/zero",
                        "which is not a regular file", allow);
}

TEST_F(GltfTest, MissingBufferFileIsNamed) {
    const GltfBuilder b = quadScene();
    const fs::path folder = sceneFolder(testDir());
    expectBufferRefused(b.writeWithUri(folder / "quad.gltf", "missing.bin", testDir() / "quad.bin"), "buffer 0",
                        folder / "missing.bin", "which does not exist");
}

// A buffer file over 4 GiB (here a sparse one, which costs no disk) is refused before it is read,
// rather than allocated and read whole.
TEST_F(GltfTest, BufferFileOverFourGibIsRefusedUnread) {
    const GltfBuilder b = quadScene();
    const fs::path folder = sceneFolder(testDir());
    const std::string scene = b.writeWithUri(folder / "quad.gltf", "big.bin", testDir() / "quad.bin");
    { std::ofstream(folder / "big.bin", std::ios::binary); }
    fs::resize_file(folder / "big.bin", (uintmax_t(5) << 30));
    expectBufferRefused(scene, "buffer 0", folder / "big.bin", "which is larger than 4 GiB (not supported)");
}

// The system cuts a path at a NUL character ("%00"), so what it would open is not what was checked.
TEST_F(GltfTest, BufferUriWithANulCharacterIsRefused) {
    const GltfBuilder b = quadScene();
    const fs::path folder = sceneFolder(testDir());
    const std::string scene = b.writeWithUri(folder / "quad.gltf", "quad.bin%00/../../quad.bin", folder / "quad.bin");
    expectBufferRefused(scene, "buffer 0", "quad.bin\\x00/../../quad.bin", "which contains a NUL character");
}

// Textures are ignored, so image files are never opened: not the folder (which tinygltf read as
// a file of 2^63 bytes), not a file elsewhere on the machine.
// Image files obey the buffers' rules: nothing outside the scene's folder, no directory or device.
TEST_F(GltfTest, ImageFilesOutsideTheRulesAreRefused) {
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"%2E", "is a directory"}, {"/proc/self/environ", "absolute"}, {"/dev/zero", "absolute"},
        {"../outside.png", "outside"}, {"missing.png", "does not exist"}};
    for (const auto& [uri, why] : cases) {
        GltfBuilder b;
        b.addTriangleMesh(b.addVec3(kTriangle));
        addTexturedMaterial(b.model, uri);
        b.addRoot({.mesh = 0});
        expectInputError(b.write(file("image.gltf")), "texture 0: uri");
    }
}

// --- warnings -------------------------------------------------------------------------------

TEST_F(GltfTest, DegenerateTrianglesDroppedWithOneWarning) {
    GltfBuilder b;
    const std::vector<Vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
    // good; repeated vertex; collinear — twice, in two meshes, for one warning in total
    const std::vector<uint32_t> indices = {0, 1, 2, 0, 0, 2, 0, 1, 3};
    const int p = b.addVec3(positions);
    b.addTriangleMesh(p, b.addIndices(indices, kUnsignedShort));
    b.addTriangleMesh(p, b.addIndices(indices, kUnsignedInt));
    b.addRoot({.mesh = 0});
    b.addRoot({.mesh = 1});
    const SceneDesc scene = load(b.write(file("degenerate.gltf")));
    EXPECT_EQ(triangles(scene).size(), 2u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("dropped 4 degenerate"), std::string::npos) << warnings[0];
    EXPECT_EQ(scene.meshes[0].positions.size(), 3u);  // the unused vertex is not copied
}

TEST_F(GltfTest, IgnoredFeaturesWarnOnceEach) {
    GltfBuilder b;
    const int p = b.addVec3(kTriangle);
    b.addMesh({primitive(p, -1, -1, -1, TINYGLTF_MODE_LINE), primitive(p, -1, -1, -1, TINYGLTF_MODE_LINE),
               primitive(p)});
    addTexturedMaterial(b.model, "missing.png");
    auto& material = b.model.materials[0];
    material.occlusionTexture.index = std::exchange(material.pbrMetallicRoughness.baseColorTexture.index, -1);
    b.model.materials.push_back(b.model.materials[0]);
    setExtension(b.model.materials[0].extensions, "KHR_materials_specular", "specularFactor", tinygltf::Value(0.5));
    setExtension(b.model.materials[1].extensions, "KHR_materials_specular", "specularFactor", tinygltf::Value(0.2));
    b.model.extensionsUsed = {"KHR_materials_specular"};
    b.addRoot({.mesh = 0});
    b.addRoot({.mesh = 0});
    const SceneDesc scene = load(b.write(file("ignored.gltf")));
    EXPECT_EQ(triangles(scene).size(), 2u);
    EXPECT_EQ(warningsContaining("LINES primitives are skipped"), 1u);
    EXPECT_EQ(warnings.size(), 3u);
    EXPECT_EQ(warningsContaining("occlusionTexture is ignored (path tracing computes what it stands in for): "
                                 "materials 'material 0', 'material 1'"), 1u);
    EXPECT_EQ(warningsContaining("KHR_materials_specular is ignored"), 1u);
    for (const std::string& w : warnings) EXPECT_EQ(w.find(file("ignored.gltf").string()), 0u) << w;
}

// COLOR_0 is read as glTF stores it: float, or unsigned byte or short normalized (c / 255,
// c / 65535), VEC3 (alpha 1) or VEC4 (a stride wider than the element included), linear (no sRGB
// decoding), per vertex, with no warning; COLOR_1 (here a type COLOR_0 may not have) is not read.
// Catches integers scaled by 256 or decoded as sRGB, and a VEC3's alpha left at 0.
TEST_F(GltfTest, VertexColoursReadAsTheirComponentTypeSays) {
    GltfBuilder b;
    const int p = b.addVec3(kTriangle);
    const std::vector<float> floats = {0.5f, 0.25f, 1.0f, 0.1f, 0.2f, 0.3f, 0.0f, 0.75f, 0.125f};
    const int f3 = b.addAccessor(b.addView(floats.data(), floats.size() * 4), kFloat, 3, TINYGLTF_TYPE_VEC3);
    const std::vector<uint8_t> bytes = {64, 128, 255, 51, 0, 1, 2, 3, 254, 253, 252, 251};
    const int u4 = b.addAccessor(b.addView(bytes.data(), bytes.size()), kUnsignedByte, 3, TINYGLTF_TYPE_VEC4);
    const std::vector<uint16_t> shorts = {65535, 32768, 1, 0, 1000, 2000, 3000, 0, 0, 65534, 7, 0};
    const int s3 = b.addAccessor(b.addView(shorts.data(), shorts.size() * 2, 8), kUnsignedShort, 3, TINYGLTF_TYPE_VEC3);
    b.model.accessors[size_t(u4)].normalized = b.model.accessors[size_t(s3)].normalized = true;
    std::vector<tinygltf::Primitive> primitives;
    for (int colours : {f3, u4, s3}) {
        primitives.push_back(primitive(p));
        primitives.back().attributes["COLOR_0"] = colours;
    }
    primitives.back().attributes["COLOR_1"] = b.addAccessor(b.addView(floats.data(), 24), kFloat, 3, TINYGLTF_TYPE_VEC2);
    b.addMesh(primitives);
    b.addRoot({.mesh = 0});
    const SceneDesc scene = load(b.write(file("colours.gltf")));
    ASSERT_EQ(scene.meshes.size(), 3u);
    std::array<std::vector<std::array<double, 4>>, 3> expected;
    for (size_t v = 0; v < 3; ++v) {
        expected[0].push_back({floats[3 * v], floats[3 * v + 1], floats[3 * v + 2], 1});
        expected[1].push_back({bytes[4 * v] / 255.0, bytes[4 * v + 1] / 255.0, bytes[4 * v + 2] / 255.0,
                               bytes[4 * v + 3] / 255.0});
        expected[2].push_back({shorts[4 * v] / 65535.0, shorts[4 * v + 1] / 65535.0, shorts[4 * v + 2] / 65535.0, 1});
    }
    for (size_t m = 0; m < 3; ++m) {
        ASSERT_EQ(scene.meshes[m].colours.size(), 3u) << "primitive " << m;
        for (size_t v = 0; v < 3; ++v)
            for (size_t c = 0; c < 4; ++c)
                EXPECT_FLOAT_EQ(scene.meshes[m].colours[v][c], float(expected[m][v][c]))
                    << "primitive " << m << " vertex " << v << " component " << c;
    }
    EXPECT_TRUE(warnings.empty()) << warnings.front();
}

// COLOR_0 of a type glTF does not allow for it, outside [0, 1] (a base colour multiplier: albedo
// above 1 would create energy) or of another count than POSITION is refused in one line.
TEST_F(GltfTest, BadVertexColoursAreRefused) {
    const float nan = std::nanf("");
    struct Case {
        const char* what;
        std::vector<float> values;  // as floats, unless `bytes`
        int type;
        bool bytes;
        const char* fragment;
    };
    const Case cases[] = {
        {"bytes not normalized", {}, TINYGLTF_TYPE_VEC4, true, "COLOR_0 accessor 1 is not float or normalized unsigned VEC4"},
        {"VEC2", {0, 0, 0, 0, 0, 0}, TINYGLTF_TYPE_VEC2, false, "is not float or normalized unsigned VEC3 or VEC4"},
        {"above 1", {0, 0, 0, 0, 1.5f, 0, 0, 0, 0}, TINYGLTF_TYPE_VEC3, false, "COLOR_0 has a value 1.5 outside [0, 1]"},
        {"negative", {0, 0, 0, 0, 0, 0, 0, 0, -0.25f}, TINYGLTF_TYPE_VEC3, false, "outside [0, 1]"},
        {"NaN", {0, 0, 0, nan, 0, 0, 0, 0, 0}, TINYGLTF_TYPE_VEC3, false, "outside [0, 1]"},
        {"two for three positions", {0, 0, 0, 0, 0, 0}, TINYGLTF_TYPE_VEC3, false, "has 2 COLOR_0 for 3 positions"},
    };
    for (const Case& k : cases) {
        SCOPED_TRACE(k.what);
        GltfBuilder b;
        tinygltf::Primitive coloured = primitive(b.addVec3(kTriangle));
        if (k.bytes) {
            const std::vector<uint8_t> bytes(12, 255);
            coloured.attributes["COLOR_0"] = b.addAccessor(b.addView(bytes.data(), bytes.size()), kUnsignedByte, 3, k.type);
        } else {
            const size_t components = k.type == TINYGLTF_TYPE_VEC2 ? 2 : 3;
            coloured.attributes["COLOR_0"] = b.addAccessor(b.addView(k.values.data(), k.values.size() * 4), kFloat,
                                                           k.values.size() / components, k.type);
        }
        b.addMesh({coloured});
        b.addRoot({.mesh = 0});
        expectInputError(b.write(file("colours.gltf")), k.fragment);
    }
}

TEST_F(GltfTest, DefaultWarningSinkPrintsWarningPrefix) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
    b.addRoot({.mesh = 0});
    const std::string path = b.write(file("stderr.gltf"));
    ::testing::internal::CaptureStderr();
    loadGltf(path);
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_EQ(err, "warning: " + path + ": dropped 1 degenerate (zero-area) triangles\n");
}

// --- bad input ------------------------------------------------------------------------------

TEST_F(GltfTest, MissingFileThrows) {
    expectInputError(file("does_not_exist.gltf").string(), "not found");
}

TEST_F(GltfTest, TruncatedGlbThrows) {
    const std::string path = quadScene().write(file("truncated.glb"));
    const auto size = fs::file_size(path);
    fs::resize_file(path, size / 2);
    expectInputError(path, ": truncated binary glTF: its header gives " + std::to_string(size) +
                               " bytes, the file has " + std::to_string(size / 2));
}

// Library wording ("Invalid magic.", "[json.exception.parse_error.101]") is not the message: it
// says which file and what is wrong with it.
TEST_F(GltfTest, GlbWithoutTheMagicIsNamedNotBinaryGltf) {
    expectInputError(writeText(file("text.glb"), "not a GLB at all"),
                     "text.glb: not a binary glTF file (bad magic: it does not start with \"glTF\")");
    const std::string json = quadScene().write(file("json.gltf"));
    fs::copy_file(json, file("json.glb"));
    expectInputError(file("json.glb").string(), "json.glb: not a binary glTF file (bad magic: it does not start with "
                                                "\"glTF\"); it looks like JSON: name it .gltf");
}

TEST_F(GltfTest, BrokenJsonThrows) {
    const std::string path =
        writeText(file("broken.gltf"), "{\"asset\":{\"version\":\"2.0\"},\n\"meshes\":[{\"primitives\":[");
    expectInputError(path, "broken.gltf: not valid JSON at line 2, column 26 (syntax error while parsing value - "
                           "unexpected end of input;");
    // nlohmann quotes the token it choked on ("last read: '...'"), here a 5000-byte string.
    const std::string longToken = writeText(file("token.gltf"), "{\"asset\": \"" + std::string(5000, 'x') + "\n\"}");
    expectInputError(longToken, "token.gltf: not valid JSON at line 1, column 5012 (syntax error while parsing value - "
                                "invalid string: control character U+000A (LF) must be escaped");
}

// tinygltf converts "extras" to its Value recursively: 16000 nested arrays overflowed the stack.
// The deepest nesting read loads; one level more is refused, naming the member.
TEST_F(GltfTest, JsonNestedDeeperThanTheLimitIsRefused) {
    std::string json = nlohmann::json::parse(std::ifstream(quadScene().write(file("quad.gltf")))).dump();
    json.pop_back();  // its closing brace
    const auto nested = [&](size_t depth) {  // "extras" is level 2, under the document
        const std::string extras = std::string(depth - 1, '[') + std::string(depth - 1, ']');
        return writeText(file("nested" + std::to_string(depth) + ".gltf"), json + ",\"extras\":" + extras + "}");
    };
    using gltf::kMaxJsonDepth;
    EXPECT_EQ(triangles(load(nested(kMaxJsonDepth))).size(), 2u);
    const std::string limit = std::to_string(kMaxJsonDepth);
    for (const size_t depth : {kMaxJsonDepth + 1, size_t(16000)})
        expectInputError(nested(depth), ".gltf: its JSON nests arrays and objects deeper than " + limit +
                                            " levels (in \"extras\"); tripath reads at most " + limit);
}

// nlohmann parses 1e400 as valid JSON and then refuses it as out of double's range, with an
// exception other than its parse_error.
TEST_F(GltfTest, NumberBeyondDoublesRangeIsRefused) {
    expectInputError(writeText(file("huge.gltf"), R"({"asset": {"version": "2.0"}, "extras": 1e400})"),
                     "huge.gltf: cannot read its JSON (number overflow parsing '1e400')");
}

TEST_F(GltfTest, EmptyFilesAndFilesWithoutAssetSaySo) {
    expectInputError(writeText(file("empty.gltf"), ""), "empty.gltf: the file is empty");
    expectInputError(writeText(file("object.gltf"), "{}"), "object.gltf: not a glTF file: it has no \"asset\" object");
    expectInputError(writeText(file("array.gltf"), "[1, 2]"),
                     "array.gltf: not a glTF file: its JSON is array, not an object");
    expectInputError(writeText(file("noversion.gltf"), R"({"asset": {}})"), "noversion.gltf: asset.version is missing");
}

// Writes `b` with asset.version set to `version`.
std::string writeWithVersion(const GltfBuilder& b, const fs::path& file, const std::string& version) {
    nlohmann::json json = nlohmann::json::parse(std::ifstream(b.write(file)));
    json["asset"]["version"] = version;
    return writeText(file, json.dump());
}

TEST_F(GltfTest, MajorVersionOtherThanTwoIsRefused) {
    const GltfBuilder b = quadScene();
    expectInputError(writeWithVersion(b, file("v3.gltf"), "3.0"),
                     "v3.gltf: glTF version \"3.0\" is not supported (only 2.x)");
    expectInputError(writeWithVersion(b, file("v1.gltf"), "1.0"), "v1.gltf: glTF version \"1.0\" is not supported");
    expectInputError(writeWithVersion(b, file("two.gltf"), "two"),
                     "two.gltf: asset.version \"two\" is not of the form major.minor");
    // Minor versions are compatible.
    EXPECT_EQ(triangles(load(writeWithVersion(b, file("v21.gltf"), "2.1"))).size(), 2u);
}

// A vertex at 1e30 is a finite float, but the edges' squared lengths and cross product (the
// normal and area the renderer computes in float) are not: said so, rather than "zero-area".
TEST_F(GltfTest, TrianglesWhoseProductsOverflowFloatAreNotFinite) {
    // A sliver reaching 1e30 (its edges' squared lengths overflow; in double it would be "zero-area"),
    // and a triangle of legs 1e10 (only its squared cross product, ~1e40, overflows).
    const std::vector<std::vector<Vec3>> tooLarge = {{{1e30f, 1e30f, 1e30f}, {1, 0, 0}, {0, 1, 0}},
                                                     {{0, 0, 0}, {1e10f, 0, 0}, {0, 1e10f, 0}}};
    for (const std::vector<Vec3>& far : tooLarge) {
        GltfBuilder b;
        std::vector<Vec3> positions = kTriangle;
        positions.insert(positions.end(), far.begin(), far.end());
        b.addTriangleMesh(b.addVec3(positions));
        b.addRoot({.mesh = 0});
        expectInputError(b.write(file("far.gltf")), "mesh 0 primitive 0 triangle 1 is not finite in float");
    }
    // Legs of 1e9: the squared cross product (~3e36) still fits in a float, and the triangle loads.
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3({{1e9f, 0, 0}, {0, 1e9f, 0}, {0, 0, 1e9f}}));
    b.addRoot({.mesh = 0});
    EXPECT_EQ(triangles(load(b.write(file("large.gltf")))).size(), 1u);
}

// http:, file: and any other scheme would be taken as a file's name ("http:/host/a.bin" in the
// scene's folder): refused as a scheme. Embedded data: URIs load (every test's buffer is one).
TEST_F(GltfTest, BufferUrisWithASchemeAreRefused) {
    const GltfBuilder b = quadScene();
    const fs::path folder = sceneFolder(testDir());
    for (const std::string uri :
         {"http://example.com/quad.bin", "file:///etc/passwd", "file:quad.bin", "s3://bucket/q.bin"}) {
        const std::string scene = b.writeWithUri(folder / "quad.gltf", uri, folder / "file:quad.bin");
        const std::string scheme = uri.substr(0, uri.find(':') + 1);
        expectInputError(scene, "buffer 0: uri \"" + uri + "\": URI scheme \"" + scheme + "\" is not supported");
    }
    expectInputError(b.writeWithUri(folder / "quad.gltf", "data:text/html,hello", folder / "unused.bin"),
                     "buffer 0: uri \"data:text/html,hello\" is a data: URI that is not base64");
}

// tinygltf's message for this quoted the whole base64 payload.
TEST_F(GltfTest, WrongByteLengthOfAnEmbeddedBufferIsSaidInNumbers) {
    const std::string path = quadScene().write(file("length.gltf"));
    nlohmann::json json = nlohmann::json::parse(std::ifstream(path));
    const auto size = json["buffers"][0]["byteLength"].get<size_t>();
    json["buffers"][0]["byteLength"] = size + 4;
    expectInputError(writeText(path, json.dump()), "length.gltf: buffer 0: byteLength is " + std::to_string(size + 4) +
                                                       ", but its data: URI holds " + std::to_string(size) + " bytes");
}

// What only tinygltf checks keeps its words, in a sentence that says who refused the file.
TEST_F(GltfTest, TinygltfsRefusalIsWrapped) {
    const std::string path = quadScene().write(file("accessor.gltf"));
    nlohmann::json json = nlohmann::json::parse(std::ifstream(path));
    json["accessors"][0].erase("componentType");
    expectInputError(writeText(path, json.dump()),
                     "accessor.gltf: the glTF reader refused it: 'componentType' property is missing");
}

// A name from the file is quoted as an excerpt: a 10 000-byte mesh name does not make a
// 10 000-byte message.
TEST_F(GltfTest, LongNamesAndUrisAreQuotedAsExcerpts) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle), b.addIndices({0, 1, 7}, kUnsignedByte));
    b.model.meshes[0].name = std::string(10000, 'm');
    b.addRoot({.mesh = 0});
    expectInputError(b.write(file("name.gltf")),
                     std::string(gltf::kExcerptLength, 'm') + "... (10000 bytes) primitive 0 index 7");
    const fs::path folder = sceneFolder(testDir());
    const std::string longUri = std::string(10000, 'u') + ".bin";
    expectInputError(quadScene().writeWithUri(folder / "quad.gltf", longUri, folder / "unused.bin"),
                     "buffer 0: uri \"" + std::string(gltf::kExcerptLength, 'u') + "... (10004 bytes)\" names");
}

TEST_F(GltfTest, AccessorReadingPastTheBufferThrows) {
    GltfBuilder b;
    const int view = b.addView(kTriangle.data(), 3 * sizeof(Vec3));
    b.addAccessor(view, kFloat, 3, TINYGLTF_TYPE_VEC3, 4);  // the last vertex runs 4 bytes past the view
    b.addTriangleMesh(0);
    b.addRoot({.mesh = 0});
    expectInputError(b.write(file("accessor.gltf")), "accessor 0 reads past the end");
}

TEST_F(GltfTest, BufferViewPastTheBufferThrows) {
    GltfBuilder b;
    b.addVec3(kTriangle);
    b.model.bufferViews.push_back(b.model.bufferViews[0]);
    b.model.bufferViews[1].byteLength = 4096;
    b.addAccessor(1, kFloat, 3, TINYGLTF_TYPE_VEC3);
    b.addTriangleMesh(1);
    b.addRoot({.mesh = 0});
    expectInputError(b.write(file("view.gltf")), "bufferView 1 reads past the end of buffer 0");
}

TEST_F(GltfTest, BufferIndexOutOfRangeThrows) {
    GltfBuilder b;
    b.addVec3(kTriangle);
    b.model.bufferViews.push_back(b.model.bufferViews[0]);
    b.model.bufferViews[1].buffer = 5;
    b.addAccessor(1, kFloat, 3, TINYGLTF_TYPE_VEC3);
    b.addTriangleMesh(1);
    b.addRoot({.mesh = 0});
    expectInputError(b.write(file("bufferindex.gltf")), "buffer 5, which does not exist");
}

TEST_F(GltfTest, VertexIndexOutOfRangeThrows) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle), b.addIndices({0, 1, 7}, kUnsignedByte));
    b.addRoot({.mesh = 0});
    expectInputError(b.write(file("index.gltf")), "index 7 is out of range");
}

TEST_F(GltfTest, NonFiniteBaseColorThrows) {
    expectMaterialRefused(pbrMaterial("bad", {1e39, 0.5, 0.5, 1}, 1, 1), "material 'bad': baseColorFactor is not finite");
}

// A name from the file is quoted in the message with its line break escaped: the message stays the
// one line the user sees (expectInputError checks for '\n'). Catches names quoted as they are.
TEST_F(GltfTest, NamesWithLineBreaksStayOnTheMessagesOneLine) {
    expectMaterialRefused(pbrMaterial("bad\nerror: forged\x1b[2J", {1e39, 0.5, 0.5, 1}, 1, 1),
                          "material 'bad\\nerror: forged\\x1b[2J': baseColorFactor is not finite");
}

TEST_F(GltfTest, NegativeEmissionThrows) {
    tinygltf::Material m;
    m.name = "neg";
    m.emissiveFactor = {1, -0.5, 0};
    expectMaterialRefused(m, "material 'neg': emission is negative");
}

TEST_F(GltfTest, NegativeEmissiveStrengthThrows) {
    tinygltf::Material m;
    m.name = "neg";
    m.emissiveFactor = {1, 1, 1};
    setExtension(m.extensions, "KHR_materials_emissive_strength", "emissiveStrength", tinygltf::Value(-2));
    expectMaterialRefused(m, "material 'neg': emissiveStrength is negative");
}

TEST_F(GltfTest, MaterialRejectedByValidateMaterialThrows) {
    expectMaterialRefused(pbrMaterial("bright", {2, 0.5, 0.5, 1}, 1, 1), "material 'bright': ");
}

TEST_F(GltfTest, ZeroScaleTransformThrows) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.addRoot({.mesh = 0, .scale = {1, 0, 1}});
    expectInputError(b.write(file("collapse.gltf")), "collapses mesh 0");
}

TEST_F(GltfTest, UnsupportedRequiredExtensionThrows) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.addRoot({.mesh = 0});
    b.model.extensionsUsed = b.model.extensionsRequired = {"KHR_draco_mesh_compression"};
    expectInputError(b.write(file("draco.gltf")), "KHR_draco_mesh_compression");
}

TEST_F(GltfTest, SceneWithoutTrianglesThrows) {
    GltfBuilder b;
    b.addMesh({primitive(b.addVec3(kTriangle), -1, -1, -1, TINYGLTF_MODE_POINTS)});
    b.addRoot({.mesh = 0});
    expectInputError(b.write(file("points.gltf")), "no triangles");
}

TEST_F(GltfTest, CycleInNodeHierarchyThrows) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.addRoot({.mesh = 0, .children = {1}});
    b.addNode({.children = {0}});
    expectInputError(b.write(file("cycle.gltf")), "cycle");
}

}  // namespace
}  // namespace tripath
