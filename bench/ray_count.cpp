// Exact ray counts, and the rays themselves, without touching the renderer. This executable defines rtcIntersect1 and
// rtcOccluded1 itself; the static linker binds the renderer's calls (libtripath_geometry.a) to
// these definitions before it ever looks at libembree3.so, and each one forwards to Embree's real
// function found with dlsym(RTLD_NEXT). The cost is one indirect call and one thread-local
// increment per ray (about a nanosecond, against hundreds for the ray itself), paid equally by the
// whole-sample and the ceiling benchmarks, so the ratio between them is unaffected.
// While a thread has a recorder set (replay.cpp), its rays are also appended there as Embree got
// them, and replayEmbree casts such a list through the real functions alone.
//
// The rays_est estimate (vertices + delivered connections) misses rays that leave the scene and
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
thread_local std::vector<tripath::bench::RecordedRay>* tRecorder = nullptr;

tripath::bench::RecordedRay record(RTCScene scene, const RTCRay& ray, bool shadow) {
    return {scene, {ray.org_x, ray.org_y, ray.org_z}, {ray.dir_x, ray.dir_y, ray.dir_z}, ray.tnear, ray.tfar, shadow};
}

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
    if (tRecorder) [[unlikely]]
        tRecorder->push_back(record(scene, rayhit->ray, false));
    gIntersect(scene, context, rayhit);
}

void rtcOccluded1(RTCScene scene, RTCIntersectContext* context, RTCRay* ray) {
    ++tCounts.occluded;
    if (tRecorder) [[unlikely]]
        tRecorder->push_back(record(scene, *ray, true));
    gOccluded(scene, context, ray);
}

}  // extern "C"

namespace tripath::bench {

RayCounts threadRayCounts() { return tCounts; }

void setRayRecorder(std::vector<RecordedRay>* recorder) { tRecorder = recorder; }

uint64_t replayEmbree(std::span<const RecordedRay> rays) {
    uint64_t hits = 0;
    RTCIntersectContext ctx;
    for (const RecordedRay& r : rays) {
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh;
        RTCRay& ray = rh.ray;
        ray.org_x = r.origin.x;
        ray.org_y = r.origin.y;
        ray.org_z = r.origin.z;
        ray.dir_x = r.dir.x;
        ray.dir_y = r.dir.y;
        ray.dir_z = r.dir.z;
        ray.tnear = r.tnear;
        ray.tfar = r.tfar;
        ray.mask = 0xffffffffu;
        ray.time = 0.0f;
        ray.flags = 0;
        if (r.shadow) {
            gOccluded(r.scene, &ctx, &ray);
            hits += ray.tfar < 0.0f;
        } else {
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            gIntersect(r.scene, &ctx, &rh);
            hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
        }
    }
    return hits;
}

namespace {

// Lane i of a packet: recorded ray r (lanes past the last ray repeat it and stay invalid).
void fillLane(RTCRay8& packet, int i, const RecordedRay& r) {
    packet.org_x[i] = r.origin.x;
    packet.org_y[i] = r.origin.y;
    packet.org_z[i] = r.origin.z;
    packet.dir_x[i] = r.dir.x;
    packet.dir_y[i] = r.dir.y;
    packet.dir_z[i] = r.dir.z;
    packet.tnear[i] = r.tnear;
    packet.tfar[i] = r.tfar;
    packet.mask[i] = 0xffffffffu;
    packet.time[i] = 0.0f;
    packet.flags[i] = 0;
    packet.id[i] = 0;
}

// Casts `rays` in packets of 8 consecutive ones (width 8) or one at a time (width 1);
// cast(valid, ctx, first, n) traces one packet of n rays and returns its hits.
template <class Cast>
uint64_t replayInPackets(std::span<const RecordedRay> rays, int width, Cast&& cast) {
    uint64_t hits = 0;
    alignas(32) int valid[8];
    for (size_t first = 0; first < rays.size(); first += size_t(width)) {
        if (width == 1) {
            hits += replayEmbree(rays.subspan(first, 1));
            continue;
        }
        const size_t n = std::min(rays.size() - first, size_t(width));
        for (size_t i = 0; i < 8; ++i) valid[i] = i < n ? -1 : 0;
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        hits += cast(valid, ctx, first, n);
    }
    return hits;
}

}  // namespace

uint64_t replayClosestHitPackets(std::span<const RecordedRay> rays, int width, bool coherent) {
    alignas(32) RTCRayHit8 packet;
    return replayInPackets(rays, width, [&](const int* valid, RTCIntersectContext& ctx, size_t first, size_t n) {
        ctx.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
        for (int i = 0; i < 8; ++i) {
            fillLane(packet.ray, i, rays[first + std::min(size_t(i), n - 1)]);
            packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        }
        rtcIntersect8(valid, rays[first].scene, &ctx, &packet);
        uint64_t hits = 0;
        for (size_t i = 0; i < n; ++i) hits += packet.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
        return hits;
    });
}

uint64_t replayShadowPackets(std::span<const RecordedRay> rays, int width) {
    alignas(32) RTCRay8 packet;
    return replayInPackets(rays, width, [&](const int* valid, RTCIntersectContext& ctx, size_t first, size_t n) {
        for (int i = 0; i < 8; ++i) fillLane(packet, i, rays[first + std::min(size_t(i), n - 1)]);
        rtcOccluded8(valid, rays[first].scene, &ctx, &packet);
        uint64_t hits = 0;
        for (size_t i = 0; i < n; ++i) hits += packet.tfar[i] < 0.0f;
        return hits;
    });
}

}  // namespace tripath::bench
