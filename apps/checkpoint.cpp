#include "checkpoint.h"

#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <utility>

#include "geometry/embree_isa.h"
#include "core/error.h"
#include "core/warnings.h"
#include "processes.h"

namespace tripath::app {

std::string checkpointPath(const std::string& out) { return out + ".checkpoint"; }

Metadata checkpointSettings(const RenderOptions& o, const Scene& scene, const Integrator& integrator,
                            const FilmLayers& layers) {
    Metadata m = convergenceSettings(o, scene, integrator.name());
    const Metadata more{{"tripath:width", std::to_string(o.width)},
                        {"tripath:height", std::to_string(o.height)},
                        {"tripath:seed", std::to_string(o.seed)},
                        {"tripath:streams", streamsName(o.domain)},
                        {"tripath:sampler", o.sampler},
                        {"tripath:embree", embreeDescription()},
                        {"tripath:depth-images", std::to_string(layers.depthImages)},
                        {"tripath:strategy-images", std::to_string(layers.strategyLength)}};
    m.insert(m.end(), more.begin(), more.end());
    const Metadata light = lightPhaseMetadata(o, scene, integrator);
    m.insert(m.end(), light.begin(), light.end());
    return m;
}

RenderResult renderResumable(const Scene& scene, const Integrator& integrator, RenderSettings rs,
                             const RenderOptions& o, const Resumable& how) {
    const std::string path = checkpointPath(how.out);
    FilmLayers layers = rs.layers;
    layers.strategies = integrator.strategies();
    // Rank 0 reads the checkpoint (the others may not see its folder) and tells them its counts.
    std::optional<RenderResult> old;
    together([&] {
        if (isRankZero()) old = readCheckpoint(path, how.settings, o.width, o.height, layers);
    });
    std::array<uint64_t, 5> counts{old ? 1u : 0u, old ? uint64_t(old->passes) : 0, old ? old->nextPass : 0,
                                   old ? uint64_t(old->seconds * 1e6) : 0, old ? old->metropolis.run : 0};
    team().max(counts);
    if (counts[0] && !old) {
        old = RenderResult{Film(o.width, o.height, layers), int(counts[1]), counts[2], counts[3] / 1e6};
        old->metropolis.run = counts[4];  // mlt's chain states travel from rank 0 inside the render
    }
    bool finished = false;  // the checkpoint already holds the whole budget
    if (old) {
        std::cerr << fmt::format("continuing from {}: {} spp, {:.1f} s\n", path, old->passes, old->seconds);
        if (how.budgetIsTotal) {
            finished = (rs.spp > 0 && old->passes >= rs.spp) || (rs.seconds > 0 && old->seconds >= rs.seconds);
            if (rs.spp > 0) rs.spp -= old->passes;
            if (rs.seconds > 0) rs.seconds -= old->seconds;
        }
        rs.resume = &*old;
    }
    const bool checkpointing = o.checkpointSeconds > 0;
    bool checkpointFailed = false;
    if (checkpointing) {
        rs.checkpointSeconds = o.checkpointSeconds;
        // A checkpoint that cannot be written (a full disk) costs the safety it gives, not the
        // render: said once, and the render goes on, trying again at the next checkpoint.
        rs.onCheckpoint = [&](const RenderResult& sofar) {
            try {
                how.writeImage(sofar);
                writeCheckpoint(path, how.settings, sofar);
            } catch (const InputError& e) {
                if (!std::exchange(checkpointFailed, true))
                    printWarning(std::string(e.what()) + "; rendering on without this checkpoint");
            }
        };
    }
    RenderResult r = finished ? std::move(*old) : render(scene, integrator, rs);
    // Stopped before any pass (in mlt's bootstrap): nothing new to keep, and the checkpoint it
    // would have continued, if any, stays as it was.
    if (r.interruptedBeforeAnyPass) return r;
    if (isRankZero()) {
        const bool interrupted = rs.stop && rs.stop->load();
        std::error_code ignored;
        if ((checkpointing && interrupted) || (how.keepState && (checkpointing || old)))
            writeCheckpoint(path, how.settings, r);
        else if (old || checkpointing)
            std::filesystem::remove(path, ignored);
    }
    return r;
}

}  // namespace tripath::app
