// Range search over a fixed set of points: every point within radius r of a query point.
//
// Vertex merging asks this once per camera vertex against all of a pass's light vertices, with
// one radius for the whole pass, so the structure is a hashed uniform grid of cell size 2r built
// by a counting sort (Georgiev et al.'s choice, and what SmallVCM uses): build is two linear passes
// with no allocation per point, and a query reads the 2×2×2 cells that cover the ball, in four
// contiguous runs of points (each two cells next to each other along x: rowOf). A kd-tree
// (nanoflann) would adapt to uneven density, but its build sorts and its queries walk a tree;
// with one fixed radius the grid does strictly less work.
// Hash collisions only add candidates, which the distance test removes; a bucket reached from two
// of those rows is read once. Each point is stored with its payload (what the caller needs to
// use it), so a query touches nothing outside the runs it reads. Points keep their input order
// within a bucket, so queries report them in a fixed order: sums over them do not depend on threads.
#pragma once
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/vec.h"

namespace tripath {

// How many query points one call's reads are overlapped for at once (PointGrid::forEachWithin over a
// span): about what a camera path holds, and as many misses as a core keeps in flight.
inline constexpr int kPointGridBatch = 16;

template <class Payload>
class PointGrid {
public:
    struct Entry {
        Vec3 p;
        Payload payload;
    };

    // Indexes `entries` for queries of radius `radius` > 0.
    PointGrid(std::span<const Entry> entries, float radius)
        : PointGrid(std::span<const std::span<const Entry>>(&entries, 1), radius) {}
    // The same for the entries of several parts, taken in order as if they were one span.
    PointGrid(std::span<const std::span<const Entry>> parts, float radius) : radius_(radius), invCell_(0.5f / radius) {
        size_t n = 0;
        for (std::span<const Entry> part : parts) n += part.size();
        if (n == 0) return;
        // About one bucket per point: short runs without a table much larger than the points.
        const uint32_t buckets = std::bit_ceil(static_cast<uint32_t>(n));
        mask_ = buckets - 1;
        std::vector<uint32_t> bucket(n);
        begin_.assign(size_t(buckets) + 1, 0);
        size_t i = 0;
        for (std::span<const Entry> part : parts)
            for (const Entry& e : part) {
                bucket[i] = bucketOf(cellCoordinate(e.p.x), cellCoordinate(e.p.y), cellCoordinate(e.p.z));
                ++begin_[bucket[i++] + 1];
            }
        for (uint32_t b = 0; b < buckets; ++b) begin_[b + 1] += begin_[b];
        sorted_.resize(n);
        std::vector<uint32_t> next(begin_.begin(), begin_.end() - 1);
        i = 0;
        for (std::span<const Entry> part : parts)
            for (const Entry& e : part) sorted_[next[bucket[i++]]++] = e;
    }

    float radius() const { return radius_; }
    size_t bytes() const { return begin_.capacity() * sizeof(uint32_t) + sorted_.capacity() * sizeof(Entry); }
    // What the constructor takes at its peak for n entries: the grid (a bound and its bucket per
    // entry) and its temporaries (each entry's bucket, each bucket's next slot).
    static size_t buildBytes(size_t n) {
        if (n == 0) return 0;
        const size_t buckets = std::bit_ceil(n);
        return n * (sizeof(Entry) + sizeof(uint32_t)) + (2 * buckets + 1) * sizeof(uint32_t);
    }

    // Calls f(payload) for every point within distance r of p (|q − p|² ≤ r²), in a fixed order.
    template <class F>
    void forEachWithin(Vec3 p, F&& f) const {
        forEachWithin(std::span<const Vec3>(&p, 1), [&](int, const Payload& payload) { f(payload); });
    }

    // Calls f(i, payload) for every point within distance r of each query point qs[i], query by
    // query in the order given, each in a fixed order. The reads are requested in two waves before
    // they are used -- every interval's bounds, then the start of every run -- for up to kBatch
    // queries at once, so that their cache misses overlap.
    static constexpr int kBatch = kPointGridBatch;
    template <class F>
    void forEachWithin(std::span<const Vec3> qs, F&& f) const {
        if (sorted_.empty()) return;
        for (size_t start = 0; start < qs.size(); start += kBatch) {
            const int n = static_cast<int>(std::min<size_t>(kBatch, qs.size() - start));
            Runs runs[kBatch];
            for (int i = 0; i < n; ++i) {
                runs[i].n = intervalsAround(qs[start + i], runs[i].first, runs[i].last);
                for (int b = 0; b < runs[i].n; ++b) {
                    __builtin_prefetch(&begin_[runs[i].first[b]]);
                    __builtin_prefetch(&begin_[runs[i].last[b]]);
                }
            }
            for (int i = 0; i < n; ++i)
                for (int b = 0; b < runs[i].n; ++b) {
                    runs[i].first[b] = begin_[runs[i].first[b]];
                    runs[i].last[b] = begin_[runs[i].last[b]];
                    if (runs[i].first[b] < runs[i].last[b]) __builtin_prefetch(&sorted_[runs[i].first[b]]);
                }
            const float r2 = radius_ * radius_;
            for (int i = 0; i < n; ++i) {
                const Vec3 p = qs[start + i];
                for (int b = 0; b < runs[i].n; ++b)
                    for (uint32_t j = runs[i].first[b]; j < runs[i].last[b]; ++j)
                        if (lengthSquared(sorted_[j].p - p) <= r2) f(static_cast<int>(start) + i, sorted_[j].payload);
            }
        }
    }

private:
    // One query's runs: first and last hold its bucket intervals until their bounds are read.
    static constexpr int kMaxIntervals = 18;  // 3 × 3 rows of cells, each in at most two pieces
    struct Runs {
        int n;
        uint32_t first[kMaxIntervals], last[kMaxIntervals];
    };

    int64_t cellCoordinate(float v) const { return static_cast<int64_t>(std::floor(v * invCell_)); }

    // A row of cells along x lies in consecutive buckets: the row (y, z) is hashed (Teschner et
    // al. 2003's large primes, xor-ed) and x added, so the cells next to each other along x that
    // a query needs are one run of points, read with one pair of bounds.
    uint32_t rowOf(int64_t y, int64_t z) const {
        const uint64_t h = (uint64_t(y) * 19349663u) ^ (uint64_t(z) * 83492791u);
        return static_cast<uint32_t>(h ^ (h >> 32));
    }
    uint32_t bucketOf(int64_t x, int64_t y, int64_t z) const { return (rowOf(y, z) + static_cast<uint32_t>(x)) & mask_; }

    // The bucket intervals [first, last) holding the cells the ball around p touches, none read
    // twice: cells are 2r wide, so the ball's box [p − r, p + r] spans two cells per axis (three
    // only if rounding stretches it across two boundaries); each row of them is one interval, or
    // two where it wraps past the table's end, and intervals that overlap (rows whose hashes lie
    // within a few buckets) are merged. Sorted by first bucket.
    int intervalsAround(Vec3 p, uint32_t first[kMaxIntervals], uint32_t last[kMaxIntervals]) const {
        int64_t lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = cellCoordinate(p[a] - radius_);
            hi[a] = std::min(lo[a] + 2, cellCoordinate(p[a] + radius_));
        }
        // A row wider than the table (a table of one or two buckets) reads the whole table once.
        const uint32_t end = mask_ + 1, cells = std::min(static_cast<uint32_t>(hi[0] - lo[0] + 1), end);
        int n = 0;
        auto add = [&](uint32_t a, uint32_t b) {  // insertion in order of first bucket
            int i = n++;
            for (; i > 0 && first[i - 1] > a; --i) {
                first[i] = first[i - 1];
                last[i] = last[i - 1];
            }
            first[i] = a;
            last[i] = b;
        };
        for (int64_t z = lo[2]; z <= hi[2]; ++z)
            for (int64_t y = lo[1]; y <= hi[1]; ++y) {
                const uint32_t b = bucketOf(lo[0], y, z);
                if (b + cells <= end) {
                    add(b, b + cells);
                } else {
                    add(b, end);
                    add(0, b + cells - end);
                }
            }
        int m = 0;  // merge overlapping intervals
        for (int i = 1; i < n; ++i) {
            if (first[i] <= last[m]) {
                last[m] = std::max(last[m], last[i]);
            } else {
                ++m;
                first[m] = first[i];
                last[m] = last[i];
            }
        }
        return m + 1;
    }

    float radius_, invCell_;
    uint32_t mask_ = 0;            // bucket count − 1 (a power of two)
    std::vector<uint32_t> begin_;  // bucket b holds sorted_[begin_[b] .. begin_[b+1])
    std::vector<Entry> sorted_;    // the points with their payloads, grouped by bucket
};

}  // namespace tripath
