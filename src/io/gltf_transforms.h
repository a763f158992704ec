// Node transforms of the glTF loader, in glm's double precision: a node's own transform
// (node.matrix, or translation × rotation × scale), their composition down the node hierarchy,
// and what meshes, cameras and lights take from the result. The sums run in a fixed order and
// zero components keep their sign, which the tangent frames built around normals see
// (gltf_transforms.cpp says where glm's own order would differ). A header of
// the io library's own (the loader's interface is gltf_loader.h).
#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <tiny_gltf.h>

#include "geometry/affine.h"
#include "io/gltf_checks.h"
#include "core/vec.h"

namespace tripath::gltf {

// Column-major like glTF's node.matrix: (row r, column c) is m[c][r]; affine (last row 0 0 0 1).

// Node `index`'s own transform: its matrix, or T × R × S from its translation, rotation (a
// quaternion, normalised here) and scale, glTF's defaults filling what is absent. Fails on a
// malformed, non-finite or non-affine transform or a zero quaternion.
glm::dmat4 localTransform(const tinygltf::Node& node, int index, const Report& report);

// T × R × S from a translation, a unit quaternion and a scale (checked by the caller).
glm::dmat4 trsMatrix(const glm::dvec3& t, const glm::dquat& r, const glm::dvec3& s);

// parent × child: the world transform of a child node.
glm::dmat4 compose(const glm::dmat4& parent, const glm::dmat4& child);

// The upper 3×3: the linear part that directions, normals and the winding see.
glm::dmat3 linearPart(const glm::dmat4& a);

bool allFinite(const glm::dmat4& a);

// True when the upper 3×3 squashes space onto a plane, line or point (or is not finite).
bool collapsesSpace(const glm::dmat4& a);

// True for a mirroring transform (negative determinant), which reverses the triangles' winding.
bool mirrors(const glm::dmat4& a);

Vec3 transformPoint(const glm::dmat4& a, Vec3 p);

// The transform in float, as an instance keeps it (scene_desc.h), and back.
Affine toAffine(const glm::dmat4& a);
glm::dmat4 toDmat4(const Affine& a);

// Unit direction of m × v; zero vector when it vanishes or is not finite.
Vec3 transformDirection(const glm::dmat3& m, Vec3 v);

// The matrix that takes normals: the inverse transpose of m.
glm::dmat3 normalMatrix(const glm::dmat3& m);

}  // namespace tripath::gltf
