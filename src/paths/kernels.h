// The factors of the three-point form (DESIGN.md §1, seeds/000 §2–4) as the walks and
// connections evaluate them.
//
// The kernels g, ε, ρ and W multiply to f(x̄) (paths/oracle.h evaluates them literally). The
// cosines of a segment are those at its two ends; ρ carries the cosines of its OUTGOING segment
// (toward the sensor). Regrouping the same product by segment gives
//   f(x̄) = Π_vertices scatter(x_i) · Π_segments G(x_i, x_{i+1}) V(x_i, x_{i+1}),
// with G = |cos||cos| / r² and scatter = Le at x0, f_r at interior vertices, W at xk. That is
// the form the subpath walks accumulate (beta) and `connect` joins: each factor is known as soon
// as the vertices it touches are. The tests check the two forms agree.
//
// Shading normals: f_r is evaluated in the shading frame, and the cosine at the receiving end of
// the incoming (light-side) segment becomes the SHADING cosine, as radiance scattering demands.
// Writing it as the factor |ns·ℓ| / |ng·ℓ| on f_r (ℓ: toward the light side) keeps G purely
// geometric and symmetric, and makes light subpaths use Veach's adjoint BSDF (thesis §5.3)
// automatically, so light tracing and path tracing agree on smooth-normal meshes.
#pragma once
#include <cmath>

#include "paths/vertex.h"

namespace tripath {

// |cos θ| at vertex v for the unit direction w: geometric normal, or the sensor's axis;
// 1 at a point light (it has no surface to foreshorten).
float cosine(const Vertex& v, Vec3 w);

// The segment between two vertices, its direction and length computed once for the kernels
// that share it (G, and the area pdfs at either end).
class Segment {
public:
    Segment(const Vertex& a, const Vertex& b) : Segment(a, &b) {}
    // The segment from a to its neighbour b, if a has one there (a subpath's endpoint does not).
    Segment(const Vertex& a, const Vertex* b) : a_(a), b_(b) {
        if (!b) return;
        d2_ = lengthSquared(b->p - a.p);
        w_ = (b->p - a.p) / std::sqrt(d2_);
    }
    Vec3 direction() const { return w_; }  // unit, a → b
    // The direction as LocalScattering takes a neighbour: null where there is no b.
    const Vec3* towardB() const { return b_ ? &w_ : nullptr; }
    // G(a,b) = |cos θa| |cos θb| / |a − b|², without visibility; 0 for coincident points.
    float G() const;
    // Solid-angle pdf at one end → area pdf at the other end, `to`: p_A = p_ω |cos θ_to| / r².
    float toArea(float pdfOmega, const Vertex& to) const;
    // The inverse: an area pdf at `at` (one end) → the solid-angle pdf at the other end.
    float toSolidAngle(float pdfArea, const Vertex& at) const;

private:
    const Vertex& a_;
    const Vertex* b_;
    float d2_ = 0;
    Vec3 w_;
};

// Visibility V(a, b): a shadow ray between the two, offset off their surfaces.
bool visible(const Scene& scene, const Vertex& a, const Vertex& b);

// Shading-normal factor |ns·ℓ| / |ng·ℓ| for a surface vertex, ℓ toward the light side (1 elsewhere).
float shadingCorrection(const Vertex& v, Vec3 towardLight);

// Leak mask: whether unit w lies on the same side of a surface vertex under its shading normal
// as under its geometric one. Near the silhouettes of coarse smooth meshes the two disagree, and a
// BSDF evaluated in the shading frame alone would let light through the surface (or reflect it
// off the back). A surface vertex scatters only between directions that both pass this test, in
// either transport mode: the mask is symmetric in the two directions, so the adjoint BSDF of
// light subpaths stays exactly the radiance BSDF's adjoint (Veach §5.3) and pt, lt and bdpt keep
// agreeing on smooth meshes.
inline bool sidesAgree(const Vertex& v, Vec3 w) { return dot(v.ng, w) * dot(v.ns, w) > 0; }

// Light paths traced per pass, N_L: one per pixel, each paired with that pixel's camera sample.
// Every light path may land in any pixel, so a splat counts 1/N_L there, and MIS compares the
// camera's per-pixel pdf divided by N_L with the light strategies' pdfs (Veach §10.3.4.3). The one
// place that number is decided: vertex merging changes it.
double lightPathsPerPass(const Camera& camera);

// Vertex v between its light-side and camera-side neighbours: the factor it contributes to the
// regrouped product, and the pdfs with which it generates either neighbour. The directions to
// the neighbours and, on a surface, the shading frame and local directions are computed once for
// all of them; `connect` evaluates every one at both ends of the connecting segment. Walks and
// connections both take their pdfs from here, with directions from the points alone (never the
// sampled direction, which an offset ray origin bends on short segments), so that every
// strategy's pdf of a path is computed the same way: the MIS weights depend on it.
//
// The neighbours are given as unit directions from v, null where there is none. An endpoint
// lacks one: the sensor its camera side, an emitter point its light side -- as does a surface a
// camera walk hit, taken as the start of the light's path (strategy s = 0). (Pointers, and an
// inline constructor: this runs several times per connection, and optional<Vec3> arguments
// passed through memory stall store forwarding.)
class LocalScattering {
public:
    LocalScattering(const Scene& scene, const Vertex& v, const Vec3* towardLight, const Vec3* towardCamera)
        : scene_(scene), v_(v), hasLight_(towardLight != nullptr), hasCamera_(towardCamera != nullptr) {
        if (hasLight_) light_ = *towardLight;
        if (hasCamera_) camera_ = *towardCamera;
        if (v.kind == Vertex::Kind::Surface && hasLight_ && hasCamera_) {
            const Frame frame(v.ns);
            lightLocal_ = frame.toLocal(light_);
            cameraLocal_ = frame.toLocal(camera_);
        }
    }
    // scatter(v): Le toward the camera side at an emitter end, f_r × shading correction at a
    // surface, W toward the light side at the sensor.
    Spectrum value() const;
    // Solid-angle pdf with which v, reached from its light side, generates the camera-side
    // direction: its BSDF's, or an emitter's emission distribution.
    float pdfTowardCamera() const;
    // Solid-angle pdf with which v, reached from its camera side, generates the light-side
    // direction: its BSDF's, or the sensor's per-pixel pdf over N_L (lightPathsPerPass). Zero
    // through a delta lobe, which MIS knows by the vertex's flag, not by the zero.
    float pdfTowardLight() const;

private:
    bool emits() const;  // an emitter end: no light side
    const Scene& scene_;
    const Vertex& v_;
    bool hasLight_, hasCamera_;
    Vec3 light_, camera_;
    Vec3 lightLocal_, cameraLocal_;  // in v's shading frame (surfaces between two neighbours)
};

}  // namespace tripath
