// An affine map of 3-space in float, x ↦ A·x + t, kept as the columns of A and t (the layout of
// Embree's RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR). It places a mesh instance (scene_desc.h): object-
// space points, directions and normals go to world space through it and its normal transform.
#pragma once
#include "core/vec.h"

namespace tripath {

struct Affine {
    Vec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};  // the images of the axes: A's columns
    Vec3 t{0, 0, 0};                          // the translation
};

inline bool operator==(const Affine& a, const Affine& b) { return a.x == b.x && a.y == b.y && a.z == b.z && a.t == b.t; }

inline Vec3 transformVector(const Affine& a, Vec3 v) { return a.x * v.x + a.y * v.y + a.z * v.z; }
inline Vec3 transformPoint(const Affine& a, Vec3 p) { return transformVector(a, p) + a.t; }
inline float determinant(const Affine& a) { return dot(a.x, cross(a.y, a.z)); }
inline bool isFinite(const Affine& a) { return isFinite(a.x) && isFinite(a.y) && isFinite(a.z) && isFinite(a.t); }

// The linear map normals take, A's inverse transpose (translation zero): its columns are the
// cofactor columns y×z, z×x, x×y over det A, so a mirroring A keeps the normal on the side the
// object-space winding's normal maps to. Not finite when A is singular.
inline Affine normalTransform(const Affine& a) {
    const float inv = 1.0f / determinant(a);
    return {cross(a.y, a.z) * inv, cross(a.z, a.x) * inv, cross(a.x, a.y) * inv, Vec3(0.0f)};
}

}  // namespace tripath
