// The flags shared by every command that renders: scene, integrator, budget, sizes, seed; the
// scene flags are also those of `export`.
#pragma once
#include <CLI/CLI.hpp>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "io/gltf_loader.h"
#include "geometry/scene.h"
#include "evaluation/compare.h"
#include "image/image.h"
#include "integrators/integrator.h"
#include "requests/interrupt.h"
#include "integrators/render.h"
#include "requests/render_request.h"

namespace tripath::app {

// The library's render request (requests/render_request.h), which every front end fills, and
// what only the command line has.
struct RenderOptions : RenderRequest {
    double checkpointSeconds = 0;  // --checkpoint: interval; 0 writes none (checkpoint.h)
    std::string embreeIsa;         // --embree-isa: an ISA of kEmbreeIsas to pin; empty: the default (embree_isa.h)
};

// A comma-separated flag value as its items, each without surrounding blanks; "" has none, and an
// empty item (",," or a trailing comma) is kept so that the command can refuse it.
std::vector<std::string> splitCommas(const std::string& text);

// Gives the option of an integrator parameter (requests/integrator_parameters.h, found by its
// flag) its help and the default it shows, from `defaults`. Returns the option.
CLI::Option* documented(CLI::Option* option, const RenderRequest& defaults);

// Refuses an integer flag's value outside `range` (render_request.h) with validate()'s one line,
// checked on the text before CLI11 converts it, so that a number too large for the flag's type
// gets the range too (CLI11 alone says only that it cannot convert it). Returns the option.
CLI::Option* inRange(CLI::Option* option, const IntRange& range);

// Registers --scene and --allow-external-files, for every command that loads a scene.
void addSceneOptions(CLI::App& cmd, std::string& scene, GltfOptions& gltf);
// Registers the flags on a subcommand (the scene flags included), with help text that states defaults and meanings.
void addRenderOptions(CLI::App& cmd, RenderOptions& o, bool withIntegrator = true);
// Throws InputError for values out of range, before any work is done: the request's checks
// (render_request.h), --checkpoint's and --embree-isa's. Then pins --embree-isa, if given, for
// every scene built from now on. Without --integrator (compare, benchmark: their integrators are
// a list), the values alone: the command checks what its integrators use.
void validateRenderOptions(const RenderOptions& o, bool withIntegrator = true);

// A progress line on stderr when it is a terminal (percent, samples/s, time left), updated
// after each pass; nothing otherwise. Returns the callback for RenderSettings::progress.
std::function<void(int, double)> progressReporter(const RenderSettings& s, int width, int height, const std::string& label);
// The one-line summary printed when a render ends ("interrupted after 5 of 16 passes, …" when a
// signal cut it short), and with --stats the report of stats_report.h.
void printSummary(const std::string& label, const RenderResult& r, const RenderRequest& o);
// What a comparison or benchmark tells the terminal (rank 0): its lines, each render's progress
// line and summary, as above.
evaluation::Narrator terminalNarrator();

}  // namespace tripath::app
