// The oracle: the kernels of the three-point form (DESIGN.md §1, seeds/000 §2–4) evaluated
// literally, one function of points per kernel, and their product f(x̄) for a whole path.
//
//   g(x, x')            = V(x, x') / |x − x'|²                              [1/m²]
//   ε(x0 → x1)          = Le(x0 → x1) |cos θ0| |cos θ1|                     [W/m²]
//   ρ(x″ → x′ → x)      = f_r(x″ → x′ → x) |cos θ′| |cos θ|                 [1]
//   W(x_{k−1} → x_k)    = sensor importance of the last segment
//   f(x̄) = ε(x0→x1) g(x0,x1) · Π_{i=1}^{k−1} ρ(x_{i−1}→x_i→x_{i+1}) g(x_i,x_{i+1}) · W(x_{k−1}→x_k)
//
// No render calls these: the walks and connections evaluate the same product regrouped by vertex
// (paths/kernels.h). The tests check the renderer's estimates against f(x̄)/p from here, and
// bench/ times each kernel on its own.
#pragma once
#include <vector>

#include "paths/vertex.h"

namespace tripath {

// Squared distance, guarded: coincident vertices give +inf for 1/r², never NaN.
float inverseSquaredDistance(const Vertex& a, const Vertex& b);
// G(a,b) = |cos θa| |cos θb| / |a − b|², without visibility.
float geometricFactor(const Vertex& a, const Vertex& b);

// g(x, x') = V / r².
float g(const Scene& scene, const Vertex& x, const Vertex& xp);
// ε(x0 → x1) = Le(x0 → x1) |cos θ0| |cos θ1|.
Spectrum emittance(const Scene& scene, const Vertex& x0, const Vertex& x1);
// ρ(x″ → x′ → x) = f_r · |cos θ′| |cos θ| (outgoing segment x′–x), with the shading correction.
Spectrum rho(const Scene& scene, const Vertex& xpp, const Vertex& xp, const Vertex& x);
// W(x_{k−1} → x_k): the sensor importance of the pixel the segment passes through.
float W(const Scene& scene, const Vertex& xkm1, const Vertex& xk);

// The per-vertex factor of the regrouped product, from the neighbours' positions:
// LocalScattering(v, directions to the two).value(). An endpoint has no neighbour on one side.
Spectrum scatter(const Scene& scene, const Vertex& v, const Vertex* towardLight, const Vertex* towardCamera);

// Solid-angle pdf at `from` → area pdf at `to`: p_A = p_ω |cos θ_to| / r².
float toAreaPdf(float pdfOmega, const Vertex& from, const Vertex& to);

// f(x̄) for a whole path x0 … xk (x0 emitter, xk sensor), the product of the kernels above.
Spectrum pathContribution(const Scene& scene, const std::vector<Vertex>& path);

}  // namespace tripath
