// Joining a light subpath prefix (s vertices) and a camera subpath prefix (t vertices) into one
// full path of k = s + t − 1 segments: the strategy (s, t) of docs/design.md §1.
#pragma once
#include <optional>
#include <span>

#include "paths/mis.h"
#include "paths/vertex.h"

namespace tripath {

// A strategy: s light vertices and t camera vertices, joined by a shadow ray (connection: a path of
// k = s + t − 1 segments) or merged (merge.h: the two endpoints are one vertex, k = s + t − 2).
struct Strategy {
    int s = 0, t = 0;
    bool merge = false;
    int length() const { return s + t - (merge ? 2 : 1); }
    auto operator<=>(const Strategy&) const = default;
};

struct Connection {
    Spectrum unweighted{0.0f};      // f(x̄) / p_{s,t}(x̄)
    float weight = 0;               // MIS weight of (s, t) among the enabled strategies, unless measured
    bool weightGuarded = false;     // the weight's pdf ratios were not finite, so it is 0 (mis.h)
    std::optional<Vec2> raster;     // t = 1: the pixel the path lands in (splat there)
    TechniqueSums techniques{};     // where the context measures them, instead of the weight (mis.h's TechniqueMeasure)
    Spectrum weighted() const { return unweighted * weight; }
    void setWeight(MisWeight w) {
        weight = w.value;
        weightGuarded = w.guarded;
    }
};

// Strategy (s, t), t ≥ 1, s + t ≥ 2:
//   s = 0  the camera subpath's last vertex lies on an emitter;
//   s = 1  light[0] is an emitter point sampled on its own (next-event estimation);
//   t = 1  the light subpath's last vertex is connected to the sensor (the result is a splat);
//   else   the two endpoints are joined by a shadow ray.
// The subpaths are only read: what the strategy defines at the junction goes to misWeight apart;
// the endpoints' BSDF parameters are those the subpaths keep (vertex.h).
Connection connect(const Scene& scene, const SubpathView& light, int s, const SubpathView& camera, int t,
                   const MisContext& mis);

}  // namespace tripath
