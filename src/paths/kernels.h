// The kernels of the three-point form (DESIGN.md §1, seeds/000 §2–4), as functions of points.
//
//   g(x, x')            = V(x, x') / |x − x'|²                              [1/m²]
//   ε(x0 → x1)          = Le(x0 → x1) |cos θ0| |cos θ1|                     [W/m²]
//   ρ(x″ → x′ → x)      = f_r(x″ → x′ → x) |cos θ′| |cos θ|                 [1]
//   W(x_{k−1} → x_k)    = sensor importance of the last segment
//   f(x̄) = ε(x0→x1) g(x0,x1) · Π_{i=1}^{k−1} ρ(x_{i−1}→x_i→x_{i+1}) g(x_i,x_{i+1}) · W(x_{k−1}→x_k)
//
// The cosines of a segment are those at its two ends; ρ carries the cosines of its OUTGOING
// segment (toward the sensor). Regrouping the same product by segment gives
//   f(x̄) = Π_vertices scatter(x_i) · Π_segments G(x_i, x_{i+1}) V(x_i, x_{i+1}),
// with G = |cos||cos| / r² and scatter = Le at x0, f_r at interior vertices, W at xk. That is
// the form the subpath walks accumulate (beta) and `connect` joins: each factor is known as soon
// as the vertices it touches are. `pathContribution` evaluates the first form directly; the
// tests check the two agree.
//
// Shading normals: f_r is evaluated in the shading frame, and the cosine at the receiving end of
// the incoming (light-side) segment becomes the SHADING cosine, as radiance scattering demands.
// Writing it as the factor |ns·ℓ| / |ng·ℓ| on f_r (ℓ: toward the light side) keeps G purely
// geometric and symmetric, and makes light subpaths use Veach's adjoint BSDF (thesis §5.3)
// automatically, so light tracing and path tracing agree on smooth-normal meshes.
#pragma once
#include "paths/vertex.h"

namespace tripath {

// |cos θ| at vertex v for the unit direction w: geometric normal, or the sensor's axis;
// 1 at a point light (it has no surface to foreshorten).
float cosine(const Vertex& v, Vec3 w);
// Squared distance, guarded: coincident vertices give +inf for 1/r², never NaN.
float inverseSquaredDistance(const Vertex& a, const Vertex& b);
// G(a,b) = |cos θa| |cos θb| / |a − b|², without visibility.
float geometricFactor(const Vertex& a, const Vertex& b);
// Visibility V(a, b): a shadow ray between the two, offset off their surfaces.
bool visible(const Scene& scene, const Vertex& a, const Vertex& b);

// g(x, x') = V / r².
float g(const Scene& scene, const Vertex& x, const Vertex& xp);
// ε(x0 → x1) = Le(x0 → x1) |cos θ0| |cos θ1|.
Spectrum emittance(const Scene& scene, const Vertex& x0, const Vertex& x1);
// ρ(x″ → x′ → x) = f_r · |cos θ′| |cos θ| (outgoing segment x′–x), with the shading correction.
Spectrum rho(const Scene& scene, const Vertex& xpp, const Vertex& xp, const Vertex& x);
// W(x_{k−1} → x_k): the sensor importance of the pixel the segment passes through.
float W(const Scene& scene, const Vertex& xkm1, const Vertex& xk);

// Shading-normal factor |ns·ℓ| / |ng·ℓ| for a surface vertex, ℓ toward the light side (1 elsewhere).
float shadingCorrection(const Vertex& v, Vec3 towardLight);
// The per-vertex factor of the regrouped product: Le (emitter endpoint), f_r × shading
// correction (surface), W (sensor). `towardLight`/`towardCamera` are the neighbours' positions;
// an endpoint ignores the one it lacks.
Spectrum scatter(const Scene& scene, const Vertex& v, const Vertex* towardLight, const Vertex* towardCamera);

// Solid-angle pdf p_ω at `from` → area pdf at `to`: p_A = p_ω |cos θ_to| / r².
float toAreaPdf(float pdfOmega, const Vertex& from, const Vertex& to);

// Area pdf with which vertex v, reached from `from` (null at a subpath's endpoint), generates the
// point `to`: its BSDF's (surface), the emission distribution's (emitter) or the sensor's over
// the image (camera), converted to area measure at `to`. Zero through a delta lobe. Walks and
// connections both take their pdfs from here, as functions of the points alone, so every
// strategy's pdf of a path is computed the same way (the MIS weights depend on it).
float generationPdf(const Scene& scene, const Vertex& v, const Vertex* from, const Vertex& to);

// f(x̄) for a whole path x0 … xk (x0 emitter, xk sensor), the product of the kernels above.
Spectrum pathContribution(const Scene& scene, const std::vector<Vertex>& path);

}  // namespace tripath
