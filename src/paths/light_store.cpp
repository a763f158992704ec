#include "paths/light_store.h"

namespace tripath {

void LightStore::reset(size_t paths) {
    paths_ = paths;
    chunks_.resize((paths + kPathsPerChunk - 1) / kPathsPerChunk);
    for (Chunk& c : chunks_) c.clear();
}

size_t LightStore::vertices() const {
    size_t n = 0;
    for (const Chunk& c : chunks_) n += c.vertices();
    return n;
}

size_t LightStore::bytes() const {
    size_t n = 0;
    for (const Chunk& c : chunks_) n += c.bytes();
    return n;
}

LightVertexSearch::LightVertexSearch(const LightStore& store, float radius) : grid_(mergeable(store), radius) {}

std::vector<LightVertexSearch::Grid::Entry> LightVertexSearch::mergeable(const LightStore& store) {
    std::vector<Grid::Entry> out;
    out.reserve(store.vertices());
    for (size_t i = 0; i < store.paths(); ++i) {
        const std::span<const Vertex> path = store.path(i);
        for (size_t j = 1; j < path.size(); ++j)
            if (!path[j].delta) out.push_back({path[j].p, {&path[j], static_cast<uint32_t>(j + 1)}});
    }
    return out;
}

}  // namespace tripath
