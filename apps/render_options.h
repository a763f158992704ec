// The flags shared by every command that renders: scene, integrator, budget, sizes, seed; the
// scene flags are also those of `export`.
#pragma once
#include <CLI/CLI.hpp>
#include <cstdint>
#include <memory>
#include <string>

#include "geometry/gltf_loader.h"
#include "geometry/scene.h"
#include "image/image.h"
#include "integrators/integrator.h"
#include "integrators/render.h"

namespace tripath::app {

struct RenderOptions {
    std::string scene;
    GltfOptions gltf;
    std::string integrator = "bdpt";
    int spp = 0;            // 0 unless --spp was given
    double seconds = 0;     // 0 unless --time was given
    bool sppGiven = false, timeGiven = false, radiusGiven = false, radiusFactorGiven = false;
    int width = 512, height = 512;
    int maxDepth = 16;
    int rrDepth = 3;
    std::string mis = "power";
    MergeSettings merge;     // --radius, --radius-factor, --radius-pixels, --alpha (vcm, bpm, ppm)
    uint64_t seed = 1;
    int threads = 0;
    double checkpointSeconds = 0;  // --checkpoint: interval; 0 writes none (checkpoint.h)
    bool stats = false;      // --stats: time the phases and print the counts and shares at the end
    // Not a flag: the random streams the samples draw from. Renders use CameraSample; references
    // use Reference, so that a reference and a render with the same --seed are independent.
    // Recorded in the EXR as tripath:streams ("render" or "reference").
    StreamDomain domain = StreamDomain::CameraSample;
};

// "render" or "reference", as tripath:streams records a domain.
const char* streamsName(StreamDomain d);

// Registers --scene and --allow-external-files, for every command that loads a scene.
void addSceneOptions(CLI::App& cmd, std::string& scene, GltfOptions& gltf);
// Registers the flags on a subcommand (the scene flags included), with help text that states defaults and meanings.
void addRenderOptions(CLI::App& cmd, RenderOptions& o, bool withIntegrator = true);
// Throws InputError for values out of range, before any work is done.
void validateRenderOptions(const RenderOptions& o);

IntegratorSettings integratorSettings(const RenderOptions& o);
std::unique_ptr<Scene> loadScene(const RenderOptions& o);
// spp/time budget, seed and threads as the render loop takes them (defaults to 16 spp).
RenderSettings renderSettings(const RenderOptions& o);
// What decides the image a render converges to, as EXR metadata: tripath:scene, integrator,
// max-depth, rr-depth and mis. Every check that a file may be added to or measured against
// (references, checkpoints, the benchmark's reference cache) starts from these.
Metadata convergenceSettings(const RenderOptions& o, const std::string& integrator);
// The EXR metadata describing a finished render.
Metadata renderMetadata(const RenderOptions& o, const Scene& scene, const Integrator& integrator, const RenderResult& r);
// The part of it that describes the light phase: light paths per pass, and for the merging
// integrators the first pass's radius in world units and alpha (the radius schedule).
Metadata lightPhaseMetadata(const RenderOptions& o, const Scene& scene, const Integrator& integrator);

// Ctrl-C: the first one asks the render loop to stop at the next pass (the image so far is
// written); a second one exits at once.
const std::atomic<bool>* installInterruptHandler();

// A progress line on stderr when it is a terminal (percent, samples/s, time left), updated
// after each pass; nothing otherwise. Returns the callback for RenderSettings::progress.
std::function<void(int, double)> progressReporter(const RenderSettings& s, int width, int height, const std::string& label);
// The one-line summary printed when a render ends, and with --stats the report of stats_report.h.
void printSummary(const std::string& label, const RenderResult& r, const RenderOptions& o);

}  // namespace tripath::app
