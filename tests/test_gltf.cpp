// glTF loader tests: each writes its own small .gltf / .glb into a fresh temporary directory.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "geometry/error.h"
#include "geometry/gltf_loader.h"
#include "geometry/gltf_writer.h"

namespace tripath {
namespace {

namespace fs = std::filesystem;

constexpr int kUnsignedByte = 5121;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kFloat = 5126;
const float kSin45 = std::sqrt(0.5f);


std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& item : items) out += (out.empty() ? "" : ",") + item;
    return out;
}

// Assembles a glTF document: binary data goes into buffer 0, everything else is raw JSON added
// to top-level arrays ("nodes", "meshes", ...). Without explicit "scenes", scene 0 holds `roots`.
class GltfBuilder {
public:
    // Appends bytes (padded to 4) as a new bufferView; returns its index.
    int addView(const void* data, size_t size, size_t byteStride = 0) {
        const size_t offset = bin_.size();
        bin_.insert(bin_.end(), static_cast<const unsigned char*>(data),
                    static_cast<const unsigned char*>(data) + size);
        while (bin_.size() % 4 != 0) bin_.push_back(0);
        std::string view = R"({"buffer":0,"byteOffset":)" + std::to_string(offset) +
                           R"(,"byteLength":)" + std::to_string(size);
        if (byteStride != 0) view += R"(,"byteStride":)" + std::to_string(byteStride);
        return add("bufferViews", view + "}");
    }
    int addAccessor(int view, int componentType, size_t count, const std::string& type,
                    size_t byteOffset = 0) {
        return add("accessors", R"({"bufferView":)" + std::to_string(view) + R"(,"byteOffset":)" +
                                    std::to_string(byteOffset) + R"(,"componentType":)" +
                                    std::to_string(componentType) + R"(,"count":)" +
                                    std::to_string(count) + R"(,"type":")" + type + "\"}");
    }
    int addVec3(const std::vector<Vec3>& values) {
        std::vector<float> flat;
        for (Vec3 v : values) flat.insert(flat.end(), {v.x, v.y, v.z});
        return addAccessor(addView(flat.data(), flat.size() * sizeof(float)), kFloat, values.size(), "VEC3");
    }
    int addIndices(const std::vector<uint32_t>& indices, int componentType) {
        std::vector<unsigned char> bytes;
        for (uint32_t i : indices) {
            const size_t size = componentType == kUnsignedByte ? 1 : componentType == kUnsignedShort ? 2 : 4;
            for (size_t b = 0; b < size; ++b) bytes.push_back((i >> (8 * b)) & 0xff);
        }
        return addAccessor(addView(bytes.data(), bytes.size()), componentType, indices.size(), "SCALAR");
    }
    // One-primitive mesh from already added accessors; material < 0 leaves it out.
    int addTriangleMesh(int positions, int indices = -1, int material = -1, int normals = -1) {
        std::string attributes = R"("POSITION":)" + std::to_string(positions);
        if (normals >= 0) attributes += R"(,"NORMAL":)" + std::to_string(normals);
        std::string primitive = R"({"attributes":{)" + attributes + "}";
        if (indices >= 0) primitive += R"(,"indices":)" + std::to_string(indices);
        if (material >= 0) primitive += R"(,"material":)" + std::to_string(material);
        return add("meshes", R"({"primitives":[)" + primitive + "}]}");
    }
    int add(const std::string& array, const std::string& json) {
        arrays_[array].push_back(json);
        return int(arrays_[array].size()) - 1;
    }
    int addRoot(const std::string& nodeJson) {
        const int node = add("nodes", nodeJson);
        roots.push_back(node);
        return node;
    }

    std::string json(const std::string* bufferUri) const {
        std::vector<std::string> members = {R"("asset":{"version":"2.0"})"};
        if (!bin_.empty()) {
            std::string buffer = R"({"byteLength":)" + std::to_string(bin_.size());
            if (bufferUri) buffer += R"(,"uri":")" + *bufferUri + "\"";
            if (!bufferName.empty()) buffer += R"(,"name":")" + bufferName + "\"";
            members.push_back(R"("buffers":[)" + buffer + "}]");
        }
        for (const auto& [name, items] : arrays_) members.push_back("\"" + name + "\":[" + join(items) + "]");
        if (!arrays_.count("scenes")) {
            std::vector<std::string> ids;
            for (int r : roots) ids.push_back(std::to_string(r));
            members.push_back(R"("scene":0,"scenes":[{"nodes":[)" + join(ids) + "]}]");
        }
        if (!topLevel.empty()) members.push_back(topLevel);
        return "{" + join(members) + "}";
    }

    std::string writeEmbedded(const fs::path& file) const {
        const std::string uri = "data:application/octet-stream;base64," + base64(bin_);
        return writeText(file, json(&uri));
    }
    std::string writeWithBin(const fs::path& file) const {
        const std::string uri = file.stem().string() + ".bin";
        std::ofstream(file.parent_path() / uri, std::ios::binary)
            .write(reinterpret_cast<const char*>(bin_.data()), std::streamsize(bin_.size()));
        return writeText(file, json(&uri));
    }
    // The binary data in `binFile` (folders created) and a .gltf whose buffer has the given uri.
    std::string writeWithUri(const fs::path& file, const std::string& uri, const fs::path& binFile) const {
        fs::create_directories(binFile.parent_path());
        std::ofstream(binFile, std::ios::binary)
            .write(reinterpret_cast<const char*>(bin_.data()), std::streamsize(bin_.size()));
        return writeText(file, json(&uri));
    }
    std::string writeGlb(const fs::path& file) const {
        std::string text = json(nullptr);
        while (text.size() % 4 != 0) text += ' ';
        std::vector<unsigned char> out;
        auto u32 = [&out](uint32_t v) {
            for (int b = 0; b < 4; ++b) out.push_back((v >> (8 * b)) & 0xff);
        };
        const size_t total = 12 + 8 + text.size() + (bin_.empty() ? 0 : 8 + bin_.size());
        u32(0x46546C67);  // "glTF"
        u32(2);
        u32(uint32_t(total));
        u32(uint32_t(text.size()));
        u32(0x4E4F534A);  // "JSON"
        out.insert(out.end(), text.begin(), text.end());
        if (!bin_.empty()) {
            u32(uint32_t(bin_.size()));
            u32(0x004E4942);  // "BIN"
            out.insert(out.end(), bin_.begin(), bin_.end());
        }
        std::ofstream(file, std::ios::binary)
            .write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()));
        return file.string();
    }
    static std::string writeText(const fs::path& file, const std::string& text) {
        std::ofstream(file) << text;
        return file.string();
    }

    std::vector<int> roots;
    std::string topLevel;  // extra top-level members, e.g. "extensionsRequired":[...]
    std::string bufferName;  // buffer 0's name, none when empty

private:
    std::vector<unsigned char> bin_;
    std::map<std::string, std::vector<std::string>> arrays_;
};

using Triangle = std::array<Vec3, 3>;

std::vector<Triangle> triangles(const SceneDesc& scene) {
    std::vector<Triangle> out;
    for (const MeshDesc& mesh : scene.meshes)
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
            out.push_back({mesh.positions[mesh.indices[t]], mesh.positions[mesh.indices[t + 1]],
                           mesh.positions[mesh.indices[t + 2]]});
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
    // Loads a single-triangle scene whose one node is `nodeJson` + "mesh":0.
    SceneDesc loadTriangleUnder(const std::string& nodeFields) {
        GltfBuilder b;
        b.addTriangleMesh(b.addVec3(kTriangle));
        b.addRoot("{" + nodeFields + R"(,"mesh":0})");
        return load(b.writeEmbedded(file("node.gltf")));
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
        }
    }

    std::vector<std::string> warnings;

private:
    fs::path dir_;
};

// --- transforms -----------------------------------------------------------------------------

// Scale (2,3,4), then 90° about z, then translation (1,2,3).
const std::vector<Vec3> kTransformedTriangle = {{1, 4, 3}, {-2, 2, 3}, {1, 2, 7}};

TEST_F(GltfTest, TrsTransformPlacesVertices) {
    const SceneDesc scene = loadTriangleUnder(R"("translation":[1,2,3],"rotation":[0,0,)" +
                                              std::to_string(kSin45) + "," + std::to_string(kSin45) +
                                              R"(],"scale":[2,3,4])");
    const auto tris = triangles(scene);
    ASSERT_EQ(tris.size(), 1u);
    for (int i = 0; i < 3; ++i) expectNear(tris[0][i], kTransformedTriangle[i], 1e-4f);
}

TEST_F(GltfTest, MatrixTransformPlacesVertices) {
    // The same transform as a column-major matrix.
    const SceneDesc scene = loadTriangleUnder(R"("matrix":[0,2,0,0, -3,0,0,0, 0,0,4,0, 1,2,3,1])");
    const auto tris = triangles(scene);
    ASSERT_EQ(tris.size(), 1u);
    for (int i = 0; i < 3; ++i) expectNear(tris[0][i], kTransformedTriangle[i]);
}

TEST_F(GltfTest, NestedNodesComposeParentTimesChild) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.addRoot(R"({"translation":[10,0,0],"scale":[2,2,2],"children":[1]})");
    b.add("nodes", R"({"translation":[1,0,0],"children":[2]})");
    b.add("nodes", R"({"translation":[0,0,1],"mesh":0})");
    const auto tris = triangles(load(b.writeEmbedded(file("nested.gltf"))));
    ASSERT_EQ(tris.size(), 1u);
    // parent(scale 2, +10x) × child(+1x) × grandchild(+1z): (1,0,0) → (1+1, 0, 1)·2 + (10,0,0)
    expectNear(tris[0][0], {14, 0, 2});
    expectNear(tris[0][1], {12, 2, 2});
    expectNear(tris[0][2], {12, 0, 4});
}

TEST_F(GltfTest, LoadsOnlyTheDefaultScene) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.add("nodes", R"({"mesh":0})");
    b.add("nodes", R"({"mesh":0,"translation":[0,0,5]})");
    b.add("scenes", R"({"nodes":[0]})");
    b.add("scenes", R"({"nodes":[1]})");
    b.topLevel = R"("scene":1)";
    const auto tris = triangles(load(b.writeEmbedded(file("scenes.gltf"))));
    ASSERT_EQ(tris.size(), 1u);
    expectNear(tris[0][2], {0, 0, 6});
}

TEST_F(GltfTest, MeshInstancedByTwoNodesGivesTwoMeshes) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.addRoot(R"({"mesh":0})");
    b.addRoot(R"({"mesh":0,"translation":[0,3,0]})");
    const auto tris = triangles(load(b.writeEmbedded(file("instanced.gltf"))));
    ASSERT_EQ(tris.size(), 2u);
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
    for (int m = 0; m < 4; ++m) b.addRoot(R"({"mesh":)" + std::to_string(m) + "}");
    const SceneDesc scene = load(b.writeEmbedded(file("indices.gltf")));
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
    const int positions = b.addAccessor(view, kFloat, 4, "VEC3", 8);
    const int normals = b.addAccessor(view, kFloat, 4, "VEC3", 20);
    const std::vector<uint16_t> indices = {99, 0, 1, 2, 0, 2, 3};  // skip the first by byteOffset
    const int indexView = b.addView(indices.data(), indices.size() * 2);
    const int indexAccessor = b.addAccessor(indexView, kUnsignedShort, 6, "SCALAR", 2);
    b.addTriangleMesh(positions, indexAccessor, -1, normals);
    b.addRoot(R"({"mesh":0})");
    const SceneDesc scene = load(b.writeEmbedded(file("interleaved.gltf")));
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
    b.addRoot(R"({"scale":[2,1,1],"translation":[5,5,5],"children":[1]})");
    b.add("nodes", R"({"mesh":0})");
    const SceneDesc scene = load(b.writeEmbedded(file("normals.gltf")));
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
    b.addRoot(R"({"scale":[-1,1,1],"mesh":0})");
    const SceneDesc scene = load(b.writeEmbedded(file("mirror.gltf")));
    const auto tris = triangles(scene);
    ASSERT_EQ(tris.size(), 1u);
    const Vec3 geometric = cross(tris[0][1] - tris[0][0], tris[0][2] - tris[0][0]);
    expectNear(scene.meshes[0].normals[0], {0, 0, 1});
    EXPECT_GT(dot(geometric, scene.meshes[0].normals[0]), 0.0f);
}

// --- materials ------------------------------------------------------------------------------

TEST_F(GltfTest, MaterialsMapToTypesAndParameters) {
    GltfBuilder b;
    b.topLevel = R"("extensionsUsed":["KHR_materials_transmission","KHR_materials_ior"])";
    b.add("materials", R"({"name":"glass","pbrMetallicRoughness":{"baseColorFactor":[0.9,0.95,1,1],
        "roughnessFactor":0},"extensions":{"KHR_materials_transmission":{"transmissionFactor":1},
        "KHR_materials_ior":{"ior":1.33}}})");
    b.add("materials", R"({"name":"mirror","pbrMetallicRoughness":{"baseColorFactor":[0.9,0.9,0.9,1],
        "metallicFactor":1,"roughnessFactor":0}})");
    b.add("materials", R"({"name":"metal","pbrMetallicRoughness":{"baseColorFactor":[1,0.8,0.5,1],
        "metallicFactor":1,"roughnessFactor":0.3}})");
    b.add("materials", R"({"name":"diffuse","pbrMetallicRoughness":{"baseColorFactor":[0.2,0.4,0.6,1],
        "metallicFactor":0,"roughnessFactor":1}})");
    b.add("materials", R"({"name":"plastic","pbrMetallicRoughness":{"baseColorFactor":[0.5,0.1,0.1,1],
        "metallicFactor":0,"roughnessFactor":0.4}})");
    b.add("materials", R"({"name":"thin glass","pbrMetallicRoughness":{"roughnessFactor":0,"metallicFactor":0},
        "extensions":{"KHR_materials_transmission":{"transmissionFactor":1}}})");
    const int positions = b.addVec3(kTriangle);
    for (int m = 0; m < 6; ++m) b.addTriangleMesh(positions, -1, m);
    b.addTriangleMesh(positions);  // no material
    for (int m = 0; m < 7; ++m) b.addRoot(R"({"mesh":)" + std::to_string(m) + "}");
    const SceneDesc scene = load(b.writeEmbedded(file("materials.gltf")));

    ASSERT_EQ(scene.meshes.size(), 7u);
    ASSERT_EQ(scene.materials.size(), 7u);
    for (int m = 0; m < 6; ++m) EXPECT_EQ(scene.meshes[m].material, m);
    const auto& mats = scene.materials;
    EXPECT_EQ(mats[0].type, MaterialType::Dielectric);
    EXPECT_FLOAT_EQ(mats[0].ior, 1.33f);
    expectNear(mats[0].albedo, {0.9f, 0.95f, 1});
    EXPECT_EQ(mats[1].type, MaterialType::Mirror);
    expectNear(mats[1].albedo, Vec3(0.9f));
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
    EXPECT_EQ(mats[6].type, MaterialType::Lambertian);  // the default for no material
    expectNear(mats[6].albedo, Vec3(0.8f));
    EXPECT_EQ(scene.meshes[6].material, 6);
    for (const Material& m : mats) EXPECT_TRUE(isBlack(m.emission)) << m.name;
}

TEST_F(GltfTest, EmissionIsFactorTimesStrengthAndDoubleSidedIsTwoSided) {
    GltfBuilder b;
    b.add("materials", R"({"emissiveFactor":[1,0.5,0.25],"doubleSided":true,
        "extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":10}}})");
    b.add("materials", R"({"emissiveFactor":[0.5,0.5,0.5]})");
    const int positions = b.addVec3(kTriangle);
    b.addTriangleMesh(positions, -1, 0);
    b.addTriangleMesh(positions, -1, 1);
    b.addRoot(R"({"mesh":0})");
    b.addRoot(R"({"mesh":1})");
    const SceneDesc scene = load(b.writeEmbedded(file("emission.gltf")));
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
    b.add("cameras", R"({"type":"orthographic","orthographic":{"xmag":1,"ymag":1,"znear":0.1,"zfar":10}})");
    b.add("cameras", R"({"type":"perspective","perspective":{"yfov":0.8,"znear":0.1}})");
    b.add("cameras", R"({"type":"perspective","perspective":{"yfov":0.3,"znear":0.1}})");
    b.addRoot(R"({"mesh":0})");
    b.addRoot(R"({"camera":0})");
    b.addRoot(R"({"translation":[0,10,0],"children":[3]})");
    b.add("nodes", R"({"translation":[1,2,3],"rotation":[0,)" + std::to_string(kSin45) + ",0," +
                       std::to_string(kSin45) + R"(],"camera":1})");
    b.addRoot(R"({"camera":2})");
    const SceneDesc scene = load(b.writeEmbedded(file("camera.gltf")));
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
    b.addRoot(R"({"mesh":0})");
    EXPECT_FALSE(load(b.writeEmbedded(file("nocamera.gltf"))).camera.present);
}

TEST_F(GltfTest, PointLightFromKhrLightsPunctual) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.topLevel = R"("extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":{"lights":[
        {"type":"point","color":[1,0.5,0.25],"intensity":100},
        {"type":"spot","intensity":5,"spot":{}}]}})";
    b.addRoot(R"({"mesh":0})");
    b.addRoot(R"({"translation":[0,5,0],"children":[2]})");
    b.add("nodes", R"({"translation":[1,0,0],"extensions":{"KHR_lights_punctual":{"light":0}}})");
    b.addRoot(R"({"extensions":{"KHR_lights_punctual":{"light":1}}})");
    const SceneDesc scene = load(b.writeEmbedded(file("lights.gltf")));
    ASSERT_EQ(scene.pointLights.size(), 1u);
    expectNear(scene.pointLights[0].position, {1, 5, 0});
    expectNear(scene.pointLights[0].intensity, {100, 50, 25});
    EXPECT_EQ(warningsContaining("spot lights are ignored"), 1u);
}

// --- containers -----------------------------------------------------------------------------

GltfBuilder quadScene() {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kQuad), b.addIndices(kQuadIndices, kUnsignedShort));
    b.addRoot(R"({"mesh":0,"translation":[0,0,-2]})");
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
    const SceneDesc glb = load(b.writeGlb(file("quad.glb")));
    EXPECT_EQ(triangles(glb).size(), 2u);
    expectNear(triangles(glb)[0][1], {1, 0, -2});
    expectSameTriangles(glb, load(b.writeEmbedded(file("quad.gltf"))));
    EXPECT_EQ(glb.name, file("quad.glb").string());
}

TEST_F(GltfTest, GltfWithBinFileBesideIt) {
    const GltfBuilder b = quadScene();
    const SceneDesc separate = load(b.writeWithBin(file("quad.gltf")));
    EXPECT_EQ(triangles(separate).size(), 2u);
    expectSameTriangles(separate, load(b.writeGlb(file("quad.glb"))));
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
    b.bufferName = "geometry";
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
    const SceneDesc embedded = load(b.writeEmbedded(file("quad.gltf")));
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
    const SceneDesc embedded = load(b.writeEmbedded(file("quad.gltf")));
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

// The system cuts a path at a NUL character ("%00"), so what it would open is not what was checked.
TEST_F(GltfTest, BufferUriWithANulCharacterIsRefused) {
    const GltfBuilder b = quadScene();
    const fs::path folder = sceneFolder(testDir());
    const std::string scene = b.writeWithUri(folder / "quad.gltf", "quad.bin%00/../../quad.bin", folder / "quad.bin");
    expectBufferRefused(scene, "buffer 0", "quad.bin\\x00/../../quad.bin", "which contains a NUL character");
}

// Textures are ignored, so image files are never opened: not the folder (which tinygltf read as
// a file of 2^63 bytes), not a file elsewhere on the machine.
TEST_F(GltfTest, ImageFilesAreNeverOpened) {
    for (const std::string uri : {"%2E", "/proc/self/environ", "/dev/zero"}) {
        GltfBuilder b;
        b.addTriangleMesh(b.addVec3(kTriangle));
        b.add("images", R"({"uri":")" + uri + "\"}");
        b.add("textures", R"({"source":0})");
        b.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})");
        b.addRoot(R"({"mesh":0})");
        EXPECT_EQ(triangles(load(b.writeEmbedded(file("image.gltf")))).size(), 1u) << uri;
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
    b.addRoot(R"({"mesh":0})");
    b.addRoot(R"({"mesh":1})");
    const SceneDesc scene = load(b.writeEmbedded(file("degenerate.gltf")));
    EXPECT_EQ(triangles(scene).size(), 2u);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("dropped 4 degenerate"), std::string::npos) << warnings[0];
    EXPECT_EQ(scene.meshes[0].positions.size(), 3u);  // the unused vertex is not copied
}

TEST_F(GltfTest, IgnoredFeaturesWarnOnceEach) {
    GltfBuilder b;
    const int p = b.addVec3(kTriangle);
    b.add("meshes", R"({"primitives":[{"attributes":{"POSITION":0},"mode":1},
        {"attributes":{"POSITION":0},"mode":1},{"attributes":{"POSITION":0}}]})");
    (void)p;
    b.add("images", R"({"uri":"missing.png"})");
    b.add("textures", R"({"source":0})");
    b.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}},
        "extensions":{"KHR_materials_specular":{"specularFactor":0.5}}})");
    b.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}},
        "extensions":{"KHR_materials_specular":{"specularFactor":0.2}}})");
    b.topLevel = R"("extensionsUsed":["KHR_materials_specular"])";
    b.addRoot(R"({"mesh":0})");
    b.addRoot(R"({"mesh":0})");
    const SceneDesc scene = load(b.writeEmbedded(file("ignored.gltf")));
    EXPECT_EQ(triangles(scene).size(), 2u);
    EXPECT_EQ(warningsContaining("LINES primitives are skipped"), 1u);
    EXPECT_EQ(warnings.size(), 3u);
    EXPECT_EQ(warningsContaining("textures are ignored"), 1u);
    EXPECT_EQ(warningsContaining("KHR_materials_specular is ignored"), 1u);
    for (const std::string& w : warnings) EXPECT_EQ(w.find(file("ignored.gltf").string()), 0u) << w;
}

TEST_F(GltfTest, DefaultWarningSinkPrintsWarningPrefix) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}}));
    b.addRoot(R"({"mesh":0})");
    const std::string path = b.writeEmbedded(file("stderr.gltf"));
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
    const std::string path = quadScene().writeGlb(file("truncated.glb"));
    fs::resize_file(path, fs::file_size(path) / 2);
    expectInputError(path, "glTF binary");
}

TEST_F(GltfTest, BrokenJsonThrows) {
    const std::string path =
        GltfBuilder::writeText(file("broken.gltf"), R"({"asset":{"version":"2.0"},"meshes":[{"primitives":[)");
    expectInputError(path, "parse error");
}

TEST_F(GltfTest, AccessorReadingPastTheBufferThrows) {
    GltfBuilder b;
    const int view = b.addView(kTriangle.data(), 3 * sizeof(Vec3));
    b.addAccessor(view, kFloat, 3, "VEC3", 4);  // the last vertex runs 4 bytes past the view
    b.addTriangleMesh(0);
    b.addRoot(R"({"mesh":0})");
    expectInputError(b.writeEmbedded(file("accessor.gltf")), "accessor 0 reads past the end");
}

TEST_F(GltfTest, BufferViewPastTheBufferThrows) {
    GltfBuilder b;
    b.addVec3(kTriangle);
    b.add("bufferViews", R"({"buffer":0,"byteOffset":0,"byteLength":4096})");
    b.addAccessor(1, kFloat, 3, "VEC3");
    b.addTriangleMesh(1);
    b.addRoot(R"({"mesh":0})");
    expectInputError(b.writeEmbedded(file("view.gltf")), "bufferView 1 reads past the end of buffer 0");
}

TEST_F(GltfTest, BufferIndexOutOfRangeThrows) {
    GltfBuilder b;
    b.addVec3(kTriangle);
    b.add("bufferViews", R"({"buffer":5,"byteOffset":0,"byteLength":36})");
    b.addAccessor(1, kFloat, 3, "VEC3");
    b.addTriangleMesh(1);
    b.addRoot(R"({"mesh":0})");
    expectInputError(b.writeEmbedded(file("bufferindex.gltf")), "buffer 5, which does not exist");
}

TEST_F(GltfTest, VertexIndexOutOfRangeThrows) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle), b.addIndices({0, 1, 7}, kUnsignedByte));
    b.addRoot(R"({"mesh":0})");
    expectInputError(b.writeEmbedded(file("index.gltf")), "index 7 is out of range");
}

TEST_F(GltfTest, NonFiniteBaseColorThrows) {
    GltfBuilder b;
    b.add("materials", R"({"name":"bad","pbrMetallicRoughness":{"baseColorFactor":[1e39,0.5,0.5,1]}})");
    b.addTriangleMesh(b.addVec3(kTriangle), -1, 0);
    b.addRoot(R"({"mesh":0})");
    expectInputError(b.writeEmbedded(file("nan.gltf")), "material 'bad': baseColorFactor is not finite");
}

TEST_F(GltfTest, NegativeEmissionThrows) {
    GltfBuilder b;
    b.add("materials", R"({"name":"neg","emissiveFactor":[1,-0.5,0]})");
    b.addTriangleMesh(b.addVec3(kTriangle), -1, 0);
    b.addRoot(R"({"mesh":0})");
    expectInputError(b.writeEmbedded(file("negative.gltf")), "material 'neg': emission is negative");
}

TEST_F(GltfTest, NegativeEmissiveStrengthThrows) {
    GltfBuilder b;
    b.add("materials", R"({"name":"neg","emissiveFactor":[1,1,1],
        "extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":-2}}})");
    b.addTriangleMesh(b.addVec3(kTriangle), -1, 0);
    b.addRoot(R"({"mesh":0})");
    expectInputError(b.writeEmbedded(file("strength.gltf")), "material 'neg': emissiveStrength is negative");
}

TEST_F(GltfTest, MaterialRejectedByValidateMaterialThrows) {
    GltfBuilder b;
    b.add("materials", R"({"name":"bright","pbrMetallicRoughness":{"baseColorFactor":[2,0.5,0.5,1]}})");
    b.addTriangleMesh(b.addVec3(kTriangle), -1, 0);
    b.addRoot(R"({"mesh":0})");
    expectInputError(b.writeEmbedded(file("albedo.gltf")), "material 'bright': ");
}

TEST_F(GltfTest, ZeroScaleTransformThrows) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.addRoot(R"({"scale":[1,0,1],"mesh":0})");
    expectInputError(b.writeEmbedded(file("collapse.gltf")), "collapses mesh 0");
}

TEST_F(GltfTest, UnsupportedRequiredExtensionThrows) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.addRoot(R"({"mesh":0})");
    b.topLevel = R"("extensionsUsed":["KHR_draco_mesh_compression"],"extensionsRequired":["KHR_draco_mesh_compression"])";
    expectInputError(b.writeEmbedded(file("draco.gltf")), "KHR_draco_mesh_compression");
}

TEST_F(GltfTest, SceneWithoutTrianglesThrows) {
    GltfBuilder b;
    b.addVec3(kTriangle);
    b.add("meshes", R"({"primitives":[{"attributes":{"POSITION":0},"mode":0}]})");
    b.addRoot(R"({"mesh":0})");
    expectInputError(b.writeEmbedded(file("points.gltf")), "no triangles");
}

TEST_F(GltfTest, CycleInNodeHierarchyThrows) {
    GltfBuilder b;
    b.addTriangleMesh(b.addVec3(kTriangle));
    b.addRoot(R"({"mesh":0,"children":[1]})");
    b.add("nodes", R"({"children":[0]})");
    expectInputError(b.writeEmbedded(file("cycle.gltf")), "cycle");
}

}  // namespace
}  // namespace tripath
