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

float geometricFactor(const Vertex& a, const Vertex& b) {
    const float d2 = lengthSquared(a.p - b.p);
    if (!(d2 > 0)) return 0.0f;  // coincident points carry no transport
    const Vec3 w = (b.p - a.p) / std::sqrt(d2);
    return cosine(a, w) * cosine(b, w) / d2;
}

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

Spectrum scatter(const Scene& scene, const Vertex& v, const Vertex* towardLight, const Vertex* towardCamera) {
    switch (v.kind) {
        case Vertex::Kind::Sensor:
            return Spectrum(W(scene, *towardLight, v));
        case Vertex::Kind::Emitter:
            return scene.emitters().Le(v.emitter, v.ng, unitDirection(v, *towardCamera));
        case Vertex::Kind::Surface: {
            if (!towardLight) return scene.emitters().Le(v.emitter, v.ng, unitDirection(v, *towardCamera));
            const Vec3 l = unitDirection(v, *towardLight), c = unitDirection(v, *towardCamera);
            const Frame frame(v.ns);
            return evalBsdf(*v.material, frame.toLocal(c), frame.toLocal(l), TransportMode::Radiance) *
                   shadingCorrection(v, l);
        }
    }
    return Spectrum(0.0f);
}

float toAreaPdf(float pdfOmega, const Vertex& from, const Vertex& to) {
    const float d2 = lengthSquared(to.p - from.p);
    if (!(d2 > 0)) return 0.0f;
    return pdfOmega * cosine(to, (to.p - from.p) / std::sqrt(d2)) / d2;
}

float generationPdf(const Scene& scene, const Vertex& v, const Vertex* from, const Vertex& to) {
    const Vec3 w = unitDirection(v, to);
    float pdfOmega = 0;
    switch (v.kind) {
        case Vertex::Kind::Sensor: pdfOmega = scene.camera().imagePdf(w); break;
        case Vertex::Kind::Emitter: pdfOmega = scene.emitters().directionPdf(v.emitter, v.ng, w); break;
        case Vertex::Kind::Surface: {
            const Frame frame(v.ns);
            pdfOmega = pdfBsdf(*v.material, frame.toLocal(unitDirection(v, *from)), frame.toLocal(w));
            break;
        }
    }
    return toAreaPdf(pdfOmega, v, to);
}

Spectrum pathContribution(const Scene& scene, const std::vector<Vertex>& x) {
    const size_t k = x.size() - 1;
    Spectrum f = emittance(scene, x[0], x[1]) * g(scene, x[0], x[1]);
    for (size_t i = 1; i < k; ++i) f *= rho(scene, x[i - 1], x[i], x[i + 1]) * g(scene, x[i], x[i + 1]);
    return f * W(scene, x[k - 1], x[k]);
}

}  // namespace tripath
