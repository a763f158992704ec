#include "geometry/point_grid.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace tripath {

PointGrid::PointGrid(std::span<const Vec3> points, float radius) : radius_(radius), invCell_(0.5f / radius) {
    if (points.empty()) return;
    // About one bucket per point: short runs without a table much larger than the points.
    const uint32_t buckets = std::bit_ceil(static_cast<uint32_t>(std::max<size_t>(points.size(), 1)));
    mask_ = buckets - 1;
    std::vector<uint32_t> bucket(points.size());
    begin_.assign(size_t(buckets) + 1, 0);
    for (size_t i = 0; i < points.size(); ++i) {
        const Vec3 p = points[i];
        bucket[i] = bucketOf(cellCoordinate(p.x), cellCoordinate(p.y), cellCoordinate(p.z));
        ++begin_[bucket[i] + 1];
    }
    for (uint32_t b = 0; b < buckets; ++b) begin_[b + 1] += begin_[b];
    sorted_.resize(points.size());
    index_.resize(points.size());
    std::vector<uint32_t> next(begin_.begin(), begin_.end() - 1);
    for (size_t i = 0; i < points.size(); ++i) {
        const uint32_t j = next[bucket[i]]++;
        sorted_[j] = points[i];
        index_[j] = static_cast<uint32_t>(i);
    }
}

int64_t PointGrid::cellCoordinate(float v) const { return static_cast<int64_t>(std::floor(v * invCell_)); }

uint32_t PointGrid::bucketOf(int64_t x, int64_t y, int64_t z) const {
    // Teschner et al. 2003's spatial hash: three large primes, xor-ed.
    const uint64_t h = (uint64_t(x) * 73856093u) ^ (uint64_t(y) * 19349663u) ^ (uint64_t(z) * 83492791u);
    return static_cast<uint32_t>(h ^ (h >> 32)) & mask_;
}

int PointGrid::bucketsAround(Vec3 p, uint32_t out[27]) const {
    // Cells are 2r wide, so the ball's box [p − r, p + r] spans two cells per axis (three only
    // if rounding stretches it across two boundaries).
    int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        lo[a] = cellCoordinate(p[a] - radius_);
        hi[a] = std::min(lo[a] + 2, cellCoordinate(p[a] + radius_));
    }
    int n = 0;
    for (int64_t z = lo[2]; z <= hi[2]; ++z)
        for (int64_t y = lo[1]; y <= hi[1]; ++y)
            for (int64_t x = lo[0]; x <= hi[0]; ++x) {
                const uint32_t b = bucketOf(x, y, z);
                if (std::find(out, out + n, b) == out + n) out[n++] = b;
            }
    return n;
}

}  // namespace tripath
