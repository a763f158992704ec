#include "paths/light_store.h"

namespace tripath {

void LightStore::append(std::span<const Vertex> path) {
    vertices_.insert(vertices_.end(), path.begin(), path.end());
    begin_.push_back(static_cast<uint32_t>(vertices_.size()));
}

void LightStore::append(const LightStore& other) {
    const uint32_t offset = static_cast<uint32_t>(vertices_.size());
    vertices_.insert(vertices_.end(), other.vertices_.begin(), other.vertices_.end());
    for (size_t i = 1; i < other.begin_.size(); ++i) begin_.push_back(offset + other.begin_[i]);
}

void LightStore::clear() {
    vertices_.clear();
    begin_.assign(1, 0);
}

LightVertexSearch::LightVertexSearch(const LightStore& store, float radius)
    : store_(store), grid_(mergeable(store), radius) {}

std::vector<LightVertexSearch::Grid::Entry> LightVertexSearch::mergeable(const LightStore& store) {
    std::vector<Grid::Entry> out;
    const Vertex* base = store.vertices().data();
    for (size_t i = 0; i < store.paths(); ++i) {
        const std::span<const Vertex> path = store.path(i);
        for (size_t j = 1; j < path.size(); ++j)
            if (!path[j].delta)
                out.push_back({path[j].p, {static_cast<uint32_t>(&path[j] - base), static_cast<uint32_t>(j + 1)}});
    }
    return out;
}

}  // namespace tripath
