// Every enabled strategy over one pair of subpaths, and every merge of a camera subpath with the
// pass's light vertices: the loops all integrators share.
//
// The integrators differ only in the subpaths they build and the strategies they switch on
// (docs/design.md §1): PT passes an empty light subpath, LT a camera subpath of the sensor alone.
// Strategy s = 1 always uses an emitter point sampled afresh (next-event estimation), so PT has
// it without a light subpath; its pdf is the same as that of a light subpath's first vertex.
#pragma once
#include <algorithm>

#include "core/rng.h"
#include "core/stats.h"
#include "paths/connect.h"
#include "paths/light_store.h"
#include "paths/merge.h"
#include "paths/sample_dimensions.h"
#include "paths/walk.h"

namespace tripath {

inline constexpr Counter kRangeQueries{Event::RangeQueries};
inline constexpr Counter kMerges{Event::Merges};

// Strategy (1, t): next-event estimation from a fresh emitter point.
template <Sampler S>
Connection connectNextEvent(const Scene& scene, S& rng, const SubpathView& camera, int t, const MisContext& mis) {
    rng.dimensions(dimensions::nextEvent(t - 1));
    const Vertex y0 = sampleEmitterVertex(scene, rng);
    return connect(scene, SubpathView(std::span<const Vertex>(&y0, 1)), 1, camera, t, mis);  // y0 emits: no BSDF
}

// Calls sink(strategy, connection) for each enabled (s, t) with t ≥ firstT, 1 ≤ k = s + t − 1 ≤
// maxDepth and a non-zero contribution. (A camera subpath of the sensor alone gives the t = 1
// strategies only, the splats of light tracing.)
template <Sampler S, class Sink>
void evaluateStrategies(const Scene& scene, const SubpathView& light, const SubpathView& camera, int firstT, S& rng,
                        int maxDepth, const MisContext& mis, Sink&& sink) {
    const int nl = static_cast<int>(light.size()), nc = static_cast<int>(camera.size());
    for (int t = firstT; t <= nc; ++t) {
        const int sMax = std::min(std::max(nl, 1), maxDepth + 1 - t);
        for (int s = 0; s <= sMax; ++s) {
            if (s + t < 2 || !mis.strategies.enabled(s, t)) continue;
            // Initialised from the call rather than assigned: no copy of the Connection.
            const Connection c = s == 1 ? connectNextEvent(scene, rng, camera, t, mis)
                                        : connect(scene, light, s, camera, t, mis);
            if (!isBlack(c.unweighted)) sink(Strategy{s, t}, c);
        }
    }
}

// Calls sink(strategy, merge) for each merge of a non-delta camera vertex z_{t−1} (t ≥ 2) on a
// surface with a light vertex the search finds within its radius, with k = s + t − 2 ≤ maxDepth and
// a non-zero contribution, in a fixed order.
template <class Sink>
void evaluateMerges(const Scene& scene, const LightVertexSearch& search, const SubpathView& camera, int maxDepth,
                    const MisContext& mis, Sink&& sink) {
    // The camera vertices that merge, queried together so that the range search overlaps their
    // memory reads (LightVertexSearch::forEachWithin), as many at a time as it overlaps.
    constexpr int kBatch = LightVertexSearch::kQueriesAtOnce;
    Vec3 points[kBatch];
    int ts[kBatch];
    const int last = std::min(static_cast<int>(camera.size()), maxDepth);
    for (int t = 2; t <= last;) {
        int n = 0;
        for (; t <= last && n < kBatch; ++t)
            if (!camera[t - 1].delta && !camera[t - 1].atInfinity) {
                points[n] = camera[t - 1].p;
                ts[n++] = t;
            }
        kRangeQueries.add(uint64_t(n));
        search.forEachWithin(std::span<const Vec3>(points, n), [&](int query, std::span<const Vertex> light, int s) {
            const int tq = ts[query];
            if (s + tq - 2 > maxDepth) return;
            kMerges.add();
            const Connection c = merge(scene, light, s, camera, tq, mis);
            if (!isBlack(c.unweighted)) sink(Strategy{s, tq, true}, c);
        });
    }
}

}  // namespace tripath
