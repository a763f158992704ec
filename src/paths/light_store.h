// A pass's light phase, stored: the N_L light subpaths of one pass, traced before any camera
// sample, kept read-only while the camera samples connect to them and merge with them.
//
// Paths are stored end to end in chunks of kPathsPerChunk consecutive light paths, each chunk one
// flat array; a chunk is filled by one task, so the light phase needs no copy to put its paths in
// order, and the arrays keep their capacity from pass to pass (no allocation once warm). The
// store is the same whatever thread traced which chunk. Camera sample i connects to light path
// i mod N_L (bdpt, vcm; PixelSampleIntegrator::sample); merges search every stored vertex at once
// (LightVertexSearch). Nothing writes
// into a stored vertex after the light phase: MIS reads the subpaths and takes what a strategy
// defines at its junction apart (mis.h), so all threads can share the store.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "paths/point_grid.h"
#include "paths/vertex.h"

namespace tripath {

class LightStore {
public:
    static constexpr size_t kPathsPerChunk = 1024;

    // Light paths in order, each of its chunk's paths appended in turn by one writer, with the
    // BSDF parameters their walks kept (in a scene that varies them: vertex.h), indexed alike.
    class Chunk {
    public:
        void clear() {
            vertices_.clear();
            bsdfs_.clear();
            begin_.assign(1, 0);
        }
        void append(const SubpathView& path) {
            vertices_.insert(vertices_.end(), path.vertices.begin(), path.vertices.end());
            bsdfs_.insert(bsdfs_.end(), path.bsdfs.begin(), path.bsdfs.end());
            begin_.push_back(static_cast<uint32_t>(vertices_.size()));
        }
        size_t paths() const { return begin_.size() - 1; }
        SubpathView path(size_t i) const {
            const size_t first = begin_[i], n = begin_[i + 1] - first;
            return SubpathView({vertices_.data() + first, n}, bsdfs_.empty() ? std::span<const BsdfParams>()
                                                                             : std::span(bsdfs_.data() + first, n));
        }
        size_t vertices() const { return vertices_.size(); }
        size_t bytes() const {
            return vertices_.capacity() * sizeof(Vertex) + bsdfs_.capacity() * sizeof(BsdfParams) +
                   begin_.capacity() * sizeof(uint32_t);
        }

    private:
        std::vector<Vertex> vertices_;
        std::vector<BsdfParams> bsdfs_;   // one per vertex, or none
        std::vector<uint32_t> begin_{0};  // path i holds vertices_[begin_[i] .. begin_[i+1])
    };

    // Empties the store and makes room for `paths` light paths, in chunks to be filled in order.
    void reset(size_t paths);
    size_t chunks() const { return chunks_.size(); }
    Chunk& chunk(size_t c) { return chunks_[c]; }
    const Chunk& chunk(size_t c) const { return chunks_[c]; }

    size_t paths() const { return paths_; }
    SubpathView path(size_t i) const { return chunks_[i / kPathsPerChunk].path(i % kPathsPerChunk); }
    size_t vertices() const;
    size_t bytes() const;
    // What a store of `paths` light paths, `vertices` vertices and `bsdfs` BSDF parameters in all
    // (kept beside vertices where textures or vertex colours vary them) takes.
    static uint64_t bytesFor(double paths, double vertices, double bsdfs) {
        return static_cast<uint64_t>(
            std::ceil(vertices * sizeof(Vertex) + bsdfs * sizeof(BsdfParams) + paths * sizeof(uint32_t)));
    }

private:
    std::vector<Chunk> chunks_;
    size_t paths_ = 0;
};

// Range search over the stored light vertices a camera vertex can merge with: those a light walk
// reached (index ≥ 1 in their path; the emitter point y0 is where light starts, not a vertex it
// arrives at) that scatter through no delta lobe (a merge evaluates the BSDF there).
class LightVertexSearch {
public:
    struct Candidate {
        const Vertex* vertex;  // in the store
        uint32_t s;            // its index in its light subpath, plus one
    };
    using Entry = PointGrid<Candidate>::Entry;
    // Appends the mergeable vertices of one chunk of the store to `out`, in the chunk's order. The
    // light phase calls it in the task that traced the chunk, while the chunk's vertices are
    // still in that core's cache.
    static void mergeable(const LightStore::Chunk& chunk, std::vector<Entry>& out);
    // Indexes the mergeable vertices of every chunk of a store (mergeable's output per chunk,
    // in chunk order) for queries of radius `radius`.
    LightVertexSearch(std::span<const std::vector<Entry>> chunks, float radius);
    float radius() const { return grid_.radius(); }
    size_t bytes() const { return grid_.bytes(); }
    // What building one over `entries` mergeable vertices takes at its peak.
    static uint64_t bytesFor(size_t entries) { return PointGrid<Candidate>::buildBytes(entries); }
    // Calls f(i, prefix, s) for each mergeable light vertex within the radius of each query point
    // qs[i], query by query in the order given, each in a fixed order: `prefix` is its light
    // subpath up to and including it, which is y_{s−1} of that prefix. The vertices found, scattered
    // over the store, are gathered and their lines requested before the first is used, so that
    // their reads overlap (as the grid's own do: PointGrid).
    // How many query points the grid's reads overlap for at once: a caller gathering points for
    // forEachWithin gains nothing from more.
    static constexpr int kQueriesAtOnce = kPointGridBatch;
    template <class F>
    void forEachWithin(std::span<const Vec3> qs, F&& f) const {
        constexpr int kBatch = 32;
        struct Found {
            int query;
            Candidate c;
        } found[kBatch];
        int n = 0;
        auto flush = [&] {
            for (int i = 0; i < n; ++i)
                f(found[i].query, std::span<const Vertex>(found[i].c.vertex + 1 - found[i].c.s, found[i].c.s), int(found[i].c.s));
            n = 0;
        };
        grid_.forEachWithin(qs, [&](int query, Candidate c) {
            // The vertex and the three before it, what a merge and its weight read (merge.cpp,
            // mis.h): the reference connection's junction, and the weight's steps up to the
            // vertex whose running sum it takes.
            const uintptr_t from = reinterpret_cast<uintptr_t>(c.vertex - std::min<uint32_t>(c.s - 1, 3)) & ~uintptr_t(63);
            for (uintptr_t line = from; line < reinterpret_cast<uintptr_t>(c.vertex + 1); line += 64)
                __builtin_prefetch(reinterpret_cast<const void*>(line));
            found[n++] = {query, c};
            if (n == kBatch) flush();
        });
        flush();
    }
    // The same for one query point: f(prefix, s).
    template <class F>
    void forEachWithin(Vec3 p, F&& f) const {
        forEachWithin(std::span<const Vec3>(&p, 1), [&](int, std::span<const Vertex> prefix, int s) { f(prefix, s); });
    }

private:
    PointGrid<Candidate> grid_;
};

}  // namespace tripath
