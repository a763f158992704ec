#include "paths/walk.h"

#include <limits>

#include "paths/kernels.h"
#include "paths/primary_samples.h"
#include "paths/roulette.h"
#include "paths/sample_dimensions.h"

namespace tripath {

namespace {

// What a light walk passes for N_L: it never reaches the sensor (a pinhole cannot be hit), the one
// vertex whose pdf reads N_L; were it read, the weights over it would be guarded (mis.h), not wrong.
constexpr double kNoSensor = std::numeric_limits<double>::quiet_NaN();

template <Sampler S>
Vec2 uniform2(S& rng) {
    const float a = rng.uniform();
    return {a, rng.uniform()};
}

Vertex surfaceVertex(const Scene& scene, const SurfacePoint& hit) {
    Vertex v;
    v.kind = Vertex::Kind::Surface;
    v.p = hit.p;
    v.ng = hit.ng;
    v.ns = hit.ns;
    v.triangle = hit.triangle;
    v.bary = hit.bary;
    v.material = &scene.materialOf(hit.triangle);
    v.emitter = scene.emitters().emitterOfTriangle(hit.triangle);
    v.delta = isDelta(*v.material);
    v.continuation = continuationProbability(*v.material);
    v.absorbs = !isBlack(v.material->absorption);
    return v;
}

// f_r × shading correction at v for the directions (wo, wi) of a sample s drawn about the normal
// n: about the pair's normal (shading_normal.h), 0 where the leak mask under it drops either
// direction. That normal is the sampler's for a delta lobe (a mirror reflection's own bend is
// never the stronger; a refraction has none) and for most glossy pairs, whose f_r the sample
// holds already; the others are evaluated afresh. No direction is dropped before this: the pdf
// MIS takes for the sample is the sampler's about n, and must be the density of what the walk
// goes on with.
[[gnu::always_inline]] inline Spectrum scattered(const BsdfParams& bsdf, const Vertex& v, Vec3 n, const BsdfSample& s,
                                                 Vec3 wo, Vec3 wi, Vec3 towardLight, TransportMode mode) {
    if (!s.delta && !(v.ns == v.ng)) [[unlikely]] {
        const Vec3 other = bentNormal(v.ns, v.ng, wi);
        if (dot(other, v.ng) > dot(n, v.ng)) {
            if (!sidesAgree(v, other, wo) || !sidesAgree(v, other, wi)) return Spectrum(0.0f);
            const Frame frame(other);
            return evalBsdf(bsdf, frame.toLocal(wo), frame.toLocal(wi), mode) * shadingCorrection(v, other, towardLight);
        }
    }
    if (!sidesAgree(v, n, wo) || !sidesAgree(v, n, wi)) return Spectrum(0.0f);
    return s.f * shadingCorrection(v, n, towardLight);
}

// Keeps the BSDF parameters of surface vertex v, the path's last, derived here once for every use
// (vertex.h: Subpath). Out of line: scenes that vary none never call it.
[[gnu::noinline]] void keepBsdf(const Scene& scene, Subpath& path, const Vertex& v) {
    std::optional<BsdfParams> varied;
    path.bsdfs.push_back(*bsdfAt(scene, v, varied));
}

// Appends v to the path with, where the scene varies BSDF parameters, v's (a placeholder where it
// scatters nowhere).
[[gnu::always_inline]] inline void push(const Scene& scene, Subpath& path, const Vertex& v) {
    path.vertices.push_back(v);
    if (!scene.variesBsdfs()) return;
    if (v.kind == Vertex::Kind::Surface)
        keepBsdf(scene, path, v);
    else
        path.bsdfs.emplace_back();
}

// Where a camera walk's ray that leaves the scene ends: the environment, in the direction `dir`.
Vertex environmentVertex(const Scene& scene, Vec3 dir) {
    Vertex v;
    v.kind = Vertex::Kind::Emitter;
    v.atInfinity = true;
    v.ns = dir;
    v.emitter = scene.emitters().environment();
    return v;
}

// The area pdfs of the segment just traced from `from` (the path's last vertex) to v, the
// vertex about to be appended: v's pdfFwd, and the pdfRev of the vertex before `from`, which
// `from` would generate having been reached from v. A camera walk goes against the light's
// flow, so v lies on `from`'s light side; a light walk goes with it. `lightPaths`: the pass's N_L,
// which the sensor's pdf is over.
void recordPdfs(const Scene& scene, Subpath& path, Vertex& v, TransportMode mode, double lightPaths) {
    const size_t last = path.size() - 1;
    const Vertex& from = path[last];
    Vertex* beforeFrom = last > 0 ? &path[last - 1] : nullptr;
    const Segment ahead(from, v), behind(from, beforeFrom);
    const bool cameraWalk = mode == TransportMode::Radiance;
    const LocalScattering at(scene, from, SubpathView(path).bsdf(last), cameraWalk ? ahead.towardB() : behind.towardB(),
                             cameraWalk ? behind.towardB() : ahead.towardB());
    v.pdfFwd = ahead.toArea(cameraWalk ? at.pdfTowardLight(lightPaths) : at.pdfTowardCamera(), v);
    if (beforeFrom) {
        const float pdfBack = cameraWalk ? at.pdfTowardCamera() : at.pdfTowardLight(lightPaths);
        beforeFrom->pdfRev = behind.toArea(pdfBack, *beforeFrom);
    }
}

// What scattering at the walk's last vertex `from` (factor `scatter`: f_r × shading correction,
// Le at an emitter, W at the sensor) into the direction it drew with solid-angle pdf `pdf`
// contributes to the throughput of the vertex v it reached:
//     light walk    β(y_j) = β(y_{j−1}) · ρ(y_{j−2} → y_{j−1} → y_j) · g(y_{j−1}, y_j) / p_A(y_j)
//                   (ε(y0 → y1) for the first step);
//     camera walk   β(z_j) = β(z_{j−1}) · ρ(z_j → z_{j−1} → z_{j−2}) · g(z_j, z_{j−1}) / p_A(z_j)
//                   (W(z1 → z0) for the first step),
// with p_A(v) = p_ω |cos θ_v| / r². A light walk's ρ carries the cosines of the segment just
// traced; a camera walk's those of the segment behind `from`, toward the sensor, which the light's
// flow leaves next: the cosines of the camera walk's newest segment belong to the kernel of the
// vertex it reached, known only when a connection or an emitter decides it.
// All cosines are of the rays the walk traced (kernels.h: traced).
Spectrum stepFactor(const Subpath& path, const Vertex& v, Spectrum scatter, float pdf, TransportMode mode) {
    const Vertex& from = path.vertices.back();
    const Segment step(from, v, -v.arrival);
    Spectrum kernel;
    if (mode == TransportMode::Importance)
        kernel = from.kind == Vertex::Kind::Emitter ? emittance(scatter, step) : rho(scatter, step);
    else
        kernel = from.kind == Vertex::Kind::Sensor ? scatter : rho(scatter, traced(from, path[path.size() - 2]));
    return kernel * step.transmittance() * step.gOverArea(pdf, v);
}

// The step of a walk: appends v, which the path's last vertex reached along `dir` (having scattered
// with factor `scatter` and solid-angle pdf `pdf`), with its throughput and the pdfs `pdfs` asks
// for. False, and nothing appended, where the throughput vanishes or is not finite (a grazing hit,
// p_A = 0, or coincident points).
[[gnu::always_inline]] inline bool appendStep(const Scene& scene, Subpath& path, Vertex& v, Vec3 dir, Spectrum beta,
                                              Spectrum scatter, float pdf, TransportMode mode, WalkPdfs pdfs,
                                              double lightPaths) {
    v.arrival = -dir;
    v.beta = beta * stepFactor(path, v, scatter, pdf, mode);
    if (!isFinite(v.beta) || isBlack(v.beta)) return false;
    if (pdfs == WalkPdfs::All || (pdfs == WalkPdfs::AtEmitters && v.emitter >= 0)) recordPdfs(scene, path, v, mode, lightPaths);
    push(scene, path, v);
    return true;
}

// A camera walk's ray that left the scene along `dir` ends on the environment, if there is one.
// Out of line: the walk's loop keeps one copy of the step, for the surfaces it hits.
[[gnu::noinline]] void appendEnvironment(const Scene& scene, Subpath& path, Vec3 dir, Spectrum beta, Spectrum scatter,
                                         float pdf, WalkPdfs pdfs, double lightPaths) {
    Vertex sky = environmentVertex(scene, dir);
    if (sky.emitter >= 0) appendStep(scene, path, sky, dir, beta, scatter, pdf, TransportMode::Radiance, pdfs, lightPaths);
}

// Extends `path` from its last vertex, which scattered with factor `scatter` into `dir` with
// solid-angle pdf `pdf`; `beta` is that vertex's throughput divided by its roulette survival
// probability. The directions are the sampler's and the kernels evaluated with its f_r (a delta
// lobe's f_r and pdf cancel in the ratio); the vertices' pdfs for MIS are recomputed from the
// points (LocalScattering) rather than taken from the sampler: the ray leaves from an offset
// origin, and on short segments the direction between the vertices is not quite the sampled one;
// connections see only the points, so the walks must too. Only the pdfs `pdfs` asks for are
// computed.
// `firstHit`, if set, is what the first ray hits, traced already; `lightPaths` is the pass's N_L.
template <Sampler S>
void randomWalk(const Scene& scene, S& rng, Spectrum beta, Spectrum scatter, float pdf, Vec3 dir, TransportMode mode,
                const WalkSettings& settings, WalkPdfs pdfs, double lightPaths, size_t maxVertices, Subpath& path,
                const std::optional<SurfacePoint>* firstHit = nullptr) {
    while (path.size() < maxVertices) {
        const Vertex& from = path.vertices.back();
        const Vec3 origin = from.onSurface() ? offsetRayOrigin(from.p, from.ng, dir) : from.p;
        const auto hit = firstHit ? *firstHit : scene.intersect(origin, dir);
        firstHit = nullptr;
        if (!hit) {
            if (mode == TransportMode::Radiance) appendEnvironment(scene, path, dir, beta, scatter, pdf, pdfs, lightPaths);
            return;
        }
        // The next vertex's numbers depend on its place in the path alone.
        const int at = static_cast<int>(path.size());
        rng.dimensions(mode == TransportMode::Radiance ? dimensions::cameraScatter(at) : dimensions::lightScatter(at));
        Vertex v = surfaceVertex(scene, *hit);
        if (!appendStep(scene, path, v, dir, beta, scatter, pdf, mode, pdfs, lightPaths)) return;
        if (path.size() == maxVertices || (mode == TransportMode::Radiance && settings.cameraUntilNonDelta && !v.delta)) return;

        const Vec3 wo = normalize(path[path.size() - 2].p - v.p);
        const Vec3 n = bentNormal(v.ns, v.ng, wo);  // the sampler's normal (shading_normal.h)
        const Frame frame(n);
        // Every draw in its own statement: the order of a call's arguments is unspecified, and
        // the image a seed gives must not depend on the compiler.
        const Vec2 u = uniform2(rng);
        const float uc = rng.uniform();
        const BsdfParams& bsdf = *SubpathView(path).bsdf(path.size() - 1);
        const auto bs = sampleBsdf(bsdf, frame.toLocal(wo), u, uc, mode);
        if (!bs || !(bs->pdf > 0)) return;
        const Vec3 wi = frame.toWorld(bs->wi);
        // Radiance flows against a camera walk (light arrives along wi) and with a light walk.
        const Vec3 towardLight = mode == TransportMode::Radiance ? wi : wo;
        scatter = scattered(bsdf, v, n, *bs, wo, wi, towardLight, mode);
        pdf = bs->pdf;
        beta = path.vertices.back().beta;
        const float q = Roulette{settings.rrDepth}.continuation(v, static_cast<int>(path.size()) - 1);
        if (q < 1.0f) {
            if (!(rng.uniform() < q)) return;
            beta = beta / q;
        }
        if (isBlack(scatter)) return;
        dir = wi;
    }
}

}  // namespace

Vertex sensorVertex(const Scene& scene) {
    Vertex z0;
    z0.kind = Vertex::Kind::Sensor;
    z0.p = scene.camera().position();
    z0.ng = scene.camera().forward();
    z0.beta = Spectrum(1.0f);
    z0.pdfFwd = 1.0f;  // a pinhole: the position is certain
    return z0;
}

namespace {

// y0 of the emitter `uc` chooses, at the point `u` draws on it.
Vertex emitterVertex(const Scene& scene, float uc, Vec2 u) {
    const EmitterSample es = scene.emitters().sample(uc, u, scene.triangles());
    const Emitter& e = scene.emitters().all()[es.emitter];
    Vertex y0;
    y0.kind = Vertex::Kind::Emitter;
    y0.p = es.p;
    y0.ng = es.n;
    y0.ns = es.towardLight;
    y0.atInfinity = e.atInfinity();
    y0.delta = e.delta();
    y0.emitter = static_cast<int>(es.emitter);
    y0.triangle = e.triangle;
    y0.bary = es.bary;
    y0.pdfFwd = es.pdfA;
    y0.beta = Spectrum(1.0f / es.pdfA);
    if (e.kind == Emitter::Kind::Triangle) {  // a surface that may close an absorbing volume
        y0.material = &scene.materialOf(e.triangle);
        y0.absorbs = !isBlack(y0.material->absorption);
    }
    return y0;
}

}  // namespace

template <Sampler S>
Vertex sampleEmitterVertex(const Scene& scene, S& rng) {
    const float uc = rng.uniform();
    return emitterVertex(scene, uc, uniform2(rng));
}

void sensorSubpath(const Scene& scene, Subpath& path) {
    path.clear();
    push(scene, path, sensorVertex(scene));
}

template <Sampler S>
void cameraSubpath(const Scene& scene, const CameraRay& ray, S& rng, const WalkSettings& settings, WalkPdfs pdfs,
                   double lightPaths, Subpath& path) {
    sensorSubpath(scene, path);
    const Camera& cam = scene.camera();
    const Vec3 dir = ray.hit ? ray.direction : cam.direction(ray.raster);
    // The pinhole draws a point of the pixel uniformly: W is the pixel's importance and the pdf the
    // per-pixel density (camera.h), both of a direction the camera made (however it rounds at the
    // image's edge). MIS sees the per-pixel pdf over N_L (kernels.h).
    randomWalk(scene, rng, Spectrum(1.0f), Spectrum(cam.importanceDensity(dir)), cam.pixelDensity(dir), dir,
               TransportMode::Radiance, settings, pdfs, lightPaths, static_cast<size_t>(settings.maxDepth) + 1, path, ray.hit);
}

template <Sampler S>
void lightSubpath(const Scene& scene, S& rng, const WalkSettings& settings, WalkPdfs pdfs, Subpath& path) {
    path.clear();
    if (settings.maxDepth < 1) return;
    // The emitter's point and the direction it emits in from one set, so that the light path's
    // starts are stratified in the four dimensions that place its first hit; the emitter and the
    // lobe from another (sample_dimensions.h).
    rng.dimensions(dimensions::kEmitterChoice);
    const float emitter = rng.uniform();
    rng.dimensions(dimensions::kEmitterPoint);
    const Vec2 point = uniform2(rng);
    push(scene, path, emitterVertex(scene, emitter, point));
    Vertex& y0 = path.vertices.back();
    const Emitters& emitters = scene.emitters();
    rng.dimensions(dimensions::kEmissionLobe);
    const float uc = rng.uniform();
    rng.dimensions(dimensions::kEmissionDirection);
    const Vec2 u = uniform2(rng);
    // From an emitter at infinity, light crosses the bounding disc at a point drawn on it: the
    // walk starts there (y0.p), along the emitter's direction.
    if (y0.atInfinity) y0.p = emitters.beamOrigin(y0.ns, u);
    const Vec3 dir = y0.atInfinity ? -y0.ns : emitters.sampleDirection(y0.emitter, y0.ng, u, uc);
    const float pdfDir = emitters.directionPdf(y0.emitter, y0.ng, dir);
    if (!(pdfDir > 0)) return;
    const Spectrum Le = emitters.Le(y0.emitter, y0.ng, dir, y0.bary);
    if (isBlack(Le)) return;
    randomWalk(scene, rng, y0.beta, Le, pdfDir, dir, TransportMode::Importance, settings, pdfs, kNoSensor,
               static_cast<size_t>(settings.maxDepth), path);
}

// The walks for every sampler: the render loop's streams, plain random streams (tests, benchmarks)
// and mlt's chains.
template Vertex sampleEmitterVertex(const Scene&, SampleStream&);
template void cameraSubpath(const Scene&, const CameraRay&, SampleStream&, const WalkSettings&, WalkPdfs, double, Subpath&);
template void lightSubpath(const Scene&, SampleStream&, const WalkSettings&, WalkPdfs, Subpath&);
template Vertex sampleEmitterVertex(const Scene&, Rng&);
template Vertex sampleEmitterVertex(const Scene&, PrimarySamples&);
template void cameraSubpath(const Scene&, const CameraRay&, Rng&, const WalkSettings&, WalkPdfs, double, Subpath&);
template void cameraSubpath(const Scene&, const CameraRay&, PrimarySamples&, const WalkSettings&, WalkPdfs, double, Subpath&);
template void lightSubpath(const Scene&, Rng&, const WalkSettings&, WalkPdfs, Subpath&);
template void lightSubpath(const Scene&, PrimarySamples&, const WalkSettings&, WalkPdfs, Subpath&);

}  // namespace tripath
