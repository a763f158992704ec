#include "paths/multiplexed_target.h"

#include <algorithm>
#include <limits>

#include "paths/strategies.h"

namespace tripath {

namespace {

// A roulette start no walk reaches: the chains' walks never end a path early.
constexpr int kNoRoulette = std::numeric_limits<int>::max();

// The walks of strategy (s, t): a camera subpath of t vertices from a raster position drawn over
// the whole film, and a light subpath of s vertices (s ≥ 2; next-event estimation draws its own
// point at the junction). False where a walk ended short of its length.
bool walkSubpaths(const MultiplexedTarget& target, Strategy st, PrimarySamples& u, TargetPaths& paths, Vec2& raster) {
    const Scene& scene = *target.scene;
    const Camera& cam = scene.camera();
    if (st.t >= 2) {
        u.startStream(PrimarySamples::Stream::Camera);
        const float ux = u.uniform();
        const float uy = u.uniform();
        raster = {ux * float(cam.width()), uy * float(cam.height())};
        const WalkSettings walk{.maxDepth = st.t - 1, .rrDepth = kNoRoulette};
        cameraSubpath(scene, CameraRay(raster), u, walk, WalkPdfs::All, target.pixels, paths.camera);
        if (static_cast<int>(paths.camera.size()) < st.t) return false;
    } else {
        sensorSubpath(scene, paths.camera);
    }
    paths.light.clear();
    if (st.s >= 2) {
        u.startStream(PrimarySamples::Stream::Light);
        const WalkSettings walk{.maxDepth = st.s, .rrDepth = kNoRoulette};
        lightSubpath(scene, u, walk, WalkPdfs::All, paths.light);
        if (static_cast<int>(paths.light.size()) < st.s) return false;
    }
    return true;
}

}  // namespace

// No running sums (mis.h): a weight takes a subpath's sum only from beyond the vertices at walk
// indices below max(1, depth − 1), whose roulette factors the other walk's length decides, and
// the chains' roulette starts beyond every path (kNoRoulette). Each weight steps over its whole
// path with or without them, so recording them would be work that nothing reads.
MisContext multiplexedMisContext(MisHeuristic heuristic, double pixels) {
    return {heuristic, StrategySet{}, Roulette{kNoRoulette}, passConstants(pixels, 0.0f)};
}

PathSample evaluateTarget(const MultiplexedTarget& target, int k, PrimarySamples& u, TargetPaths& paths) {
    PathSample out;
    u.startStream(PrimarySamples::Stream::Strategy);
    const int s = std::min(static_cast<int>(u.uniform() * float(k + 1)), k);
    out.strategy = {s, k + 1 - s};
    if (!walkSubpaths(target, out.strategy, u, paths, out.raster)) return out;
    u.startStream(PrimarySamples::Stream::Strategy);
    const Scene& scene = *target.scene;
    const Connection c = s == 1 ? connectNextEvent(scene, u, paths.camera, out.strategy.t, target.mis)
                                : connect(scene, paths.light, s, paths.camera, out.strategy.t, target.mis);
    out.weightGuarded = c.weightGuarded;
    if (isBlack(c.unweighted)) return out;
    if (out.strategy.t == 1) out.raster = *c.raster;
    const double imageScale = out.strategy.t >= 2 ? target.pixels : 1.0;  // per-pixel estimate → over the image
    out.value = c.weighted() * static_cast<float>(double(k + 1) * imageScale);
    return out;
}

}  // namespace tripath
