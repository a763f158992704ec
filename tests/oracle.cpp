#include "oracle.h"

#include <cmath>
#include <limits>

namespace tripath {

Vec3 unitDirection(const Vertex& from, const Vertex& to) {
    if (to.atInfinity) return to.ns;
    if (from.atInfinity) return -from.ns;
    return normalize(to.p - from.p);
}

float cosineToward(const Vertex& x, Vec3 w) {
    return x.kind == Vertex::Kind::Emitter && lengthSquared(x.ng) == 0 ? 1.0f : std::abs(dot(x.ng, w));
}

float inverseSquaredDistance(const Vertex& a, const Vertex& b) {
    const float d2 = lengthSquared(a.p - b.p);
    return d2 > 0 ? 1.0f / d2 : std::numeric_limits<float>::infinity();
}

Spectrum geometricFactor(const Vertex& a, const Vertex& b) {
    const Segment s(a, b);
    return g(s) * s.cosines();
}

Spectrum scatter(const Scene& scene, const Vertex& v, const Vertex* towardLight, const Vertex* towardCamera) {
    const Vec3 l = towardLight ? unitDirection(v, *towardLight) : Vec3();
    const Vec3 c = towardCamera ? unitDirection(v, *towardCamera) : Vec3();
    std::optional<BsdfParams> parameters;
    return LocalScattering(scene, v, bsdfAt(scene, v, parameters), towardLight ? &l : nullptr, towardCamera ? &c : nullptr)
        .value();
}

float toAreaPdf(float pdfOmega, const Vertex& from, const Vertex& to) {
    if (to.atInfinity) return pdfOmega;
    const float c = cosineToward(to, unitDirection(to, from));
    if (from.atInfinity) return pdfOmega * c;
    const float d2 = lengthSquared(to.p - from.p);
    return d2 > 0 ? pdfOmega * c / d2 : 0.0f;
}

Spectrum pathContribution(const Scene& scene, const std::vector<Vertex>& x) {
    const size_t k = x.size() - 1;
    Spectrum f = emittance(scene, x[0], x[1]) * g(scene, x[0], x[1]);
    for (size_t i = 1; i < k; ++i) f *= rho(scene, x[i - 1], x[i], x[i + 1]) * g(scene, x[i], x[i + 1]);
    return f * W(scene, x[k - 1], x[k]);
}

}  // namespace tripath
