// The oracle: f(x̄) of a whole path as the literal product of the kernels of points
// (paths/kernels.h), and the pieces of it the tests name. The renderer's estimates are checked
// against f(x̄)/p from here; walks, connections and merges call the same kernels through their
// fast overloads.
#pragma once
#include <vector>

#include "paths/kernels.h"

namespace tripath {

// The unit direction from one vertex to another; a vertex at infinity is a direction (its ns,
// toward it), whichever end it is: the oracle's own statement of that measure.
Vec3 unitDirection(const Vertex& from, const Vertex& to);
// |cos θ| at x toward unit w: 1 at an emitter without a surface (a point light, or an emitter at
// infinity, measured in solid angle).
float cosineToward(const Vertex& x, Vec3 w);

// Squared distance, guarded: coincident vertices give +inf for 1/r², never NaN.
float inverseSquaredDistance(const Vertex& a, const Vertex& b);
// G(a,b) = |cos θa| |cos θb| / |a − b|², without visibility: the cosines ρ or ε carry, times g.
Spectrum geometricFactor(const Vertex& a, const Vertex& b);

// What v contributes besides cosines (f_r × shading correction, Le, or W), from the neighbours'
// positions: LocalScattering(v, directions to the two).value(). An endpoint lacks one neighbour.
Spectrum scatter(const Scene& scene, const Vertex& v, const Vertex* towardLight, const Vertex* towardCamera);

// Solid-angle pdf at `from` → area pdf at `to`: p_A = p_ω |cos θ_to| / r²; p_ω itself toward a vertex
// at infinity, and p |cos θ_to| from one (p there is a density per unit area across the beam).
float toAreaPdf(float pdfOmega, const Vertex& from, const Vertex& to);

// f(x̄) for a whole path x0 … xk (x0 emitter, xk sensor), the product of the kernels of points.
Spectrum pathContribution(const Scene& scene, const std::vector<Vertex>& path);

}  // namespace tripath
