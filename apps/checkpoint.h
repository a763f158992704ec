// Checkpoints on the command line: a render that continues from <out>.checkpoint when that exists,
// and writes one every --checkpoint seconds and on interruption. The file and what it holds:
// requests/checkpoint_file.h.
#pragma once
#include <string>

#include "integrators/render.h"
#include "render_options.h"
#include "requests/checkpoint_file.h"

namespace tripath::app {

std::string checkpointPath(const std::string& out);

// What must match for a checkpoint to be continued: the scene's files (scene_identity.h), integrator, size, depths, MIS,
// seed, streams, Embree's version and ISA, the film's layers and the light phase's schedule.
Metadata checkpointSettings(const RenderOptions& o, const Scene& scene, const Integrator& integrator,
                            const FilmLayers& layers);

// A render that continues from <out>.checkpoint when that exists (on any rank count), writes one
// every --checkpoint seconds (with the image so far, through `writeImage`; a write that fails is
// warned about once and the render goes on), and on interruption.
struct Resumable {
    std::string out;
    Metadata settings;          // checkpointSettings(...)
    bool budgetIsTotal = true;  // render: --spp/--time include the resumed part; reference: they add to it
    bool keepState = false;     // keep <out>.checkpoint when the render completes (reference: to add more later)
    std::function<void(const RenderResult&)> writeImage;  // rank 0: write the image of a render so far
};
RenderResult renderResumable(const Scene& scene, const Integrator& integrator, RenderSettings rs,
                             const RenderOptions& o, const Resumable& how);

}  // namespace tripath::app
