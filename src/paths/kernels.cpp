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

void LocalScattering::bendFrames(Vec3 towardLight, Vec3 towardCamera) {
    const Vec3 nLight = bentNormal(v_.ns, v_.ng, towardLight), nCamera = bentNormal(v_.ns, v_.ng, towardCamera);
    const Frame frame(nLight);
    lightLocal_ = frame.toLocal(towardLight);
    cameraLocal_ = frame.toLocal(towardCamera);
    normal_ = nLight;
    if (!(nCamera == nLight)) apart_ = BentApart(nCamera, towardLight, towardCamera);
}

Spectrum LocalScattering::value() const {
    if (v_.kind == Vertex::Kind::Sensor) return Spectrum(hasLight_ ? scene_.camera().importance(light_) : 0.0f);
    if (emits()) return scene_.emitters().Le(v_.emitter, v_.ng, camera_, v_.bary);
    if (apart_) [[unlikely]] return valueAboutThePairsNormal();
    if (!sidesAgree(v_, normal_, light_) || !sidesAgree(v_, normal_, camera_)) return Spectrum(0.0f);
    return evalBsdf(*bsdf_, cameraLocal_, lightLocal_, TransportMode::Radiance) * shadingCorrection(v_, normal_, light_);
}

// f_r × shading correction where the two directions' bent normals differ: about the one nearer ng.
Spectrum LocalScattering::valueAboutThePairsNormal() const {
    const bool aboutCamera = dot(apart_->normal, v_.ng) > dot(normal_, v_.ng);
    const Vec3 n = aboutCamera ? apart_->normal : normal_;
    if (!sidesAgree(v_, n, light_) || !sidesAgree(v_, n, camera_)) return Spectrum(0.0f);
    const Spectrum f = aboutCamera ? evalBsdf(*bsdf_, apart_->cameraLocal, apart_->lightLocal, TransportMode::Radiance)
                                   : evalBsdf(*bsdf_, cameraLocal_, lightLocal_, TransportMode::Radiance);
    return f * shadingCorrection(v_, n, light_);
}

float LocalScattering::pdfTowardCamera() const {
    if (v_.kind == Vertex::Kind::Sensor) return 0.0f;  // the path's end: nothing lies beyond it
    if (emits()) return scene_.emitters().directionPdf(v_.emitter, v_.ng, camera_);
    return pdfBsdf(*bsdf_, lightLocal_, cameraLocal_);
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
    return apart_ ? pdfBsdf(*bsdf_, apart_->cameraLocal, apart_->lightLocal) : pdfBsdf(*bsdf_, cameraLocal_, lightLocal_);
}

Spectrum g(const Scene& scene, const Vertex& x, const Vertex& xp) {
    return visible(scene, x, xp) ? g(Segment(x, xp)) : Spectrum(0.0f);
}

Spectrum emittance(const Scene& scene, const Vertex& x0, const Vertex& x1) {
    const Segment out(x0, x1);
    return emittance(LocalScattering(scene, x0, nullptr, nullptr, out.towardB()), out);
}

Spectrum rho(const Scene& scene, const Vertex& xpp, const Vertex& xp, const Vertex& x) {
    const Segment in(xp, xpp), out(xp, x);
    std::optional<BsdfParams> scratch;
    return rho(LocalScattering(scene, xp, bsdfAt(scene, xp, scratch), in.towardB(), out.towardB()), out);
}

float W(const Scene& scene, const Vertex& xkm1, const Vertex& xk) {
    const Segment in(xk, xkm1);
    return W(LocalScattering(scene, xk, nullptr, in.towardB(), nullptr));
}

}  // namespace tripath
