#include "integrators/light_phase.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/stats.h"

namespace tripath {

namespace {
constexpr Counter kLightVertices{Event::LightVertices};
}  // namespace

SampleStream lightPathStream(const StreamSource& source, uint64_t index, uint64_t paths, uint64_t j) {
    const StreamDomain domain = lightPathDomain(source.domain);
    return SampleStream(source.sampler, source.sobolSeed(), domain, j, index,
                        Rng(source.seed, static_cast<uint64_t>(domain), index * paths + j));
}

LightPathSurvey LightPhase::survey(const Scene& scene, const PixelSampleIntegrator& integrator, uint64_t index,
                                   const StreamSource& source) {
    LightPathSurvey out;
    if (!integrator.hasLightPhase()) return out;
    const uint64_t paths = static_cast<uint64_t>(integrator.lightPaths(scene));
    const uint64_t traced = std::min<uint64_t>(paths, kSurveyPaths);
    const WalkPdfs pdfs = integrator.walkStrategies().lightWalkPdfs();
    const bool splats = integrator.strategies().minT <= 1;
    Subpath path;
    for (uint64_t j = 0; j < traced; ++j) {
        SampleStream rng = lightPathStream(source, index, paths, j * paths / traced);
        lightSubpath(scene, rng, integrator.settings().walk, pdfs, path);
        out.vertices += double(path.size());
        out.bsdfs += double(path.bsdfs.size());
        for (size_t i = 0; i < path.size(); ++i) {
            const bool interiorDelta = i >= 1 && path[i].delta;
            out.mergeable += i >= 1 && !interiorDelta;
            out.splats += splats && !interiorDelta && !path[i].atInfinity;
        }
    }
    for (double* v : {&out.vertices, &out.bsdfs, &out.mergeable, &out.splats}) *v /= double(traced);
    return out;
}

uint64_t LightPhase::bytes(double paths, const LightPathSurvey& survey, bool merges) {
    uint64_t n = LightStore::bytesFor(paths, paths * survey.vertices, paths * survey.bsdfs);
    if (merges) {
        const auto entries = static_cast<size_t>(std::ceil(paths * survey.mergeable));
        n += entries * sizeof(LightVertexSearch::Entry) + LightVertexSearch::bytesFor(entries);
    }
    return n;
}

Pass LightPhase::run(const Scene& scene, const PixelSampleIntegrator& integrator, uint64_t index,
                     const StreamSource& source) {
    Pass pass;
    pass.index = index;
    if (!firstRadius_) firstRadius_ = integrator.firstMergeRadius(scene);
    const PassConstants constants = passConstants(integrator.lightPaths(scene), integrator.mergeRadius(*firstRadius_, index));
    pass.mis = integrator.misContext(constants);
    search_.reset();
    if (!integrator.hasLightPhase()) return pass;

    const uint64_t paths = static_cast<uint64_t>(constants.lightPaths);
    const WalkPdfs pdfs = integrator.walkStrategies().lightWalkPdfs();
    const WalkSettings& walk = integrator.settings().walk;
    store_.reset(paths);
    const bool merges = integrator.strategies().merges();
    mergeable_.resize(merges ? store_.chunks() : 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, store_.chunks(), 1), [&](const tbb::blocked_range<size_t>& r) {
        thread_local Subpath path;
        enrolThread();
        const PhaseScope scope(Phase::LightPaths);
        for (size_t c = r.begin(); c < r.end(); ++c) {
            LightStore::Chunk& chunk = store_.chunk(c);
            const uint64_t first = c * LightStore::kPathsPerChunk;
            for (uint64_t i = first; i < std::min(paths, first + LightStore::kPathsPerChunk); ++i) {
                SampleStream rng = lightPathStream(source, index, paths, i);
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
