#include "paths/kernels.h"

namespace tripath {

bool visible(const Scene& scene, const Vertex& a, const Vertex& b) {
    if (b.atInfinity) return scene.unoccludedToward(a.p, a.offsetNormal(), b.ns);
    if (a.atInfinity) return scene.unoccludedToward(b.p, b.offsetNormal(), a.ns);
    return scene.unoccluded(a.p, a.offsetNormal(), b.p, b.offsetNormal());
}

bool LocalScattering::emits() const {
    return v_.kind == Vertex::Kind::Emitter || (v_.kind == Vertex::Kind::Surface && !hasLight_);
}

Spectrum LocalScattering::value() const {
    if (v_.kind == Vertex::Kind::Sensor) return Spectrum(hasLight_ ? scene_.camera().importance(light_) : 0.0f);
    if (emits()) return scene_.emitters().Le(v_.emitter, v_.ng, camera_, v_.bary);
    // About the pair's normal: the bent one nearer ng.
    const bool aboutLight = dot(nLight_, v_.ng) >= dot(nCamera_, v_.ng);
    const Vec3 n = aboutLight ? nLight_ : nCamera_;
    const LocalDirections& d = aboutLight ? aboutLight_ : aboutCamera_;
    if (!sidesAgree(v_, n, light_) || !sidesAgree(v_, n, camera_)) return Spectrum(0.0f);
    return evalBsdf(bsdf(), d.camera, d.light, TransportMode::Radiance) * shadingCorrection(v_, n, light_);
}

float LocalScattering::pdfTowardCamera() const {
    if (v_.kind == Vertex::Kind::Sensor) return 0.0f;  // the path's end: nothing lies beyond it
    if (emits()) return scene_.emitters().directionPdf(v_.emitter, v_.ng, camera_);
    return pdfBsdf(bsdf(), aboutLight_.light, aboutLight_.camera);
}

float LocalScattering::pdfTowardLight(double lightPaths) const {
    if (v_.kind == Vertex::Kind::Sensor) {
        // Per-pixel pdf / N_L, the per-pixel pdf being the whole image's times the pixel count.
        // Not gated by the image's edge: where the camera generated the vertex, the direction
        // recomputed from the points may round to just outside it (far more than rounding in a
        // scene whose hit points are only as precise as its extent allows), and a zero here
        // would make the camera's own strategy impossible. A direction truly outside has W = 0.
        const Camera& cam = scene_.camera();
        if (!hasLight_ || !(dot(light_, v_.ng) > 0)) return 0.0f;  // v_.ng: the optical axis
        return cam.pixelDensity(light_) / static_cast<float>(lightPaths);
    }
    if (emits()) return 0.0f;  // the path's start: nothing lies before it
    return pdfBsdf(bsdf(), aboutCamera_.camera, aboutCamera_.light);
}

float g(const Scene& scene, const Vertex& x, const Vertex& xp) { return visible(scene, x, xp) ? g(Segment(x, xp)) : 0.0f; }

Spectrum emittance(const Scene& scene, const Vertex& x0, const Vertex& x1) {
    const Segment out(x0, x1);
    return emittance(LocalScattering(scene, x0, nullptr, out.towardB()), out);
}

Spectrum rho(const Scene& scene, const Vertex& xpp, const Vertex& xp, const Vertex& x) {
    const Segment in(xp, xpp), out(xp, x);
    return rho(LocalScattering(scene, xp, in.towardB(), out.towardB()), out);
}

float W(const Scene& scene, const Vertex& xkm1, const Vertex& xk) {
    const Segment in(xk, xkm1);
    return W(LocalScattering(scene, xk, in.towardB(), nullptr));
}

}  // namespace tripath
