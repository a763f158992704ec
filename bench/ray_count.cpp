// Exact ray counts without touching the renderer. This executable defines rtcIntersect1 and
// rtcOccluded1 itself; the static linker binds the renderer's calls (libtripath_geometry.a) to
// these definitions before it ever looks at libembree3.so, and each one forwards to Embree's real
// function found with dlsym(RTLD_NEXT). The cost is one indirect call and one thread-local
// increment per ray (about a nanosecond, against hundreds for the ray itself), paid equally by the
// whole-sample and the ceiling benchmarks, so the ratio between them is unaffected.
//
// The brief's estimate (vertices + delivered connections) misses rays that leave the scene and
// shadow rays that turn out blocked; samples.cpp reports both so the README can show the gap.
#include <dlfcn.h>
#include <embree3/rtcore.h>

#include <cstdio>
#include <cstdlib>

#include "bench_scenes.h"

namespace {

using IntersectFn = void (*)(RTCScene, RTCIntersectContext*, RTCRayHit*);
using OccludedFn = void (*)(RTCScene, RTCIntersectContext*, RTCRay*);

thread_local tripath::bench::RayCounts tCounts;

template <class Fn>
Fn realEmbree(const char* name) {
    void* f = dlsym(RTLD_NEXT, name);
    if (!f) {
        // Without the real function there is nothing sensible to measure: say so and stop.
        std::fprintf(stderr, "tripath_bench: cannot find Embree's %s: %s\n", name, dlerror());
        std::abort();
    }
    return reinterpret_cast<Fn>(f);
}

// Resolved during static initialisation, before main and therefore before any ray is cast, so
// the hot path reads a plain pointer with no first-call guard.
const IntersectFn gIntersect = realEmbree<IntersectFn>("rtcIntersect1");
const OccludedFn gOccluded = realEmbree<OccludedFn>("rtcOccluded1");

}  // namespace

extern "C" {

void rtcIntersect1(RTCScene scene, RTCIntersectContext* context, RTCRayHit* rayhit) {
    ++tCounts.intersect;
    gIntersect(scene, context, rayhit);
}

void rtcOccluded1(RTCScene scene, RTCIntersectContext* context, RTCRay* ray) {
    ++tCounts.occluded;
    gOccluded(scene, context, ray);
}

}  // extern "C"

namespace tripath::bench {

RayCounts threadRayCounts() { return tCounts; }

}  // namespace tripath::bench
