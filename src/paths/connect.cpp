#include "paths/connect.h"

#include "core/stats.h"
#include "paths/kernels.h"

namespace tripath {

namespace {

constexpr Counter kConnections{Event::Connections};
constexpr Counter kEmitterHits{Event::EmitterHits};

// s = 0: the camera subpath's last vertex pt lies on an emitter, which is the light's start.
// Its reverse pdf is the emitter sampler's, and the vertex before it would have been generated
// by an emission direction from pt. Whatever pt's material, it emits here: it is x0, not a
// scatterer (mis.h).
Connection emitterHit(const Scene& scene, std::span<const Vertex> light, std::span<const Vertex> camera, int t,
                      const MisContext& mis) {
    Connection c;
    const Vertex& pt = camera[t - 1];
    const Vertex& ptMinus = camera[t - 2];
    if (pt.emitter < 0) return c;
    kEmitterHits.add();
    const Segment toCamera(pt, ptMinus);
    const LocalScattering at(scene, pt, nullptr, nullptr, toCamera.towardB());  // an emitter: no BSDF
    c.unweighted = pt.beta * emittance(at.value(), traced(pt, ptMinus));  // ε(pt → ptMinus)
    if (isBlack(c.unweighted)) return c;
    const StrategySet& reads = mis.junctionStrategies();
    Junction junction;
    if (reads.readsCameraPdfs(t - 1, 0, t)) junction.cameraEnd = scene.emitters().pdfA(pt.emitter, pt.ns);
    if (reads.readsCameraPdfs(t - 2, 0, t)) junction.cameraBeforeEnd = toCamera.toArea(at.pdfTowardCamera(), ptMinus);
    if (mis.measure.on)
        c.techniques = connectionTechniqueSums(light, 0, camera, t, junction, mis.measured());
    else
        c.setWeight(misWeight(light, 0, camera, t, junction, mis));
    return c;
}

// s ≥ 1: the endpoints qs (light side) and pt (camera side) joined by a shadow ray. f/p of the
// joined path is the two prefixes' throughputs times the kernels the connecting segment
// completes (kernels.h): ε(qs → pt) or ρ(qs−1 → qs → pt), g(qs, pt), and ρ(qs → pt → pt−1) or
// W(qs → pt). The segment and each endpoint's local geometry are computed once, and of the four
// reverse pdfs the connection defines only those the strategy set's weight reads are computed.
Connection join(const Scene& scene, const SubpathView& light, int s, const SubpathView& camera, int t,
                const MisContext& mis) {
    Connection c;
    const Vertex& qs = light[s - 1];
    const Vertex* qsMinus = s > 1 ? &light[s - 2] : nullptr;
    const Vertex& pt = camera[t - 1];
    const Vertex* ptMinus = t > 1 ? &camera[t - 2] : nullptr;
    const int k = s + t - 1;
    if (scattersDelta(qs, s - 1, k) || scattersDelta(pt, s, k)) return c;  // no shadow ray joins a delta lobe
    if (pt.atInfinity) return c;  // a camera ray that left the scene: only s = 0 reaches its end
    kConnections.add();
    const Segment segment(qs, pt);
    if (t == 1) {
        c.raster = scene.camera().raster(-segment.direction());
        if (!c.raster) return c;
    }
    const Vec3 towardQ = -segment.direction();
    const Segment backQ(qs, qsMinus), backP(pt, ptMinus);  // to each endpoint's own predecessor
    const LocalScattering atQ(scene, qs, light.bsdf(s - 1), backQ.towardB(), segment.towardB());
    const LocalScattering atP(scene, pt, camera.bsdf(t - 1), &towardQ, backP.towardB());
    const Spectrum kernelQ = s == 1 ? emittance(atQ, segment) : rho(atQ, segment);
    const Spectrum kernelP = t == 1 ? Spectrum(W(atP)) : rho(atP.value(), traced(pt, *ptMinus));
    c.unweighted = qs.beta * kernelQ * g(segment) * kernelP * pt.beta;
    if (isBlack(c.unweighted)) return c;
    if (!visible(scene, qs, pt)) {
        c.unweighted = Spectrum(0.0f);
        return c;
    }
    const StrategySet& reads = mis.junctionStrategies();
    Junction junction;
    if (reads.readsCameraPdfs(t - 1, s, t)) junction.cameraEnd = segment.toArea(atQ.pdfTowardCamera(), pt);
    if (reads.readsCameraPdfs(t - 2, s, t)) junction.cameraBeforeEnd = backP.toArea(atP.pdfTowardCamera(), *ptMinus);
    if (reads.readsLightPdfs(s - 1, s, t)) junction.lightEnd = segment.toArea(atP.pdfTowardLight(mis.constants.lightPaths), qs);
    if (reads.readsLightPdfs(s - 2, s, t)) junction.lightBeforeEnd = backQ.toArea(atQ.pdfTowardLight(mis.constants.lightPaths), *qsMinus);
    if (mis.measure.on)
        c.techniques = connectionTechniqueSums(light.vertices, s, camera.vertices, t, junction, mis.measured());
    else
        c.setWeight(misWeight(light.vertices, s, camera.vertices, t, junction, mis));
    return c;
}

}  // namespace

Connection connect(const Scene& scene, const SubpathView& light, int s, const SubpathView& camera, int t,
                   const MisContext& mis) {
    return s == 0 ? emitterHit(scene, light.vertices, camera.vertices, t, mis) : join(scene, light, s, camera, t, mis);
}

}  // namespace tripath
