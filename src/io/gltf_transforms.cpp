// Node transforms in glm (gltf_transforms.h). glm supplies the types, products, determinant and
// quaternion rotation; where its own operators would add in another order or move signs of
// zero, the functions below say so and fix the order and the signs themselves.
#include "io/gltf_transforms.h"

#include <glm/gtc/matrix_access.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <vector>

namespace tripath::gltf {

namespace {

// A mesh transform collapses when |det| / (product of its column lengths) falls below this.
constexpr double kCollapseRatio = 1e-6;

glm::dvec3 toGlm(Vec3 v) { return {v.x, v.y, v.z}; }
Vec3 toVec3(glm::dvec3 v) { return {float(v.x), float(v.y), float(v.z)}; }

bool isAffine(const glm::dmat4& a) { return glm::row(a, 3) == glm::dvec4(0, 0, 0, 1); }

}  // namespace

glm::dmat4 trsMatrix(const glm::dvec3& t, const glm::dquat& r, const glm::dvec3& s) {
    glm::dmat4 m = glm::scale(glm::dmat4(glm::mat3_cast(r)), s);  // R × S: columns scaled
    m[3] = glm::dvec4(t, 1.0);                                      // T × (R × S)
    return m;
}

Affine toAffine(const glm::dmat4& a) {
    return {toVec3(glm::dvec3(a[0])), toVec3(glm::dvec3(a[1])), toVec3(glm::dvec3(a[2])), toVec3(glm::dvec3(a[3]))};
}

glm::dmat4 toDmat4(const Affine& a) {
    return {glm::dvec4(toGlm(a.x), 0), glm::dvec4(toGlm(a.y), 0), glm::dvec4(toGlm(a.z), 0), glm::dvec4(toGlm(a.t), 1)};
}

glm::dmat3 linearPart(const glm::dmat4& a) { return glm::dmat3(a); }

bool allFinite(const glm::dmat4& a) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(a[c][r])) return false;
    return true;
}

bool collapsesSpace(const glm::dmat4& a) {
    const glm::dmat3 m = linearPart(a);
    const double scale = glm::length(m[0]) * glm::length(m[1]) * glm::length(m[2]);
    return !(std::abs(glm::determinant(m)) > kCollapseRatio * scale);
}

bool mirrors(const glm::dmat4& a) { return glm::determinant(linearPart(a)) < 0; }

// parent × child, the world transform of the child. Zero entries come out as +0 whatever the
// signs of their products (x + 0 is x for any other x): a vertex coordinate at zero keeps one
// sign, and with it the tangent frames built from the triangle's normal (copysign in vec.h).
glm::dmat4 compose(const glm::dmat4& parent, const glm::dmat4& child) {
    return parent * child + glm::dmat4(0.0);
}

// The linear part, then the translation: ((a x + b y) + c z) + t, where glm's dmat4 × dvec4 would
// add in pairs, (a x + b y) + (c z + t), and round differently.
Vec3 transformPoint(const glm::dmat4& a, Vec3 p) {
    return toVec3(linearPart(a) * toGlm(p) + glm::dvec3(a[3]));
}

Vec3 transformDirection(const glm::dmat3& m, Vec3 v) {
    const glm::dvec3 d = m * toGlm(v);
    const double len = glm::length(d);
    if (!(len > 0) || !std::isfinite(len)) return Vec3(0.0f);
    return toVec3(d / len);
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

glm::dmat4 localTransform(const tinygltf::Node& node, int index, const Report& report) {
    const std::string what = "node " + std::to_string(index);
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16) report.fail(what + " matrix does not have 16 entries");
        if (!allFinite(node.matrix)) report.fail(what + " has a non-finite matrix");
        const glm::dmat4 m = glm::make_mat4(node.matrix.data());
        if (!isAffine(m)) report.fail(what + " matrix is not affine (last row must be 0 0 0 1)");
        return m;
    }
    const std::vector<double> t = node.translation.empty() ? std::vector<double>{0, 0, 0} : node.translation;
    const std::vector<double> q = node.rotation.empty() ? std::vector<double>{0, 0, 0, 1} : node.rotation;
    const std::vector<double> s = node.scale.empty() ? std::vector<double>{1, 1, 1} : node.scale;
    if (t.size() != 3 || q.size() != 4 || s.size() != 3) report.fail(what + " has a malformed translation, rotation or scale");
    if (!allFinite(t) || !allFinite(q) || !allFinite(s)) report.fail(what + " has a non-finite translation, rotation or scale");
    const glm::dquat rotation(q[3], q[0], q[1], q[2]);  // glTF stores (x, y, z, w); glm takes w first
    if (!(glm::length(rotation) > 0)) report.fail(what + " rotation quaternion has zero length");
    return trsMatrix(glm::make_vec3(t.data()), glm::normalize(rotation), glm::make_vec3(s.data()));
}

}  // namespace tripath::gltf
