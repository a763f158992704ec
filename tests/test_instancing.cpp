// glTF instancing, end to end: one mesh placed by several nodes, and the same copies as
// EXT_mesh_gpu_instancing, against the same geometry written out flattened (each copy's vertices
// and normals transformed here, in double, by the glTF rules written out longhand: T × R × S with
// the rotation as a quaternion, normals by R × S⁻¹, the winding reversed by a mirroring copy).
// The copies have non-uniform scales, arbitrary rotations, a mirror and a parent node with a
// transform of its own, so a lost copy, a TRS or parent/instance product in the wrong order or
// normals through the wrong matrix each move hits. Also: the scene stores the instanced mesh once,
// an export writes it once and loads back the same, and bad instancing data is refused.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "geometry/scene.h"
#include "io/gltf_loader.h"
#include "io/gltf_model.h"
#include "io/gltf_writer.h"
#include "scenes/scene_builder.h"
#include "shell_test.h"
#include "support.h"

namespace tripath {
namespace {

namespace fs = std::filesystem;

// ---- transforms, longhand, in double ------------------------------------------------------------

struct D3 {
    double x, y, z;
};
D3 operator+(D3 a, D3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
D3 operator*(D3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
D3 cross(D3 a, D3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
D3 unit(D3 a) { return a * (1.0 / std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z)); }
D3 d3(Vec3 v) { return {v.x, v.y, v.z}; }
Vec3 f3(D3 v) { return {float(v.x), float(v.y), float(v.z)}; }

struct Trs {
    std::array<double, 3> t;
    std::array<double, 4> q;  // x y z w, normalised where used
    std::array<double, 3> s;
};

// v rotated by unit quaternion (u, w): v + 2w (u × v) + 2 u × (u × v).
D3 rotate(const Trs& m, D3 v) {
    const double n = std::sqrt(m.q[0] * m.q[0] + m.q[1] * m.q[1] + m.q[2] * m.q[2] + m.q[3] * m.q[3]);
    const D3 u{m.q[0] / n, m.q[1] / n, m.q[2] / n};
    const double w = m.q[3] / n;
    return v + cross(u, v) * (2 * w) + cross(u, cross(u, v)) * 2;
}
D3 point(const Trs& m, D3 p) { return rotate(m, {p.x * m.s[0], p.y * m.s[1], p.z * m.s[2]}) + D3{m.t[0], m.t[1], m.t[2]}; }
D3 normal(const Trs& m, D3 n) { return rotate(m, {n.x / m.s[0], n.y / m.s[1], n.z / m.s[2]}); }
bool mirrors(const Trs& m) { return m.s[0] * m.s[1] * m.s[2] < 0; }

// The parent node of every copy, and the copies' own transforms (one mirrors, all scale unevenly).
const Trs kParent{{0.25, -0.5, 0.125}, {0, 0.2588190451, 0, 0.9659258263}, {1.0, 1.5, 0.75}};
const std::vector<Trs> kCopies = {
    {{-1.1, 0.4, -0.3}, {0.1, 0.7, 0.2, 0.6}, {0.5, 0.25, 0.4}},
    {{0.9, 0.35, 0.2}, {-0.3, 0.1, 0.8, 0.5}, {0.3, 0.6, 0.3}},
    {{-0.1, 0.3, 0.7}, {0, 0, 0, 1}, {-0.45, 0.3, 0.3}},
    {{0.2, 0.5, -0.9}, {0.5, 0.5, 0.5, 0.5}, {0.2, 0.2, 0.7}},
};

// ---- the scene ----------------------------------------------------------------------------------

// A floor, an area light and an octahedron with smooth normals (the mesh that is copied).
struct Geometry {
    std::vector<Vec3> positions, normals;
    std::vector<uint32_t> indices;
};

Geometry octahedron() {
    Geometry g;
    g.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    g.normals = g.positions;
    g.indices = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
    return g;
}

const Geometry kFloor{{{-3, 0, -3}, {-3, 0, 3}, {3, 0, 3}, {3, 0, -3}}, {}, {0, 1, 2, 0, 2, 3}};
const Geometry kLight{{{-0.5, 2.5, -0.5}, {0.5, 2.5, -0.5}, {0.5, 2.5, 0.5}, {-0.5, 2.5, 0.5}}, {}, {0, 1, 2, 0, 2, 3}};

enum class Form { Nodes, Extension, Flat };

class Document {
public:
    int mesh(const Geometry& g, int material) {
        tinygltf::Primitive p;
        p.attributes["POSITION"] = floats(g.positions.data(), g.positions.size(), TINYGLTF_TYPE_VEC3);
        if (!g.normals.empty()) p.attributes["NORMAL"] = floats(g.normals.data(), g.normals.size(), TINYGLTF_TYPE_VEC3);
        p.indices = appendAccessor(model, appendBufferView(model, g.indices.data(), 4 * g.indices.size()),
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, g.indices.size(), TINYGLTF_TYPE_SCALAR);
        p.material = material;
        p.mode = TINYGLTF_MODE_TRIANGLES;
        model.meshes.emplace_back().primitives = {p};
        return int(model.meshes.size()) - 1;
    }
    int floats(const void* data, size_t count, int type) {
        const size_t n = type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
        return appendAccessor(model, appendBufferView(model, data, count * n * sizeof(float)),
                              TINYGLTF_COMPONENT_TYPE_FLOAT, count, type);
    }
    int node(int mesh, const Trs* trs = nullptr) {
        tinygltf::Node n;
        n.mesh = mesh;
        if (trs) {
            n.translation.assign(trs->t.begin(), trs->t.end());
            n.rotation.assign(trs->q.begin(), trs->q.end());
            n.scale.assign(trs->s.begin(), trs->s.end());
        }
        model.nodes.push_back(n);
        return int(model.nodes.size()) - 1;
    }
    std::string write(const fs::path& file) {
        model.scenes.emplace_back().nodes = roots;
        model.defaultScene = 0;
        writeGltfModel(model, file.string());
        return file.string();
    }

    tinygltf::Model model;
    std::vector<int> roots;
};

tinygltf::Material material(const char* name, std::vector<double> color, std::vector<double> emission = {0, 0, 0}) {
    tinygltf::Material m;
    m.name = name;
    m.pbrMetallicRoughness.baseColorFactor = {color[0], color[1], color[2], 1};
    m.pbrMetallicRoughness.metallicFactor = 0;
    m.pbrMetallicRoughness.roughnessFactor = 1;
    m.emissiveFactor = std::move(emission);
    return m;
}

// Copy i of `g` in world space (parent × copy), written out.
Geometry flattened(const Geometry& g, const Trs& copy) {
    Geometry out = g;
    for (Vec3& p : out.positions) p = f3(point(kParent, point(copy, d3(p))));
    for (Vec3& n : out.normals) n = f3(unit(normal(kParent, normal(copy, d3(n)))));
    if (mirrors(copy) != mirrors(kParent))
        for (size_t i = 0; i < out.indices.size(); i += 3) std::swap(out.indices[i + 1], out.indices[i + 2]);
    return out;
}

// The test scene as a glTF file, its copies in the given form; the camera looks down at them.
std::string writeScene(Form form, const fs::path& file, const std::vector<Trs>& copies = kCopies) {
    Document d;
    d.model.materials = {material("floor", {0.8, 0.8, 0.8}), material("copy", {0.3, 0.5, 0.7}),
                         material("light", {0, 0, 0}, {1, 1, 1})};
    d.roots.push_back(d.node(d.mesh(kFloor, 0)));
    d.roots.push_back(d.node(d.mesh(kLight, 2)));
    const Geometry shape = octahedron();
    if (form == Form::Flat) {
        for (const Trs& c : copies) d.roots.push_back(d.node(d.mesh(flattened(shape, c), 1)));
    } else {
        const int mesh = d.mesh(shape, 1);
        const int parent = d.node(-1, &kParent);
        d.roots.push_back(parent);
        if (form == Form::Nodes) {
            for (const Trs& c : copies) {
                const int child = d.node(mesh, &c);
                d.model.nodes[size_t(parent)].children.push_back(child);
            }
        } else {
            std::vector<float> t, r, s;
            for (const Trs& c : copies) {
                t.insert(t.end(), c.t.begin(), c.t.end());
                r.insert(r.end(), c.q.begin(), c.q.end());
                s.insert(s.end(), c.s.begin(), c.s.end());
            }
            d.model.nodes[size_t(parent)].mesh = mesh;
            tinygltf::Value::Object attributes{
                {"TRANSLATION", tinygltf::Value(d.floats(t.data(), copies.size(), TINYGLTF_TYPE_VEC3))},
                {"ROTATION", tinygltf::Value(d.floats(r.data(), copies.size(), TINYGLTF_TYPE_VEC4))},
                {"SCALE", tinygltf::Value(d.floats(s.data(), copies.size(), TINYGLTF_TYPE_VEC3))}};
            setExtension(d.model.nodes[size_t(parent)].extensions, "EXT_mesh_gpu_instancing", "attributes",
                         tinygltf::Value(std::move(attributes)));
            d.model.extensionsUsed = {"EXT_mesh_gpu_instancing"};
        }
    }
    tinygltf::Camera camera;
    camera.type = "perspective";
    camera.perspective.yfov = 0.9;
    camera.perspective.znear = 0.01;
    d.model.cameras = {camera};
    tinygltf::Node eye;
    eye.camera = 0;
    eye.translation = {0, 2.2, 3.2};
    eye.rotation = {-0.2588190451, 0, 0, 0.9659258263};  // 30° down
    d.model.nodes.push_back(eye);
    d.roots.push_back(int(d.model.nodes.size()) - 1);
    return d.write(file);
}

class Instancing : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
               ("tripath_instancing_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) +
                "_" + std::to_string(std::random_device{}()));
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }
    fs::path file(const std::string& name) const { return dir_ / name; }
    SceneDesc load(Form form) {
        const char* names[] = {"nodes.gltf", "extension.gltf", "flat.gltf"};
        return loadGltf(writeScene(form, file(names[int(form)])), nullptr);
    }

    fs::path dir_;
};

constexpr int kSize = 48;

// For a ray from the camera through each flattened triangle's centroid: the same surface, point
// and normals in both scenes (to float rounding of unit-sized coordinates).
void expectSameHits(const Scene& flat, const Scene& instanced) {
    int compared = 0;
    for (const Triangle& t : flat.triangles()) {
        const Vec3 origin = flat.camera().position();
        const Vec3 dir = normalize((t.p[0] + t.p[1] + t.p[2]) * (1.0f / 3) - origin);
        const auto a = flat.intersect(origin, dir), b = instanced.intersect(origin, dir);
        ASSERT_EQ(a.has_value(), b.has_value());
        if (!a) continue;
        ++compared;
        EXPECT_EQ(flat.materialOf(a->triangle).name, instanced.materialOf(b->triangle).name);
        EXPECT_NEAR(a->t, b->t, 1e-5f);
        EXPECT_LT(length(a->p - b->p), 1e-5f);
        EXPECT_LT(length(a->ng - b->ng), 1e-5f) << "geometric normal";
        EXPECT_LT(length(a->ns - b->ns), 1e-5f) << "shading normal";
    }
    EXPECT_GT(compared, 20);
}

// Relative L1 difference of two renders with the same seed.
double imageDifference(const Scene& a, const Scene& b, const std::string& integrator) {
    RenderRequest r = test::smallRequest();
    r.integrator = integrator;
    r.width = r.height = kSize;
    r.spp = 8;
    const Image ia = test::renderScene(a, r).film.image(r.spp), ib = test::renderScene(b, r).film.image(r.spp);
    double diff = 0, total = 0;
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x)
            for (int c = 0; c < 3; ++c) {
                diff += std::abs(double(ia.at(x, y)[c]) - ib.at(x, y)[c]);
                total += ia.at(x, y)[c];
            }
    return diff / total;
}

TEST_F(Instancing, NodesAndExtensionRenderAsTheFlattenedCopies) {
    const Scene flat(load(Form::Flat), kSize, kSize);
    for (Form form : {Form::Nodes, Form::Extension}) {
        SCOPED_TRACE(form == Form::Nodes ? "nodes" : "EXT_mesh_gpu_instancing");
        const Scene instanced(load(form), kSize, kSize);
        expectSameHits(flat, instanced);
        EXPECT_EQ(instanced.boundsMin(), flat.boundsMin());
        EXPECT_EQ(instanced.boundsMax(), flat.boundsMax());
        // Float rounding alone leaves ~1e-8 (measured); one sample of the 18432 going another way
        // at a discontinuity would leave ~5e-5; a lost or misplaced copy, far more. mlt too: with
        // the same seed its chains propose the same points and, their targets agreeing to
        // rounding, accept the same ones (2e-8 measured). One decision flipped by rounding (a
        // uniform number within ~1e-7 of its threshold: about one chance in 10^3 over the 18432
        // steps) would send a chain of 18 steps elsewhere, ~1e-3 of the image.
        for (const char* integrator : {"pt", "mlt"})
            EXPECT_LT(imageDifference(flat, instanced, integrator), 1e-4) << integrator;
    }
}

TEST_F(Instancing, TheSceneStoresTheInstancedMeshOnce) {
    const size_t unique = 2 + 2 + octahedron().indices.size() / 3;  // floor, light, one octahedron
    EXPECT_EQ(Scene(load(Form::Flat), kSize, kSize).triangles().size(), 4 + 8 * kCopies.size());
    for (Form form : {Form::Nodes, Form::Extension}) {
        const SceneDesc desc = load(form);
        EXPECT_EQ(desc.meshes.size(), 3u);
        EXPECT_EQ(Scene(desc, kSize, kSize).triangles().size(), unique);
    }
}

// An emissive mesh's copies are placed in world space (the emitters sample world-space
// triangles): each copy is an emitter of its own area.
TEST_F(Instancing, EmissiveCopiesAreEmittersEach) {
    SceneDesc desc = load(Form::Nodes);
    for (MeshDesc& m : desc.meshes)
        if (m.name.find("light") == std::string::npos && m.material == 1) m.material = 2;
    const Scene scene(desc, kSize, kSize);
    double area = 0;
    for (const Emitter& e : scene.emitters().all()) area += e.area;
    const Scene flat(load(Form::Flat), kSize, kSize);
    double expected = 0;
    for (const Triangle& t : flat.triangles())
        if (flat.materials()[size_t(t.material)].name != "floor") expected += t.area();
    EXPECT_NEAR(area, expected, 1e-5 * expected);
}

// The same meshes and instances; normals within 1e-6, the loader normalising them again.
void expectSameDesc(const SceneDesc& a, const SceneDesc& b) {
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (size_t i = 0; i < a.meshes.size(); ++i) {
        EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions);
        ASSERT_EQ(a.meshes[i].normals.size(), b.meshes[i].normals.size());
        for (size_t k = 0; k < a.meshes[i].normals.size(); ++k)
            ASSERT_NEAR(length(a.meshes[i].normals[k] - b.meshes[i].normals[k]), 0.0f, 1e-6f) << "mesh " << i;
        EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices);
        EXPECT_EQ(a.meshes[i].material, b.meshes[i].material);
    }
    ASSERT_EQ(a.instances.size(), b.instances.size());
    for (size_t i = 0; i < a.instances.size(); ++i) {
        EXPECT_EQ(a.instances[i].mesh, b.instances[i].mesh);
        EXPECT_TRUE(a.instances[i].toWorld == b.instances[i].toWorld);
        EXPECT_TRUE(a.instances[i].trs == b.instances[i].trs);
        EXPECT_TRUE(a.instances[i].parent == b.instances[i].parent);
    }
}

std::string slurp(const fs::path& file) {
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST_F(Instancing, ExportWritesTheMeshOnceAndLoadsBackTheSame) {
    for (Form form : {Form::Nodes, Form::Extension}) {
        const SceneDesc desc = load(form);
        const fs::path out = file("exported.gltf");
        writeGltf(desc, out.string(), nullptr);
        expectSameDesc(desc, loadGltf(out.string(), nullptr));
        const bool extension = slurp(out).find("EXT_mesh_gpu_instancing") != std::string::npos;
        EXPECT_EQ(extension, form == Form::Extension);
    }
}

// What a .gltf takes on disk: the file and the .bin beside it.
uintmax_t gltfBytes(const fs::path& file) {
    const fs::path bin = binBeside(file.string());
    return fs::file_size(file) + (fs::exists(bin) ? fs::file_size(bin) : 0);
}

Geometry sphere(int rings) {
    SceneDesc s;
    s.materials.push_back(Material{});
    build::addSphere(s, "sphere", 0, Vec3(0.0f), 1.0f, rings, false, false);
    return {s.meshes[0].positions, s.meshes[0].normals, s.meshes[0].indices};
}

// A mesh of 2000 triangles placed 60 times: the source holds it once, and so must the export.
TEST_F(Instancing, ExportOfAnInstancedModelStaysUnderTwiceTheSource) {
    std::vector<Trs> copies;
    for (int i = 0; i < 60; ++i) copies.push_back({{i * 0.1, 0, 0}, {0, 0, 0, 1}, {1, 1, 1}});
    Document d;
    d.model.materials = {material("m", {0.5, 0.5, 0.5})};
    const int mesh = d.mesh(sphere(32), 0);
    for (const Trs& c : copies) d.roots.push_back(d.node(mesh, &c));
    const std::string source = d.write(file("source.gltf"));
    const fs::path out = file("exported.gltf");
    writeGltf(loadGltf(source, nullptr), out.string(), nullptr);
    EXPECT_LT(gltfBytes(out), 2 * gltfBytes(source)) << gltfBytes(out) << " vs " << gltfBytes(source);
    const std::string extSource = writeScene(Form::Extension, file("ext.gltf"));
    writeGltf(loadGltf(extSource, nullptr), out.string(), nullptr);
    EXPECT_LT(gltfBytes(out), 2 * gltfBytes(extSource));
}

// One sphere's accessors read by a mesh per material, each mesh placed once (as in Khronos'
// MetalRoughSpheresNoTextures): the file holds the sphere once, and so must the export, which
// loads back the same.
TEST_F(Instancing, MeshesSharingTheirAccessorsAreExportedOnce) {
    const Geometry shape = sphere(64);
    auto sizes = [&](int copies) {
        Document d;
        const int first = d.mesh(shape, 0);
        for (int i = 0; i < copies; ++i) {
            d.model.materials.push_back(material("m", {0.1 + 0.8 * i / copies, 0.5, 0.5}));
            if (i > 0) {
                d.model.meshes.push_back(d.model.meshes[size_t(first)]);
                d.model.meshes.back().primitives[0].material = i;
            }
            const Trs at{{2.5 * i, 0.5, 0}, {0, 0, 0, 1}, {1, 1, 1}};
            d.roots.push_back(d.node(int(d.model.meshes.size()) - 1, &at));
        }
        const std::string source = d.write(file("shared-" + std::to_string(copies) + ".gltf"));
        const SceneDesc loaded = loadGltf(source, nullptr);
        const fs::path out = file("exported-" + std::to_string(copies) + ".gltf");
        writeGltf(loaded, out.string(), nullptr);
        expectSameDesc(loaded, loadGltf(out.string(), nullptr));
        return std::pair{gltfBytes(source), gltfBytes(out)};
    };
    const auto [oneSource, one] = sizes(1);
    const auto [source, many] = sizes(24);
    // A further copy adds a material, a mesh and a node to the JSON, and no array: the 23 of them
    // add less than one copy of the sphere's arrays (float positions and normals, short indices).
    const size_t arrays = 12 * (shape.positions.size() + shape.normals.size()) + 2 * shape.indices.size();
    EXPECT_LT(many - one, arrays) << one << " bytes for one copy, " << many << " for 24";
    EXPECT_LT(many, 2 * source) << source << " bytes in the source";
}

// Copies of a mesh in world space at different places (no instances): each writes its own
// positions, but the normals and indices they have in common once.
TEST_F(Instancing, ArraysTheSceneRepeatsAreWrittenOnce) {
    const Geometry shape = sphere(64);
    auto exported = [&](int copies) {
        SceneDesc d;
        d.name = "copies";
        d.materials.push_back(Material{});
        for (int i = 0; i < copies; ++i) {
            MeshDesc m{"copy", shape.positions, shape.normals, shape.indices, 0};
            for (Vec3& p : m.positions) p = p + Vec3(2.5f * float(i), 0, 0);
            d.meshes.push_back(m);
        }
        // Written once so that the loader drops the sphere's degenerate triangles at its poles, then again.
        const fs::path first = file("copies-" + std::to_string(copies) + ".gltf");
        writeGltf(d, first.string(), nullptr);
        const SceneDesc loaded = loadGltf(first.string(), nullptr);
        const fs::path out = file("copies-again-" + std::to_string(copies) + ".gltf");
        writeGltf(loaded, out.string(), nullptr);
        expectSameDesc(loaded, loadGltf(out.string(), nullptr));
        return gltfBytes(out);
    };
    const uintmax_t one = exported(1), many = exported(24);
    // Each further copy adds its positions and a mesh and a node to the JSON, which is less than
    // its positions and normals.
    const size_t positionsAndNormals = 12 * (shape.positions.size() + shape.normals.size());
    EXPECT_LT(many - one, 23 * positionsAndNormals) << one << " bytes for one copy, " << many << " for 24";
}

// ---- bad instancing data -------------------------------------------------------------------------

// The extension document with one attribute's accessor replaced by `values` (count elements of `type`).
std::string withAttribute(const fs::path& file, const char* attribute, const std::vector<float>& values, size_t count,
                          int type, int componentType = TINYGLTF_COMPONENT_TYPE_FLOAT) {
    tinygltf::Model model;
    tinygltf::TinyGLTF reader;
    std::string err, warn;
    EXPECT_TRUE(reader.LoadASCIIFromFile(&model, &err, &warn, writeScene(Form::Extension, file)));
    for (tinygltf::Node& n : model.nodes) {
        const auto ext = n.extensions.find("EXT_mesh_gpu_instancing");
        if (ext == n.extensions.end()) continue;
        auto attributes = ext->second.Get("attributes").Get<tinygltf::Value::Object>();
        const int view = appendBufferView(model, values.data(), values.size() * sizeof(float));
        attributes[attribute] = tinygltf::Value(appendAccessor(model, view, componentType, count, type));
        setExtension(n.extensions, "EXT_mesh_gpu_instancing", "attributes", tinygltf::Value(std::move(attributes)));
    }
    writeGltfModel(model, file.string());
    return file.string();
}

void expectRefused(const std::string& path, const std::string& fragment) {
    try {
        loadGltf(path, nullptr);
        ADD_FAILURE() << "no InputError (expected one containing '" << fragment << "')";
    } catch (const InputError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(fragment), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST_F(Instancing, BadInstancingDataIsRefusedInOneLine) {
    const std::vector<float> three(9, 0.5f);
    expectRefused(withAttribute(file("count.gltf"), "SCALE", three, 3, TINYGLTF_TYPE_VEC3), "accessors disagree");
    std::vector<float> translations(3 * kCopies.size(), 0.0f);
    translations[4] = std::numeric_limits<float>::infinity();
    expectRefused(withAttribute(file("inf.gltf"), "TRANSLATION", translations, kCopies.size(), TINYGLTF_TYPE_VEC3),
                  "non-finite");
    std::vector<float> scales(3 * kCopies.size(), 1.0f);
    scales[7] = 0;
    expectRefused(withAttribute(file("zero.gltf"), "SCALE", scales, kCopies.size(), TINYGLTF_TYPE_VEC3), "has a zero scale");
    const std::vector<float> zeroRotations(4 * kCopies.size(), 0.0f);
    expectRefused(withAttribute(file("q.gltf"), "ROTATION", zeroRotations, kCopies.size(), TINYGLTF_TYPE_VEC4),
                  "zero length");
    expectRefused(withAttribute(file("type.gltf"), "ROTATION", std::vector<float>(4 * kCopies.size(), 0.5f),
                                kCopies.size(), TINYGLTF_TYPE_VEC3),
                  "is not float VEC4");
}

class InstancingCli : public test::ShellTest {};

TEST_F(InstancingCli, BadInstancingDataExitsWithOneLine) {
    std::vector<float> scales(3 * kCopies.size(), 1.0f);
    scales[1] = 0;
    const std::string scene = withAttribute(path("bad.gltf"), "SCALE", scales, kCopies.size(), TINYGLTF_TYPE_VEC3);
    const Outcome o = shell("'" TRIPATH_BINARY "' render --scene '" + scene + "' --spp 1 --width 8 --height 8 --out '" +
                            path("x.exr") + "'");
    EXPECT_EQ(o.exitCode, 1) << o.err;
    EXPECT_NE(o.err.find("has a zero scale"), std::string::npos) << o.err;
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
    EXPECT_FALSE(fs::exists(path("x.exr")));
}

}  // namespace
}  // namespace tripath
