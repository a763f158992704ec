// A pass's light phase, stored: the N_L light subpaths of one pass, traced before any camera
// sample, kept read-only while the camera samples connect to them and merge with them.
//
// Paths lie end to end in one flat array in light-path order, so the store is the same whatever
// thread traced which path. Camera sample i connects to light path i (bdpt, lt, vcm); merges
// search every stored vertex at once (LightVertexSearch). Nothing writes into a stored vertex
// after the light phase: MIS reads the subpaths and takes what a strategy defines at its junction
// apart (mis.h), so all threads can share the store.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "geometry/point_grid.h"
#include "paths/vertex.h"

namespace tripath {

class LightStore {
public:
    // Appends the next light path (possibly empty).
    void append(std::span<const Vertex> path);
    // Appends every path of `other`, in order.
    void append(const LightStore& other);
    void clear();
    size_t paths() const { return begin_.size() - 1; }
    std::span<const Vertex> path(size_t i) const {
        return {vertices_.data() + begin_[i], vertices_.data() + begin_[i + 1]};
    }
    const std::vector<Vertex>& vertices() const { return vertices_; }
    size_t bytes() const { return vertices_.capacity() * sizeof(Vertex) + begin_.capacity() * sizeof(uint32_t); }

private:
    std::vector<Vertex> vertices_;
    std::vector<uint32_t> begin_{0};  // path i holds vertices_[begin_[i] .. begin_[i+1])
};

// Range search over the stored light vertices a camera vertex can merge with: those a light walk
// reached (index ≥ 1 in their path; the emitter point y0 is where light starts, not a vertex it
// arrives at) that scatter through no delta lobe (a merge evaluates the BSDF there).
class LightVertexSearch {
public:
    LightVertexSearch(const LightStore& store, float radius);
    float radius() const { return grid_.radius(); }
    size_t bytes() const { return grid_.bytes(); }
    // Calls f(prefix, s) for each mergeable light vertex within the radius of p, in a fixed order:
    // `prefix` is its light subpath up to and including it, which is y_{s−1} of that prefix.
    template <class F>
    void forEachWithin(Vec3 p, F&& f) const {
        grid_.forEachWithin(p, [&](Candidate c) {
            const Vertex* y = store_.vertices().data() + c.vertex;
            f(std::span<const Vertex>(y + 1 - c.s, c.s), static_cast<int>(c.s));
        });
    }

private:
    struct Candidate {
        uint32_t vertex;  // its index in the store's flat array
        uint32_t s;       // its index in its light subpath, plus one
    };
    using Grid = PointGrid<Candidate>;
    static std::vector<Grid::Entry> mergeable(const LightStore& store);
    const LightStore& store_;
    Grid grid_;
};

}  // namespace tripath
