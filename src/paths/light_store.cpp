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

namespace {

using Entry = LightVertexSearch::Entry;

std::vector<std::span<const Entry>> spans(std::span<const std::vector<Entry>> chunks) { return {chunks.begin(), chunks.end()}; }

}  // namespace

LightVertexSearch::LightVertexSearch(std::span<const std::vector<Entry>> chunks, float radius)
    : grid_(spans(chunks), radius) {}

void LightVertexSearch::mergeable(const LightStore::Chunk& chunk, std::vector<Entry>& out) {
    for (size_t i = 0; i < chunk.paths(); ++i) {
        const std::span<const Vertex> path = chunk.path(i).vertices;
        for (size_t j = 1; j < path.size(); ++j)
            if (!path[j].delta) out.push_back({path[j].p, {&path[j], static_cast<uint32_t>(j + 1)}});
    }
}

}  // namespace tripath
