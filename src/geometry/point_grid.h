// Range search over a fixed set of points: every point within radius r of a query point.
//
// Vertex merging asks this once per camera vertex against all of a pass's light vertices, with
// one radius for the whole pass, so the structure is a hashed uniform grid of cell size 2r built
// by a counting sort (Georgiev et al.'s choice, and what SmallVCM uses): build is two linear passes
// with no allocation per point, and a query reads the 2×2×2 cells that cover the ball, each a
// contiguous run of points. A kd-tree (nanoflann) would adapt to uneven density, but its build
// sorts and its queries walk a tree; with one fixed radius the grid does strictly less work.
// Hash collisions only add candidates, which the distance test removes; a bucket reached from two
// of those cells is read once. Points keep their input order within a bucket, so queries
// report them in a fixed order: sums over them do not depend on threads.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/vec.h"

namespace tripath {

class PointGrid {
public:
    // Indexes `points` (copied) for queries of radius `radius` > 0.
    PointGrid(std::span<const Vec3> points, float radius);

    float radius() const { return radius_; }
    // Calls f(i) for every input point i with |points[i] − p|² ≤ r², in a fixed order.
    template <class F>
    void forEachWithin(Vec3 p, F&& f) const {
        if (sorted_.empty()) return;
        uint32_t buckets[27];
        const int n = bucketsAround(p, buckets);
        const float r2 = radius_ * radius_;
        for (int b = 0; b < n; ++b)
            for (uint32_t j = begin_[buckets[b]]; j < begin_[buckets[b] + 1]; ++j)
                if (lengthSquared(sorted_[j] - p) <= r2) f(index_[j]);
    }

private:
    // The distinct buckets of the cells the ball around p touches (2×2×2; 3 on an axis only
    // where rounding puts p ± r on either side of two cell boundaries).
    int bucketsAround(Vec3 p, uint32_t out[27]) const;
    uint32_t bucketOf(int64_t x, int64_t y, int64_t z) const;
    int64_t cellCoordinate(float v) const;

    float radius_, invCell_;
    uint32_t mask_ = 0;              // bucket count − 1 (a power of two)
    std::vector<uint32_t> begin_;    // bucket b holds sorted_[begin_[b] .. begin_[b+1])
    std::vector<Vec3> sorted_;       // the points, grouped by bucket
    std::vector<uint32_t> index_;    // their input indices
};

}  // namespace tripath
