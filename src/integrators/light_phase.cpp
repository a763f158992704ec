#include "integrators/light_phase.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/stats.h"

namespace tripath {

namespace {
constexpr Counter kLightVertices{Event::LightVertices};
}  // namespace

Pass LightPhase::run(const Scene& scene, const Integrator& integrator, uint64_t index, uint64_t seed,
                     StreamDomain cameraDomain) {
    Pass pass;
    pass.index = index;
    if (!firstRadius_) firstRadius_ = integrator.firstMergeRadius(scene);
    const PassConstants constants = passConstants(integrator.lightPaths(scene), integrator.mergeRadius(*firstRadius_, index));
    pass.mis = integrator.misContext(constants);
    search_.reset();
    if (!integrator.hasLightPhase()) return pass;

    const uint64_t paths = static_cast<uint64_t>(constants.lightPaths);
    const uint64_t domain = static_cast<uint64_t>(lightPathDomain(cameraDomain));
    const WalkPdfs pdfs = integrator.strategies().lightWalkPdfs();
    const WalkSettings& walk = integrator.settings().walk;
    store_.reset(paths);
    const bool merges = constants.radius > 0;
    mergeable_.resize(merges ? store_.chunks() : 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, store_.chunks(), 1), [&](const tbb::blocked_range<size_t>& r) {
        thread_local Subpath path;
        enrolThread();
        const PhaseScope scope(Phase::LightPaths);
        for (size_t c = r.begin(); c < r.end(); ++c) {
            LightStore::Chunk& chunk = store_.chunk(c);
            const uint64_t first = c * LightStore::kPathsPerChunk;
            for (uint64_t i = first; i < std::min(paths, first + LightStore::kPathsPerChunk); ++i) {
                Rng rng(seed, domain, index * paths + i);
                lightSubpath(scene, rng, walk, pdfs, path);
                recordRunningSums(path.vertices, true, pass.mis);
                kLightVertices.add(path.size());
                chunk.append(path);
            }
            if (merges) {
                mergeable_[c].clear();
                LightVertexSearch::mergeable(chunk, mergeable_[c]);
            }
        }
    });
    pass.light = &store_;
    if (merges) {
        const PhaseScope scope(Phase::MergeIndex);
        search_.emplace(mergeable_, constants.radius);
        pass.search = &*search_;
    }
    return pass;
}

}  // namespace tripath
