// The bend of a shading normal toward the geometric one (shading_normal.h).
//
// In the plane of ng and ns, with z = ng and x the unit component of ns across it (both turned to
// w's side), a normal tilted by φ from z is (sin φ, 0, cos φ), and the mirror reflection of w
// about it has the cosine with z
//     R_z(φ) = 2 (w·N) cos φ − w_z = w_x sin 2φ + w_z cos 2φ = A cos(2φ − δ),
// A = √(w_x² + w_z²), δ = atan2(w_x, w_z). R_z(φ) ≥ τ holds on |2φ − δ| ≤ acos(τ / A), an interval
// holding φ = 0 when w_z ≥ τ; its upper end is the tilt nearest ns that keeps the reflection up.
#include "paths/shading_normal.h"

#include <algorithm>
#include <cmath>

namespace tripath::detail {

Vec3 bendTowardGeometric(Vec3 ns, Vec3 ng, Vec3 w) {
    const float side = dot(w, ng) >= 0 ? 1.0f : -1.0f;
    const Vec3 z = ng * side, n = ns * side;
    const float wz = dot(w, z);
    if (!(wz >= kMinReflectionCosine)) return ns;  // grazing: no tilt keeps the reflection up
    const Vec3 across = n - z * dot(n, z);
    const float sinAlpha = length(across);
    if (!(sinAlpha > 1e-6f)) return ns;
    const Vec3 x = across / sinAlpha;
    const float alpha = std::atan2(sinAlpha, dot(n, z));
    const float wx = dot(w, x);
    const float amplitude = std::sqrt(wx * wx + wz * wz);
    const float phi = 0.5f * (std::atan2(wx, wz) + std::acos(std::min(1.0f, kMinReflectionCosine / amplitude)));
    const float tilt = std::clamp(phi, 0.0f, alpha);
    return normalize(x * std::sin(tilt) + z * std::cos(tilt)) * side;
}

}  // namespace tripath::detail
