#include "paths/kernels.h"

#include <limits>

namespace tripath {

namespace {
Vec3 unitDirection(const Vertex& from, const Vertex& to) { return normalize(to.p - from.p); }
}  // namespace

float cosine(const Vertex& v, Vec3 w) { return v.isDeltaLight() ? 1.0f : absDot(v.ng, w); }

float inverseSquaredDistance(const Vertex& a, const Vertex& b) {
    const float d2 = lengthSquared(a.p - b.p);
    return d2 > 0 ? 1.0f / d2 : std::numeric_limits<float>::infinity();
}

float Segment::G() const {
    if (!(d2_ > 0)) return 0.0f;  // coincident points carry no transport
    return cosine(a_, w_) * cosine(*b_, w_) / d2_;
}

float Segment::toArea(float pdfOmega, const Vertex& to) const {
    if (!(d2_ > 0)) return 0.0f;
    return pdfOmega * cosine(to, w_) / d2_;
}

float geometricFactor(const Vertex& a, const Vertex& b) { return Segment(a, b).G(); }

bool visible(const Scene& scene, const Vertex& a, const Vertex& b) {
    return scene.unoccluded(a.p, a.offsetNormal(), b.p, b.offsetNormal());
}

float g(const Scene& scene, const Vertex& x, const Vertex& xp) {
    return visible(scene, x, xp) ? inverseSquaredDistance(x, xp) : 0.0f;
}

Spectrum emittance(const Scene& scene, const Vertex& x0, const Vertex& x1) {
    const Vec3 w = unitDirection(x0, x1);
    return scatter(scene, x0, nullptr, &x1) * (cosine(x0, w) * cosine(x1, w));
}

Spectrum rho(const Scene& scene, const Vertex& xpp, const Vertex& xp, const Vertex& x) {
    const Vec3 w = unitDirection(xp, x);
    return scatter(scene, xp, &xpp, &x) * (cosine(xp, w) * cosine(x, w));
}

float W(const Scene& scene, const Vertex& xkm1, const Vertex& xk) {
    return scene.camera().importance(unitDirection(xk, xkm1));
}

float shadingCorrection(const Vertex& v, Vec3 towardLight) {
    if (v.kind != Vertex::Kind::Surface) return 1.0f;
    const float cosG = absDot(v.ng, towardLight);
    return cosG > 0 ? absDot(v.ns, towardLight) / cosG : 0.0f;
}

bool LocalScattering::emits() const {
    return v_.kind == Vertex::Kind::Emitter || (v_.kind == Vertex::Kind::Surface && !hasLight_);
}

Spectrum LocalScattering::value() const {
    if (v_.kind == Vertex::Kind::Sensor) return Spectrum(inImage_ ? scene_.camera().importanceInImage(light_) : 0.0f);
    if (emits()) return scene_.emitters().Le(v_.emitter, v_.ng, camera_);
    return evalBsdf(*v_.material, cameraLocal_, lightLocal_, TransportMode::Radiance) * shadingCorrection(v_, light_);
}

float LocalScattering::pdfTowardCamera() const {
    if (v_.kind == Vertex::Kind::Sensor) return 0.0f;  // the path's end: nothing lies beyond it
    if (emits()) return scene_.emitters().directionPdf(v_.emitter, v_.ng, camera_);
    return pdfBsdf(*v_.material, lightLocal_, cameraLocal_);
}

float LocalScattering::pdfTowardLight() const {
    if (v_.kind == Vertex::Kind::Sensor) return inImage_ ? scene_.camera().imagePdfInImage(light_) : 0.0f;
    if (emits()) return 0.0f;  // the path's start: nothing lies before it
    return pdfBsdf(*v_.material, cameraLocal_, lightLocal_);
}

Spectrum scatter(const Scene& scene, const Vertex& v, const Vertex* towardLight, const Vertex* towardCamera) {
    const Vec3 l = towardLight ? unitDirection(v, *towardLight) : Vec3();
    const Vec3 c = towardCamera ? unitDirection(v, *towardCamera) : Vec3();
    return LocalScattering(scene, v, towardLight ? &l : nullptr, towardCamera ? &c : nullptr).value();
}

float toAreaPdf(float pdfOmega, const Vertex& from, const Vertex& to) { return Segment(from, to).toArea(pdfOmega, to); }

Spectrum pathContribution(const Scene& scene, const std::vector<Vertex>& x) {
    const size_t k = x.size() - 1;
    Spectrum f = emittance(scene, x[0], x[1]) * g(scene, x[0], x[1]);
    for (size_t i = 1; i < k; ++i) f *= rho(scene, x[i - 1], x[i], x[i + 1]) * g(scene, x[i], x[i + 1]);
    return f * W(scene, x[k - 1], x[k]);
}

}  // namespace tripath
