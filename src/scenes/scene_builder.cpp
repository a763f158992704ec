#include "scenes/scene_builder.h"

#include <cmath>

namespace tripath::build {

int addMaterial(SceneDesc& s, Material m) {
    s.materials.push_back(std::move(m));
    return static_cast<int>(s.materials.size()) - 1;
}

Material lambertian(const char* name, Spectrum albedo) {
    Material m;
    m.name = name;
    m.type = MaterialType::Lambertian;
    m.albedo = albedo;
    return m;
}

Material emitter(const char* name, Spectrum radiance) {
    Material m = lambertian(name, Spectrum(0.0f));
    m.emission = radiance;
    return m;
}

Material glass(const char* name) {
    Material m;
    m.name = name;
    m.type = MaterialType::Dielectric;
    m.albedo = Spectrum(1.0f);
    m.ior = 1.5f;
    return m;
}

void addQuad(SceneDesc& s, const char* name, int material, Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    s.meshes.push_back(MeshDesc{name, {a, b, c, d}, {}, {0, 1, 2, 0, 2, 3}, material});
}

void addSquare(SceneDesc& s, const char* name, int material, Vec3 c, Vec3 n, float half) {
    const Vec3 helper = std::abs(n.y) < 0.9f ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
    const Vec3 u = normalize(cross(helper, n)) * half;  // u × v = n: counter-clockwise from the front
    const Vec3 v = cross(n, u);
    addQuad(s, name, material, c - u - v, c + u - v, c + u + v, c - u + v);
}

void addBox(SceneDesc& s, const char* name, int material, Vec3 lo, Vec3 hi, float angle, Vec3 pivot) {
    const float c = std::cos(angle), sn = std::sin(angle);
    MeshDesc m{name, {}, {}, {}, material};
    for (int i = 0; i < 8; ++i) {
        const Vec3 p(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        if (angle == 0) {
            m.positions.push_back(p);
        } else {
            const Vec3 d = p - pivot;
            m.positions.push_back(pivot + Vec3(c * d.x + sn * d.z, d.y, -sn * d.x + c * d.z));
        }
    }
    // Corner i has bit 0 = +x, bit 1 = +y, bit 2 = +z; each face listed counter-clockwise from outside.
    const uint32_t faces[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3}, {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
    for (const auto& f : faces)
        for (uint32_t k : {f[0], f[1], f[2], f[0], f[2], f[3]}) m.indices.push_back(k);
    s.meshes.push_back(std::move(m));
}

void addSphere(SceneDesc& s, const char* name, int material, Vec3 centre, float radius, int rings, bool inward,
               bool flat) {
    MeshDesc m{name, {}, {}, {}, material};
    const int segments = 2 * rings;
    for (int i = 0; i <= rings; ++i) {
        const float theta = kPi * i / rings;
        for (int j = 0; j <= segments; ++j) {
            const float phi = 2.0f * kPi * j / segments;
            const Vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
            m.positions.push_back(centre + n * radius);
            if (!flat) m.normals.push_back(inward ? -n : n);
        }
    }
    auto at = [&](int i, int j) { return static_cast<uint32_t>(i * (segments + 1) + j); };
    auto triangle = [&](uint32_t p, uint32_t q, uint32_t r) {
        if (inward) std::swap(p, r);
        m.indices.insert(m.indices.end(), {p, q, r});
    };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            // Outward winding is (i,j) (i+1,j+1) (i+1,j); at the poles one triangle of each quad
            // has zero area and is left out.
            const uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            if (i != rings - 1) triangle(a, c, b);
            if (i != 0) triangle(a, d, c);
        }
    s.meshes.push_back(std::move(m));
}

CameraDesc lookAt(Vec3 from, Vec3 to, float yfov) {
    CameraDesc c;
    c.present = true;
    c.position = from;
    c.forward = normalize(to - from);
    c.up = normalize(cross(cross(c.forward, Vec3(0, 1, 0)), c.forward));
    c.yfov = yfov;
    return c;
}

}  // namespace tripath::build
