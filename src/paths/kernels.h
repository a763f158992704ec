// The kernels of the three-point form (docs/design.md §1), as every walk, connection
// and merge evaluates them:
//
//   g(x, x')            = V(x, x') / |x − x'|²                              [1/m²]
//   ε(x0 → x1)          = Le(x0 → x1) |cos θ0| |cos θ1|                     [W/m²]
//   ρ(x″ → x′ → x)      = f_r(x″ → x′ → x) |cos θ′| |cos θ|                 [1]
//   W(x_{k−1} → x_k)    = sensor importance of the last segment
//   f(x̄) = ε(x0→x1) g(x0,x1) · Π_{i=1}^{k−1} ρ(x_{i−1}→x_i→x_{i+1}) g(x_i,x_{i+1}) · W(x_{k−1}→x_k)
//
// Every cosine of a segment lives in the ρ or ε of the segment's light-side vertex. A subpath's
// throughput β (vertex.h) is the product of the kernels whose points it holds over its vertices'
// pdfs, and a connection multiplies in the ones the joining segment completes: ρ or ε at the
// light-side endpoint, g between the two, ρ or W at the camera-side endpoint (connect.cpp).
//
// Each kernel has two forms: of points (the definition, which the tests use as an oracle), and
// of what a walk or a connection has already computed: the endpoint's LocalScattering (its frame
// and local directions) and the Segment (direction and length). The point forms build those and
// call the fast ones, so there is one implementation of each kernel.
//
// Shading normals: f_r is evaluated in the shading frame, and the cosine at the receiving end of
// the incoming (light-side) segment becomes the SHADING cosine, as radiance scattering demands.
// Writing it as the factor |ns·ℓ| / |ng·ℓ| on f_r (ℓ: toward the light side) keeps the cosines in
// ρ purely geometric, and makes light subpaths use Veach's adjoint BSDF (thesis §5.3)
// automatically, so light tracing and path tracing agree on smooth-normal meshes.
#pragma once
#include <cmath>
#include <optional>

#include "paths/shading_normal.h"
#include "paths/vertex.h"

namespace tripath {

// |cos θ| at vertex v for the unit direction w: geometric normal, or the sensor's axis;
// 1 at an emitter without a surface (a point light has none to foreshorten; at infinity, the
// solid-angle measure has none).
[[gnu::always_inline]] inline float cosine(const Vertex& v, Vec3 w) { return v.isFreeEmitter() ? 1.0f : absDot(v.ng, w); }

// The segment between two vertices, its direction and length computed once for the kernels
// that share it (g, the cosines of ρ or ε, and the area pdfs at either end).
//
// A segment to a vertex at infinity (vertex.h) has that vertex's direction and, in place of the
// squared length, 1: the far end is measured in solid angle, so g = V (no 1/r²), its cosine is 1,
// a solid-angle pdf toward it is its pdf, and the beam's density per unit area across it (emitters.h)
// becomes an area density at the near end by the near end's cosine alone (docs/design.md §2).
class Segment {
public:
    Segment(const Vertex& a, const Vertex& b) : Segment(a, &b) {}
    // The segment from a to its neighbour b, if a has one there (a subpath's endpoint does not).
    Segment(const Vertex& a, const Vertex* b) : a_(a), b_(b) {
        if (!b) return;
        if (a.atInfinity || b->atInfinity) [[unlikely]] {
            d2_ = 1.0f;
            w_ = b->atInfinity ? b->ns : -a.ns;
            return;
        }
        d2_ = lengthSquared(b->p - a.p);
        w_ = (b->p - a.p) / std::sqrt(d2_);
    }
    // A segment a walk traced from a to b along the unit direction w (or from b to a along −w):
    // its cosines are those of the ray itself, which an offset origin and rounded hit points make
    // differ slightly from the direction between the points (kernels that end up beside the
    // sampler's pdf of that ray must use its direction, or their ratio drifts: see `traced`).
    Segment(const Vertex& a, const Vertex& b, Vec3 w)
        : a_(a), b_(&b), d2_(a.atInfinity || b.atInfinity ? 1.0f : lengthSquared(b.p - a.p)), w_(w) {}
    Vec3 direction() const { return w_; }  // unit, a → b
    // The direction as LocalScattering takes a neighbour: null where there is no b.
    const Vec3* towardB() const { return b_ ? &w_ : nullptr; }
    // 1 / |a − b|²: g(a, b) without its visibility; 0 for coincident points (no transport).
    float inverseSquaredLength() const { return d2_ > 0 ? 1.0f / d2_ : 0.0f; }
    // |cos θa| |cos θb|: the cosines of the segment at both ends.
    float cosines() const { return cosine(a_, w_) * cosine(*b_, w_); }
    // Solid-angle pdf at one end → area pdf at the other end, `to`: p_A = p_ω |cos θ_to| / r².
    float toArea(float pdfOmega, const Vertex& to) const { return d2_ > 0 ? pdfOmega * cosine(to, w_) / d2_ : 0.0f; }
    // The inverse: an area pdf at `at` (one end) → the solid-angle pdf at the other end.
    float toSolidAngle(float pdfArea, const Vertex& at) const { return pdfArea * d2_ / cosine(at, w_); }
    // g(a, b) / p_A(b) for b generated from a with solid-angle pdf p_ω: the r² cancels, leaving
    // 1 / (p_ω |cos θ_b|) (a walk's step: one division where the two factors would take two).
    float gOverArea(float pdfOmega, const Vertex& b) const { return d2_ > 0 ? 1.0f / (pdfOmega * cosine(b, w_)) : 0.0f; }
    // The Beer–Lambert transmittance exp(−σ_a |a − b|) of a segment that runs inside an absorbing
    // volume (it leaves the back of a surface whose material absorbs, or reaches one from behind:
    // Material::absorption); 1 elsewhere, and for a segment to or from infinity. It is part of g:
    // every strategy's contribution carries it and no sampler draws it, so no pdf changes.
    Spectrum transmittance() const {
        const Vertex* inside = absorbsBehind(a_, w_) ? &a_ : b_ && absorbsBehind(*b_, -w_) ? b_ : nullptr;
        if (!inside) [[likely]] return Spectrum(1.0f);
        if (!b_ || a_.atInfinity || b_->atInfinity || !(d2_ > 0)) return Spectrum(1.0f);
        return exp(inside->material->absorption * -std::sqrt(d2_));
    }

private:
    // Whether the unit direction `away` leaves v into the volume behind its surface.
    static bool absorbsBehind(const Vertex& v, Vec3 away) { return v.absorbs && dot(away, v.ng) < 0; }
    const Vertex& a_;
    const Vertex* b_;
    float d2_ = 0;
    Vec3 w_;
};

// Visibility V(a, b): a shadow ray between the two, offset off their surfaces.
bool visible(const Scene& scene, const Vertex& a, const Vertex& b);

// Shading-normal factor |n·ℓ| / |ng·ℓ| for a surface vertex scattering about the shading normal n
// (shading_normal.h), ℓ toward the light side (1 elsewhere).
inline float shadingCorrection(const Vertex& v, Vec3 n, Vec3 towardLight) {
    if (v.kind != Vertex::Kind::Surface) return 1.0f;
    const float cosG = absDot(v.ng, towardLight);
    return cosG > 0 ? absDot(n, towardLight) / cosG : 0.0f;
}

// Leak mask: whether unit w lies on the same side of a surface vertex under the shading normal n
// it scatters about (shading_normal.h) as under its geometric one. Near the silhouettes of coarse
// smooth meshes the two disagree, and a BSDF evaluated in the shading frame alone would let light
// through the surface (or reflect it off the back). A surface vertex scatters only between directions that both pass this test, in
// either transport mode: the mask is symmetric in the two directions, so the adjoint BSDF of
// light subpaths stays exactly the radiance BSDF's adjoint (Veach §5.3) and pt, lt and bdpt keep
// agreeing on smooth meshes.
inline bool sidesAgree(const Vertex& v, Vec3 n, Vec3 w) { return dot(v.ng, w) * dot(n, w) > 0; }

// Vertex v between its light-side and camera-side neighbours: the factor it contributes to the
// regrouped product, and the pdfs with which it generates either neighbour. The directions to
// the neighbours and, on a surface, the shading frames and local directions are computed once for
// all of them (a pdf about the normal bent for the direction it is generated from, f_r about the
// pair's: shading_normal.h); `connect` evaluates every one at both ends of the connecting
// segment. Walks and connections both take their pdfs from here, with directions from the points
// alone (never the sampled direction, which an offset ray origin bends on short segments), so
// that every strategy's pdf of a path is computed the same way: the MIS weights depend on it.
//
// The neighbours are given as unit directions from v, null where there is none. An endpoint
// lacks one: the sensor its camera side, an emitter point its light side -- as does a surface a
// camera walk hit, taken as the start of the light's path (strategy s = 0). v's BSDF parameters
// come derived (the subpath keeps them: vertex.h), and are read only at a surface between two
// neighbours. (Pointers rather than optionals, and an inline constructor: this runs several
// times per connection.)
class LocalScattering {
public:
    // Local directions from the arguments, not from the members just written (store forwarding).
    LocalScattering(const Scene& scene, const Vertex& v, const BsdfParams* bsdf, const Vec3* towardLight,
                    const Vec3* towardCamera)
        : scene_(scene), v_(v), bsdf_(bsdf), hasLight_(towardLight != nullptr), hasCamera_(towardCamera != nullptr),
          light_(hasLight_ ? *towardLight : Vec3()), camera_(hasCamera_ ? *towardCamera : Vec3()) {
        if (v.kind == Vertex::Kind::Surface && hasLight_ && hasCamera_) {
            if (v.ns == v.ng) [[likely]] {  // flat shading: one frame, nothing bent
                const Frame frame(v.ns);
                lightLocal_ = frame.toLocal(*towardLight);
                cameraLocal_ = frame.toLocal(*towardCamera);
                normal_ = v.ns;
            } else {
                bendFrames(*towardLight, *towardCamera);
            }
        }
    }
    // What v contributes besides cosines: Le toward the camera side at an emitter end, f_r ×
    // shading correction at a surface, W toward the light side at the sensor.
    Spectrum value() const;
    // Solid-angle pdf with which v, reached from its light side, generates the camera-side
    // direction: its BSDF's, or an emitter's emission distribution.
    float pdfTowardCamera() const;
    // Solid-angle pdf with which v, reached from its camera side, generates the light-side
    // direction: its BSDF's, or the sensor's per-pixel pdf over the pass's N_L, `lightPaths`
    // (pass_constants.h): each pixel's camera sample connects with one of the pass's light paths,
    // and each of them is joined to the sensor once and may land in any pixel, so MIS compares
    // the camera's per-pixel pdf divided by N_L with the light strategies' pdfs (Veach §10.3.4.3).
    // Zero through a delta lobe, which MIS knows by the vertex's flag, not by the zero.
    float pdfTowardLight(double lightPaths) const;

private:
    bool emits() const;  // an emitter end: no light side
    // The frames of a surface whose shading normal differs from its geometric one (shading_normal.h).
    void bendFrames(Vec3 towardLight, Vec3 towardCamera);
    Spectrum valueAboutThePairsNormal() const;
    const Scene& scene_;
    const Vertex& v_;
    const BsdfParams* bsdf_;  // v's parameters: its material's, or its own where textures or vertex colours vary them
    bool hasLight_, hasCamera_;
    Vec3 light_, camera_;
    // Surfaces between two neighbours: both directions in the frame of the normal bent for the
    // light-side one (normal_), and, where the camera-side one's differs, that normal and the
    // directions in its frame.
    struct BentApart {
        BentApart(Vec3 n, Vec3 towardLight, Vec3 towardCamera) : normal(n) {
            const Frame frame(n);
            lightLocal = frame.toLocal(towardLight);
            cameraLocal = frame.toLocal(towardCamera);
        }
        Vec3 normal, lightLocal, cameraLocal;
    };
    Vec3 normal_, lightLocal_, cameraLocal_;
    std::optional<BentApart> apart_;
};

// The segment from a camera or light subpath's vertex v back to its predecessor, along the
// direction the walk traced it. Where a kernel's cosines meet the walk's sampling pdf of that
// segment (the camera side of a connection, a merge or an emitter hit, and the camera walk's
// own next step), this keeps f/p what the sampler made it: at the coordinates of a scene far from
// the origin, hit points are rounded to a fair fraction of a small object's size, and cosines
// between the points would bias the image (DegenerateFar).
inline Segment traced(const Vertex& v, const Vertex& predecessor) { return Segment(v, predecessor, v.arrival); }

// ρ(x″ → x′ → x) with x′'s f_r × shading correction already evaluated (LocalScattering::value,
// or the BSDF sample a walk drew) and `out` the segment x′ → x.
inline Spectrum rho(Spectrum scatter, const Segment& out) { return scatter * out.cosines(); }
inline Spectrum rho(const LocalScattering& at, const Segment& out) { return rho(at.value(), out); }
// ε(x0 → x1) with Le(x0 → x1) already evaluated, `out` the segment x0 → x1.
inline Spectrum emittance(Spectrum Le, const Segment& out) { return Le * out.cosines(); }
inline Spectrum emittance(const LocalScattering& at, const Segment& out) { return emittance(at.value(), out); }
// W(x_{k−1} → x_k) at the sensor's LocalScattering (its light side toward x_{k−1}).
inline float W(const LocalScattering& atSensor) { return atSensor.value().x; }
// g(x, x') of a segment whose visibility is known: its shadow ray came back unoccluded, or a walk
// traced it; times its transmittance where it runs inside an absorbing volume.
inline Spectrum g(const Segment& s) { return s.transmittance() * s.inverseSquaredLength(); }

// The point forms, the definitions.
// g(x, x') = V T / r², with its shadow ray (T: the transmittance of an absorbing volume, else 1).
Spectrum g(const Scene& scene, const Vertex& x, const Vertex& xp);
// ε(x0 → x1) = Le(x0 → x1) |cos θ0| |cos θ1|.
Spectrum emittance(const Scene& scene, const Vertex& x0, const Vertex& x1);
// ρ(x″ → x′ → x) = f_r · |cos θ′| |cos θ| (outgoing segment x′–x), with the shading correction.
Spectrum rho(const Scene& scene, const Vertex& xpp, const Vertex& xp, const Vertex& x);
// W(x_{k−1} → x_k): the sensor importance of the pixel the segment passes through.
float W(const Scene& scene, const Vertex& xkm1, const Vertex& xk);

}  // namespace tripath
