// What the bench files share: scenes built once per process and cached, the TBB arena per thread
// count that both the whole-sample and the ray-ceiling benchmarks run in (so their rays/s compare
// like with like), per-thread ray counters, and readings of /proc/self/status.
#pragma once
#include <tbb/task_arena.h>

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "geometry/scene.h"

namespace tripath::bench {

// Every cached scene is built for this film: the size of the 512×512 renders the README times.
constexpr int kWidth = 512, kHeight = 512;

// Cache keys: a built-in scene name ("cornell", "veach-mis", …), tessellatedKey(n), or the path
// of a .gltf or .glb file, which is lit by a white sky (`--environment 1,1,1`).
std::string tessellatedKey(size_t triangles);
// The scene for a key, built on first use (outside any timed region) and kept for the process.
const Scene& cachedScene(const std::string& key);

// The scenes whole samples and the ray ceiling are measured on: (label, cache key).
inline std::vector<std::pair<const char*, std::string>> sampleScenes() {
    return {{"cornell", "cornell"}, {"cornell-spheres", "cornell-spheres"}, {"veach-mis", "veach-mis"},
            {"tess-1M", tessellatedKey(1'000'000)}};
}

// What building a cached scene cost. The peak is the process's resident high-water mark, reset
// just before the build (Linux: writing 5 to /proc/self/clear_refs), so it is the peak during the
// build on top of whatever the process already held.
struct BuildStats {
    double seconds = 0;
    long rssBeforeKiB = 0, rssAfterKiB = 0, peakKiB = 0;
    bool peakWasReset = false;
    size_t triangles = 0;
};
const BuildStats& buildStats(const std::string& key);

// A field of /proc/self/status in KiB ("VmRSS", "VmHWM"), or -1.
long procStatusKiB(const char* field);

// Rays cast by this thread since it started, counted by interposing Embree's rtcIntersect1 and
// rtcOccluded1 (ray_count.cpp): the renderer is not modified and does not know.
struct RayCounts {
    uint64_t intersect = 0, occluded = 0;
    uint64_t total() const { return intersect + occluded; }
};
RayCounts threadRayCounts();
inline RayCounts operator-(RayCounts a, RayCounts b) { return {a.intersect - b.intersect, a.occluded - b.occluded}; }
inline RayCounts& operator+=(RayCounts& a, RayCounts b) {
    a.intersect += b.intersect;
    a.occluded += b.occluded;
    return a;
}

// A ray as the renderer handed it to Embree (rtcIntersect1 or rtcOccluded1).
struct RecordedRay {
    RTCSceneTy* scene;
    Vec3 origin, dir;
    float tnear, tfar;
    bool shadow;
};
// While set (non-null), the calling thread's rays are appended to `recorder`.
void setRayRecorder(std::vector<RecordedRay>* recorder);
// Casts the rays through Embree's own functions alone, in order, on the calling thread; returns
// the hits (blocked shadow rays count as hits).
uint64_t replayEmbree(std::span<const RecordedRay> rays);
// Casts closest-hit rays `width` at a time (1, or 8 through rtcIntersect8, with Embree's coherent
// or incoherent flag).
uint64_t replayClosestHitPackets(std::span<const RecordedRay> rays, int width, bool coherent);
// Casts shadow rays `width` at a time (1, or 8 through rtcOccluded8), in order; returns the blocked ones.
uint64_t replayShadowPackets(std::span<const RecordedRay> rays, int width);

// A TBB arena of exactly `threads` workers (the caller included), one per thread count, so the
// 1- and 2-thread variants of a benchmark differ only in that number.
tbb::task_arena& arenaFor(int threads);

// The film is visited in 64×64 blocks: contiguous enough for the cache behaviour of the render
// loop's 16×16 tiles, and block i of a run is (37 i) mod 64 so that a short run still spreads
// over the whole image instead of sampling only its top rows.
constexpr int kBlock = 64;
constexpr int kBlocksX = kWidth / kBlock, kBlocksY = kHeight / kBlock, kBlocks = kBlocksX * kBlocksY;
constexpr int kBlockPixels = kBlock * kBlock;
inline int blockOfIteration(uint64_t iteration) { return static_cast<int>((iteration * 37) % kBlocks); }

}  // namespace tripath::bench
