// The shading normal a surface vertex scatters about, bent where the mirror reflection about the
// interpolated or normal-mapped normal ns would leave below the geometric surface.
//
// A shading normal tilted away from a direction w reflects it past the geometric plane: seen at
// 45° on a normal map tilted 30° away, a smooth metal's whole lobe points into the surface, and
// the leak mask (kernels.h: sidesAgree) drops it, so glossy normal-mapped surfaces show black rims
// that the BRDF, evaluated about ns alone, does not have. As Cycles' ensure_valid_reflection
// does, the normal is tilted back toward ng, along the great circle between ns and ng, by the
// least angle that keeps the reflection of w at least kMinReflectionCosine above the plane on w's
// side. Unlike Cycles, the rule is made one for both transport directions:
//   - a walk samples about bentNormal(w) of the direction it arrived from, and a pdf toward
//     either neighbour is the pdf about the normal bent for the neighbour it is generated from,
//     so the pdfs MIS compares are those of the samplers that drew them;
//   - f_r, whichever walk or connection evaluates it, is taken about the pair's normal: of the
//     two directions' bent normals, the one nearer ng. A function of the unordered pair, it
//     keeps f_r reciprocal, and light subpaths use exactly the adjoint of the camera's BSDF.
// For a mirror reflection the two coincide (the reflected direction's own bend is never
// stronger), so a delta lobe's sampled weight is f_r about the pair's normal; for a glossy lobe
// they differ only for the few directions whose own reflection would leave the surface.
//
// Where ns and ng agree (flat geometry) or the reflection is valid already, this returns ns.
#pragma once
#include "core/vec.h"

namespace tripath {

// How far above the geometric plane (as a cosine) a bent normal keeps the reflection.
inline constexpr float kMinReflectionCosine = 0.01f;

namespace detail {
Vec3 bendTowardGeometric(Vec3 ns, Vec3 ng, Vec3 w);
}

// The shading normal for the unit direction w (away from the surface, on either side): ns if
// its mirror reflection of w leaves at least kMinReflectionCosine above the geometric plane on
// w's side (or no normal between ns and ng can achieve it: w grazes the plane); otherwise the
// normal on the great circle from ns to ng nearest ns that achieves it. On ns's side of the plane.
inline Vec3 bentNormal(Vec3 ns, Vec3 ng, Vec3 w) {
    if (ns == ng) [[likely]] return ns;  // flat shading: nothing to bend
    const float wz = dot(w, ng), nz = dot(ns, ng);
    const float reflected = 2 * dot(ns, w) * nz - wz;  // the reflection's cosine with ng
    if (wz >= 0 ? reflected >= kMinReflectionCosine : reflected <= -kMinReflectionCosine) return ns;
    return detail::bendTowardGeometric(ns, ng, w);
}

}  // namespace tripath
