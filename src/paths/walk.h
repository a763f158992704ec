// Subpath generation: random walks from the sensor (camera subpaths) and from an emitter (light
// subpaths), drawing from a random stream or a chain's primary samples (core/rng.h: Sampler). Each vertex gets its throughput beta, and the forward and reverse area pdfs that
// the integrator's MIS weights read (StrategySet::cameraWalkPdfs / lightWalkPdfs).
#pragma once
#include "core/rng.h"
#include "core/sample_stream.h"
#include "paths/mis.h"
#include "paths/vertex.h"

namespace tripath {

struct WalkSettings {
    int maxDepth = 16;  // longest path in segments: camera subpaths get ≤ maxDepth+1 vertices, light ≤ maxDepth
    int rrDepth = 3;    // Russian roulette once a subpath has this many vertices (roulette.h); the front ends default per integrator (integrator.h)
    bool cameraUntilNonDelta = false;  // end camera walks at their first vertex that scatters through no delta lobe
};

// The sensor endpoint z0 of every camera subpath.
Vertex sensorVertex(const Scene& scene);
// A fresh point on an emitter as the endpoint y0 of a light subpath (or of next-event estimation):
// pdfFwd = its pdf in the emitter's measure (area, or solid angle at infinity), beta = 1 / pdfFwd.
template <Sampler S>
Vertex sampleEmitterVertex(const Scene& scene, S& rng);

// The camera subpath of the sensor alone (light tracing's, whose light subpaths join it).
void sensorSubpath(const Scene& scene, Subpath& path);

// A camera subpath's first ray: through raster position `raster`, and, when the render loop has
// traced it already (with its neighbours, in one packet: Scene::intersect8), its direction and hit.
struct CameraRay {
    CameraRay(Vec2 r) : raster(r) {}  // implicit: a raster position alone is a ray still to trace
    CameraRay(Vec2 r, Vec3 d, const std::optional<SurfacePoint>* h) : raster(r), direction(d), hit(h) {}
    Vec2 raster;
    Vec3 direction;                                // camera.direction(raster), when hit is set
    const std::optional<SurfacePoint>* hit = nullptr;
};

// Fills `path` with a camera subpath whose first segment is `ray`. A ray that leaves the scene ends
// the subpath on the environment, a vertex at infinity, when the scene has one. `lightPaths`: the
// pass's N_L, which the sensor's pdf of that segment is over (pass_constants.h).
template <Sampler S>
void cameraSubpath(const Scene& scene, const CameraRay& ray, S& rng, const WalkSettings& settings, WalkPdfs pdfs,
                   double lightPaths, Subpath& path);
// Fills `path` with a light subpath starting from a power-sampled emitter point; from an emitter at
// infinity, its walk starts on the bounding disc facing it (Emitters::beamOrigin), y0.p.
template <Sampler S>
void lightSubpath(const Scene& scene, S& rng, const WalkSettings& settings, WalkPdfs pdfs, Subpath& path);

}  // namespace tripath
